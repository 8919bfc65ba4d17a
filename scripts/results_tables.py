#!/usr/bin/env python3
"""Rewrites the README's results tables from a sweep's summary.csv, over seeds.

Usage: scripts/results_tables.py SWEEP_DIR [--ambisim build/ambisim] [--doc README.md]
                                 [--baseline shgraph+vp] [--check]

Each block of the doc between `<!-- results-table: SCENARIO bBUDGET [vSPEED] -->` and
`<!-- end results-table -->` becomes a table for that scenario, budget (faces per frame) and
camera speed scale (default 1): one row per planner in sweep order, each number the mean over
the sweep's seeds with its 95 % bootstrap interval from `ambisim compare` (one implementation
of the statistics), and on how many seeds the planner beats the baseline on viewed p95.
A block `<!-- results-headline: SCENARIO bBUDGET PLANNER -->` becomes one sentence: PLANNER
against the baseline on viewed and uniform p95 and pops, with intervals and wins.
Only deterministic results go in (no measured times: those are docs/PERFORMANCE.md's), so
the same sweep always gives the same doc. Text outside the blocks is kept, and so is a block
whose scenario the sweep does not hold (the dynamic scenarios' tables come from their own
sweep, scenarios/sweeps/dynamic.json). --check exits 1 (writing nothing) when the doc differs from
what the runs give. Standard library only.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile

METRICS = [
    ("viewed ΔE00 mean", "error.viewed.de2000.mean"),
    ("viewed ΔE00 p95", "error.viewed.de2000.p95"),
    ("viewed pops/min", "pops.viewed.per_min"),
    ("uniform ΔE00 p95", "error.uniform.de2000.p95"),
    ("uniform pops/min", "pops.uniform.per_min"),
    ("response median s", "response.median_s"),
    ("coverage", "coverage.mean"),
]
# Means over seeds of cost columns (no interval: they hardly vary, and they are costs).
COSTS = [("faces used", "faces.used", "{:.0f}"), ("bake captures", "bake.captures", "{:.0f}"),
         ("max bytes", "memory.max_bytes", "{:.0f}")]
BLOCK = re.compile(r"(<!-- results-(table|headline): ([^>]*?) -->\n)(.*?)(<!-- end results-\2 -->)",
                   re.S)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def fnum(x):
    try:
        v = float(x)
    except (TypeError, ValueError):
        return math.nan
    return v


def short(x):
    if x is None or not math.isfinite(x):
        return "–"
    a = abs(x)
    if a >= 100:
        return f"{x:.0f}"
    if a >= 10:
        return f"{x:.1f}"
    return f"{x:.2f}"


def cell(r):
    if r is None or r["mean"] is None:
        return "–"
    lo, hi = r["ci"]
    if r["seeds"] <= 1 or lo is None:
        return short(r["mean"])
    return f"{short(r['mean'])} [{short(lo)}, {short(hi)}]"


def same(a, b):
    return abs(float(a) - float(b)) < 1e-9


def parse_key(text):
    parts = text.split()
    key = {"scenario": parts[0], "budget": None, "speed": 1.0, "planner": None}
    for p in parts[1:]:
        if re.fullmatch(r"b[0-9.]+", p):
            key["budget"] = float(p[1:])
        elif re.fullmatch(r"v[0-9.]+", p):
            key["speed"] = float(p[1:])
        else:
            key["planner"] = p
    if key["budget"] is None:
        sys.exit(f"results_tables: block '{text}' names no budget (bB)")
    return key


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--ambisim", default=os.path.join(os.path.dirname(__file__), "..", "build",
                                                      "ambisim"))
    ap.add_argument("--doc", default=os.path.join(os.path.dirname(__file__), "..", "README.md"))
    ap.add_argument("--baseline", default="shgraph+vp")
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()

    summary = read_csv(os.path.join(a.sweep_dir, "summary.csv"))
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "compare.json")
        cmd = [a.ambisim, "compare", a.sweep_dir, "--baseline", a.baseline, "--json", out]
        for _, m in METRICS:
            cmd += ["--metric", m]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        rows = json.load(open(out))["rows"]
    stats = {}
    for r in rows:
        stats[(r["scenario"], r["faces_per_frame"], r["speed_scale"], r["planner"], r["metric"])] = r

    def runs_of(key):
        return [r for r in summary if r["scenario"] == key["scenario"]
                and same(r["faces_per_frame"], key["budget"]) and same(r["speed_scale"], key["speed"])]

    def stat(key, planner, metric):
        for (sc, b, v, p, m), r in stats.items():
            if sc == key["scenario"] and same(b, key["budget"]) and same(v, key["speed"]) \
                    and p == planner and m == metric:
                return r
        return None

    def table(key):
        runs = runs_of(key)
        if not runs:
            sys.exit(f"results_tables: no runs for {key['scenario']} at budget {key['budget']:g}, "
                     f"speed x{key['speed']:g} in {a.sweep_dir}")
        labels = list(dict.fromkeys(r["label"] for r in runs))
        seeds = len({r["seed"] for r in runs})
        fps = fnum(runs[0]["frames"]) / fnum(runs[0]["duration_s"])
        lines = [f"**{key['scenario']}**, budget {key['budget']:g} face/frame = "
                 f"{key['budget'] * fps:g} faces/s, camera speed x{key['speed']:g}, "
                 f"{fnum(runs[0]['duration_s']):g} s, {seeds} seed{'s' if seeds != 1 else ''} "
                 f"(mean [95 % CI]):", ""]
        head = ["planner"] + [m[0] for m in METRICS] + \
               [f"beats {a.baseline} (viewed p95)"] + [c[0] for c in COSTS]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|---|" + "---:|" * (len(head) - 1))
        for label in labels:
            mine = [r for r in runs if r["label"] == label]
            cells = [label] + [cell(stat(key, label, m)) for _, m in METRICS]
            p95 = stat(key, label, "error.viewed.de2000.p95")
            cells.append("–" if label == a.baseline or p95 is None
                         else f"{p95['beats']}/{p95['paired']}")
            for _, col, f in COSTS:
                vals = [fnum(r[col]) for r in mine if math.isfinite(fnum(r[col]))]
                cells.append(f.format(sum(vals) / len(vals)) if vals else "–")
            lines.append("| " + " | ".join(cells) + " |")
        return "\n".join(lines) + "\n"

    def headline(key):
        p = key["planner"]
        if p is None:
            sys.exit("results_tables: a headline block names no planner")
        parts = []
        for name, m in METRICS[1:5]:
            mine, base = stat(key, p, m), stat(key, a.baseline, m)
            if mine is None or base is None:
                sys.exit(f"results_tables: no {m} for {p} or {a.baseline} in {key['scenario']}")
            parts.append(f"{name} {cell(mine)} against {cell(base)} "
                         f"(beats it on {mine['beats']} of {mine['paired']} seeds)")
        return (f"On {key['scenario']} at {key['budget']:g} face/frame, `{p}` against "
                f"`{a.baseline}`: " + "; ".join(parts) + ".\n")

    doc = open(a.doc).read()

    scenarios = {r["scenario"] for r in summary}

    def replace(m):
        key = parse_key(m.group(3))
        if key["scenario"] not in scenarios:
            return m.group(0)
        body = table(key) if m.group(2) == "table" else headline(key)
        return m.group(1) + body + m.group(5)

    new = BLOCK.sub(replace, doc)
    if a.check:
        if new != doc:
            print(f"results_tables: {a.doc} differs from the runs in {a.sweep_dir}")
            sys.exit(1)
        return
    if new != doc:
        open(a.doc, "w").write(new)


if __name__ == "__main__":
    main()
