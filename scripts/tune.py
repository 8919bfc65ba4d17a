#!/usr/bin/env python3
"""The equal tuning: every planner's configurations on the training scenarios, and its best as
its `tuned` preset.

Usage: scripts/tune.py OUT_DIR [--ambisim build/ambisim] [--jobs N] [--grids FILE]
                       [--presets FILE] [--doc README.md] [--check]

Reads scenarios/tuning/grids.json (the training scenarios, the run length, seeds and budgets,
and per planner the same number of configurations, the first its defaults), writes
OUT_DIR/tuning.sweep.json with one planner label per configuration (`NAME_cK`, plus the
planner's `fixed` parameters, which are not part of its preset), runs it with
`ambisim sweep` (resuming what OUT_DIR/runs already holds), and picks per planner the
configuration with the lowest score:

    score = geometric mean over the training runs of sqrt(p95 / p95_default * (pops + 1) /
            (pops_default + 1))

where p95 is the viewed dE2000 p95 and pops the viewed pops per minute, each against the
planner's own defaults on the same run (so scenarios of different difficulty weigh alike and
neither accuracy nor stability alone decides). Ties keep the earlier configuration (the
defaults first). Writes policies/registry/presets.json (rebuild to use it) and the README block
between `<!-- tuned-presets -->` and `<!-- end tuned-presets -->`. --check writes nothing and
exits 1 when either differs from what the runs give. Standard library only.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def load_grids(path):
    with open(path) as f:
        g = json.load(f)
    n = g["configurations"]
    for name, configs in g["planners"].items():
        if len(configs) != n:
            sys.exit(f"tune: {path}: /planners/{name}: {len(configs)} configurations, want {n}")
        if configs[0] != {}:
            sys.exit(f"tune: {path}: /planners/{name}/0: the first configuration must be the "
                     "defaults ({})")
    return g


def sweep_spec(g, grids_path):
    base = os.path.dirname(os.path.abspath(grids_path))
    planners = []
    fixed = g.get("fixed", {})
    for name, configs in g["planners"].items():
        for k, params in enumerate(configs):
            planners.append({"name": name, "label": f"{name}_c{k}",
                             "params": {**params, **fixed.get(name, {})}})
    return {
        "name": "tuning",
        "scenarios": [os.path.normpath(os.path.join(base, s)) for s in g["training"]],
        "planners": planners,
        "budgets": g["budgets"],
        "seeds": g["seeds"],
        "duration_s": g["duration_s"],
    }


def fnum(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def choose(g, rows):
    """Per planner: (best index, its score, every config's score)."""
    by = {}
    for r in rows:
        by[(r["label"], r["scenario"], r["faces_per_frame"], r["seed"])] = r
    out = {}
    for name, configs in g["planners"].items():
        scores = []
        for k in range(len(configs)):
            logs = []
            for (label, scen, b, seed), r in by.items():
                if label != f"{name}_c{k}":
                    continue
                d = by.get((f"{name}_c0", scen, b, seed))
                p95, p95d = fnum(r["error.viewed.de2000.p95"]), fnum(d["error.viewed.de2000.p95"])
                pops, popsd = fnum(r["pops.viewed.per_min"]), fnum(d["pops.viewed.per_min"])
                if not all(math.isfinite(v) for v in (p95, p95d, pops, popsd)) or p95d <= 0:
                    continue
                logs.append(0.5 * (math.log(max(p95, 1e-9) / p95d) +
                                   math.log((pops + 1.0) / (popsd + 1.0))))
            scores.append(math.exp(sum(logs) / len(logs)) if logs else math.inf)
        best = min(range(len(scores)), key=lambda k: (scores[k], k))
        out[name] = (best, scores[best], scores)
    return out


def presets_json(g, chosen, catalogue):
    tuned = {}
    for name in catalogue:
        if name in chosen:
            k, score, _ = chosen[name]
            tuned[name] = {"params": g["planners"][name][k], "configuration": k,
                           "score": round(score, 4)}
        else:
            tuned[name] = {"params": {}}
    return {
        "_comment": "Written by scripts/tune.py from the equal tuning sweep (scenarios/tuning/"
                    "grids.json): per planner the configuration that scored best on the training "
                    "scenarios (score 1 = its defaults). Do not edit by hand; rerun the script.",
        "tuned": tuned,
    }


def doc_block(g, chosen):
    lines = [f"{g['configurations']} configurations per tuned planner (the first its defaults) "
             f"on {len(g['training'])} training scenarios "
             f"({', '.join(os.path.splitext(os.path.basename(s))[0] for s in g['training'])}; "
             f"{g['duration_s']} s, seeds {', '.join(map(str, g['seeds']))}, budget "
             f"{', '.join(map(str, g['budgets']))} face/frame). Score: geometric mean of "
             "sqrt(viewed p95 ratio x (pops/min + 1) ratio) against the planner's defaults; lower "
             "is better. Not tuned (their parameters only colour the time before the first "
             f"capture): {', '.join(g['untuned'])}.", "",
             "| planner | tuned preset | score | configuration scores (c0 = defaults) |",
             "|---|---|---|---|"]
    for name, (k, score, scores) in chosen.items():
        params = g["planners"][name][k]
        text = ", ".join(f"{a}={json.dumps(v)}" for a, v in params.items()) or "the defaults"
        lines.append(f"| {name} | {text} | {score:.3f} | " +
                     " ".join(f"c{i} {s:.3f}" for i, s in enumerate(scores)) + " |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--ambisim", default=os.path.join(ROOT, "build", "ambisim"))
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--grids", default=os.path.join(ROOT, "scenarios", "tuning", "grids.json"))
    ap.add_argument("--presets", default=os.path.join(ROOT, "policies", "registry", "presets.json"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "README.md"))
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()

    g = load_grids(a.grids)
    os.makedirs(a.out_dir, exist_ok=True)
    spec_path = os.path.join(a.out_dir, "tuning.sweep.json")
    with open(spec_path, "w") as f:
        json.dump(sweep_spec(g, a.grids), f, indent=1)
    runs = os.path.join(a.out_dir, "runs")
    cmd = [a.ambisim, "sweep", spec_path, "--out", runs, "-j", str(a.jobs)]
    if os.path.exists(os.path.join(runs, "summary.csv")) or os.path.isdir(runs):
        cmd.append("--resume")
    subprocess.run(cmd, check=True)
    chosen = choose(g, read_csv(os.path.join(runs, "summary.csv")))

    catalogue = [p["name"] for p in json.loads(
        subprocess.run([a.ambisim, "planners", "--json"], check=True, capture_output=True,
                       text=True).stdout)]
    missing = [n for n in catalogue if n not in g["planners"] and n not in g["untuned"]]
    if missing:
        sys.exit(f"tune: {a.grids}: no configurations for {', '.join(missing)}")
    presets = json.dumps(presets_json(g, chosen, catalogue), indent=2) + "\n"
    with open(a.doc) as f:
        doc = f.read()
    begin, end = "<!-- tuned-presets -->\n", "<!-- end tuned-presets -->"
    i, j = doc.find(begin), doc.find(end)
    if i < 0 or j < 0:
        sys.exit(f"tune: {a.doc}: no '{begin.strip()}' ... '{end}' block")
    new_doc = doc[:i + len(begin)] + doc_block(g, chosen) + doc[j:]
    with open(a.presets) as f:
        old_presets = f.read()
    if a.check:
        stale = [p for p, old, new in ((a.presets, old_presets, presets), (a.doc, doc, new_doc))
                 if old != new]
        if stale:
            print("tune: differs from the runs: " + ", ".join(stale), file=sys.stderr)
            sys.exit(1)
        return
    with open(a.presets, "w") as f:
        f.write(presets)
    with open(a.doc, "w") as f:
        f.write(new_doc)
    for name, (k, score, _) in chosen.items():
        print(f"{name}: c{k} (score {score:.3f})")


if __name__ == "__main__":
    main()
