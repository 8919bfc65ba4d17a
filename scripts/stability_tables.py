#!/usr/bin/env python3
"""Regenerate the measured tables of docs/STABILITY.md from the two stress sweeps.

Usage: scripts/stability_tables.py STRESS_DIR STRESS_BL_DIR [--doc docs/STABILITY.md] [--check]

STRESS_DIR is the output of `ambisim sweep scenarios/sweeps/stress.json`, STRESS_BL_DIR that
of `ambisim sweep scenarios/stress/sweeps/budget_lifetime.json`. Each sweep's summary.csv
(one row per run) gives the table columns (the uniform and the viewed error and pops side by
side; a NaN, a viewed value with no receiver in view, prints as "–"); each run's
runs/<run>/result.json "series" (and, for the leave_bounds scenario, views.json
"camera_path") gives the failure-mode column.

The doc holds generated blocks between HTML comment markers:

    <!-- stability-table: KEY -->
    ...generated, rewritten on every run...
    <!-- end stability-table -->

KEY is a scenario name of the stress sweep (`baseline`, `speed_100`, ...), `budget B` for the
budget/lifetime sweep at B faces per frame, or `checks` (run counts and the NaN/Inf check).
Everything outside the markers is kept as written; running twice gives the same file. A block
whose data is missing, an unknown key, or a sweep scenario or budget without a block is an
error: one line on stderr, exit 1, the doc untouched. --check writes nothing and exits 1 if
the doc is not what the runs give. Standard library only.
"""
import argparse
import csv
import json
import math
import os
import re
import sys

# --- Field names ---------------------------------------------------------------------------
# Every name read from summary.csv and result.json. Each entry lists the accepted names, the
# newest first; the first one that exists is used, so the script reads sweeps from before and
# after a rename (error.de2000.* -> error.uniform.de2000.*, pops.per_min ->
# pops.uniform.per_min). The viewed fields and viewed_receiver_minutes have no older names: a
# sweep from before them is refused with one line naming the missing field.
FIELDS = {
    # summary.csv: identity of a run
    "run": ["run"],
    "scenario": ["scenario"],
    "label": ["label"],
    "planner": ["planner"],
    "faces_per_frame": ["faces_per_frame"],
    "frames": ["frames"],
    "duration_s": ["duration_s"],
    "viewed_minutes": ["viewed_receiver_minutes"],  # 0: no receiver ever in view
    # summary.csv: the table columns
    "de_mean": ["error.uniform.de2000.mean", "error.de2000.mean"],
    "de_p95": ["error.uniform.de2000.p95", "error.de2000.p95"],
    "de_viewed_p95": ["error.viewed.de2000.p95"],
    "pops_per_min": ["pops.uniform.per_min", "pops.per_min"],
    "pops_viewed_per_min": ["pops.viewed.per_min"],
    "coverage": ["coverage.mean"],
    "faces_granted": ["faces.granted"],
    "max_live": ["probes.max_live"],
    "max_bytes": ["memory.max_bytes"],
    # result.json "series": one value per frame (null where undefined)
    "s_time": ["time"],
    "s_dt": ["dt"],
    "s_receivers": ["receivers"],
    "s_de_mean": ["de2000_mean"],
    "s_de_max": ["de2000_max"],
    "s_pops": ["pops"],
    "s_staleness": ["staleness_mean"],  # null: the receiver lookup fell back
    "s_live": ["live_probes"],
    "s_bytes": ["bytes"],
    "s_faces_granted": ["faces_granted"],
    # views.json
    "v_camera": ["camera_path"],
}

# summary.csv fields that are NaN by definition when a run has no data for them: staleness is
# defined over lookups that did not fall back; response times over true-change events. Every
# other numeric field must be finite, except the viewed ones (VIEWED), which are defined over
# receivers the camera sees and must be finite unless viewed_receiver_minutes is 0.
MAY_BE_NAN = ("staleness.", "response.")
VIEWED = ("error.viewed.", "pops.viewed.")
# Series columns that are null by definition on some frames: staleness_mean on a fallback,
# change_max on a receiver's first frame, de2000_viewed_mean when nothing is seen. Every other
# series value must be a finite number.
SERIES_MAY_BE_NULL = ("staleness_mean", "change_max", "de2000_viewed_mean")

# Table columns: header, field, format. "uniform" weighs every receiver and normal alike,
# "viewed" each receiver by its solid angle on screen (the error also each normal by its
# visible share; scenarios/README.md, "metrics"). A NaN cell (a viewed metric with nothing in
# view) prints as NAN_CELL.
COLUMNS = [
    ("uniform ΔE00 mean", "de_mean", "{:.2f}"),
    ("uniform ΔE00 p95", "de_p95", "{:.2f}"),
    ("viewed ΔE00 p95", "de_viewed_p95", "{:.2f}"),
    ("uniform pops/min", "pops_per_min", "{:.1f}"),
    ("viewed pops/min", "pops_viewed_per_min", "{:.1f}"),
    ("coverage", "coverage", "{:.3f}"),
    ("faces granted", "faces_granted", "{:.0f}"),
    ("max live", "max_live", "{:.0f}"),
    ("max bytes", "max_bytes", "{:.0f}"),
]
NAN_CELL = "–"
FAILURE_HEADER = "failure mode (measured from the series)"

# --- When a fact is listed in the failure-mode column ---------------------------------------
# Fallback: share of time (dt-weighted, over frames with a live receiver) whose receiver
# lookup the planner flagged as a fallback (LookupResult::fell_back: no probe served it, a
# default or coarse answer; the metrics then leave staleness_mean null). "the whole run" when
# every frame fell back; otherwise listed from this share on (the first probe of a 60 fps run
# takes 0.1 s, under 1 % of 15 s).
FALLBACK_MIN_SHARE = 0.10
# First probe data: time of the first frame whose lookup was served by a probe; listed from
# this time on (a probe of 6 faces at 1 face/frame and 60 fps is delivered after 0.1 s).
FIRST_DATA_MIN_S = 0.5
# Idle budget: "asks for only X of Y faces", X = faces granted, Y = the budget offered
# (frames x faces per frame); listed when the planner uses less than this share of it. Not
# listed for planners that do not plan captures within the budget: the oracle (the reference
# at every receiver, outside the budget) and the two that take their one capture at load time
# (summary bake.captures), outside the budget, so that their faces granted are 0.
IDLE_BUDGET_MAX_SHARE = 0.5
IDLE_BUDGET_EXEMPT = {"oracle", "constant", "hemisphere"}
# No live probe: share of time (dt-weighted) with live_probes 0; listed from this share on.
NO_LIVE_MIN_SHARE = 0.05

# Scenario-specific windows of the series, by scenario name (stress sweep), each the mean of
# the per-frame receiver dE00 (series de2000_mean) over the frames it names:
#   worst_1s  the worst whole-second window [k, k+1) s
#   cuts      the 0.25 s after each camera cut, and 0.5-1 s after it (the scenario's cuts)
#   segments  each frame-rate segment of the scenario's `frames.segments`
#   bounds    camera inside vs outside the world's extent (views.json camera path), and the
#             faces granted while outside
#   halves    peak bytes of the first and the second half of the run (not a dE mean)
#   same_as   compares every summary.csv field, the per-frame dE (mean and max) and the
#             per-frame counts (live probes, bytes, faces granted, pops) with the named
#             scenario's run of the same label
SCENARIO_WINDOWS = {
    "speed_100": ["worst_1s"],
    "speed_300": ["worst_1s"],
    "cuts_1s": ["cuts"],
    "fps_5": ["worst_1s"],
    "fps_drop": ["segments"],
    "origin_shift": [("same_as", "baseline")],
    "below_ground": ["worst_1s"],
    "in_canopy": ["worst_1s"],
    "leave_bounds": ["bounds"],
    "canyon": ["worst_1s"],
    "long_flight": ["halves"],
}
SAME_AS_NAMED_FIELDS = 3  # same_as names the differing summary.csv fields up to this many
CUT_FIRST_S = 0.25  # "in the 0.25 s after a cut"
CUT_LATE_S = (0.5, 1.0)  # "0.5-1 s after"
EPS = 1e-9  # frame times are sums of dt: compare against window edges with this slack

# Markers stand alone on their lines (a marker quoted inside a line of prose is not one).
START = re.compile(r"^<!-- stability-table: *(.*?) *-->$", re.M)
MARKER = re.compile(r"^(<!-- stability-table: *(.*?) *-->\n)(.*?)(^<!-- end stability-table -->$)",
                    re.S | re.M)


class DataError(Exception):
    pass


def pick(mapping, key, where):
    """The value of the first accepted name of FIELDS[key] that `mapping` has."""
    for name in FIELDS[key]:
        if name in mapping:
            return mapping[name]
    raise DataError(f"{where}: none of {', '.join(FIELDS[key])}")


def num(v):
    return float(v) if v not in (None, "") else math.nan


def read_summary(sweep_dir):
    path = os.path.join(sweep_dir, "summary.csv")
    if not os.path.isfile(path):
        raise DataError(f"no summary.csv in the sweep directory {sweep_dir}")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not rows:
        raise DataError(f"{path}: no runs")
    return rows


class Run:
    """One summary.csv row with its result.json (and views.json, when asked for)."""

    def __init__(self, sweep_dir, row):
        self.row = row
        self.id = pick(row, "run", "summary.csv")
        self.dir = os.path.join(sweep_dir, "runs", self.id)
        self._result = None
        self._camera = None

    def field(self, key):
        return pick(self.row, key, f"summary.csv row {self.id}")

    def value(self, key):
        return num(self.field(key))

    @property
    def result(self):
        if self._result is None:
            path = os.path.join(self.dir, "result.json")
            if not os.path.isfile(path):
                raise DataError(f"run {self.id}: no result.json")
            with open(path) as f:
                self._result = json.load(f)
            if "series" not in self._result:
                raise DataError(f"run {self.id}: result.json has no series")
        return self._result

    def series(self, key):
        return pick(self.result["series"], key, f"run {self.id}: series")

    def document(self):
        return self.result.get("scenario", {}).get("document", {})

    def camera_path(self):
        if self._camera is None:
            path = os.path.join(self.dir, "views.json")
            if not os.path.isfile(path):
                raise DataError(f"run {self.id}: no views.json (camera path)")
            with open(path) as f:
                self._camera = pick(json.load(f), "v_camera", f"run {self.id}: views.json")
        return self._camera


# --- Formatting ------------------------------------------------------------------------------
def share_text(share):
    """A share of time in whole percent; never rounds a partial share up to 100 % or down to 0."""
    pct = 100.0 * share
    if pct >= 99.5 and share < 1.0:
        return ">99%"
    if pct < 0.5 and share > 0.0:
        return "<1%"
    return f"{pct:.0f}%"


def de(x):
    return "n/a" if math.isnan(x) else f"{x:.1f}"


def secs(x):
    return f"{x:.1f} s"


def mean(values):
    v = [x for x in values if x is not None]
    return sum(v) / len(v) if v else math.nan


# --- Failure-mode facts ----------------------------------------------------------------------
def general_facts(run):
    facts = []
    t = run.series("s_time")
    dt = run.series("s_dt")
    recv = run.series("s_receivers")
    stale = run.series("s_staleness")
    live = run.series("s_live")
    n = len(t)
    if not n:
        raise DataError(f"run {run.id}: empty series")

    # Fallback and first probe data (frames with a live receiver only).
    with_recv = [i for i in range(n) if recv[i]]
    total = sum(dt[i] for i in with_recv)
    fell_back = [i for i in with_recv if stale[i] is None]
    share = sum(dt[i] for i in fell_back) / total if total > 0 else 0.0
    if with_recv and len(fell_back) == len(with_recv):
        facts.append("receiver lookups fall back the whole run")
    else:
        if share >= FALLBACK_MIN_SHARE:
            facts.append(f"fallback lookups {share_text(share)} of the time")
        first = next((t[i] for i in with_recv if stale[i] is not None), None)
        if first is not None and first >= FIRST_DATA_MIN_S - EPS:
            facts.append(f"first probe data at {secs(first)}")

    # Idle budget.
    budget = run.value("frames") * run.value("faces_per_frame")
    granted = run.value("faces_granted")
    if (run.field("planner") not in IDLE_BUDGET_EXEMPT and budget > 0
            and granted < IDLE_BUDGET_MAX_SHARE * budget):
        facts.append(f"asks for only {granted:.0f} of {budget:.0f} faces")

    # No live probe.
    all_t = sum(dt)
    no_live = sum(dt[i] for i in range(n) if not live[i])
    if no_live >= all_t - EPS:
        facts.append("no live probe the whole run")
    elif all_t > 0 and no_live / all_t >= NO_LIVE_MIN_SHARE:
        facts.append(f"no live probe {share_text(no_live / all_t)} of the time")
    return facts


def cut_times(doc, duration):
    cam = doc.get("camera", {})
    cuts = [c["time_s"] for c in cam.get("cuts", []) if "time_s" in c]
    pc = cam.get("periodic_cut")
    if pc:
        every = pc["every_s"]
        k, first = 0, pc.get("first_s", every)
        while first + k * every < duration - EPS:
            cuts.append(first + k * every)
            k += 1
    return sorted(cuts)


def world_bounds(doc):
    w = doc.get("world", {})
    ox, oy = w.get("origin", [0.0, 0.0])
    sx, sy = w.get("size_m", [4096.0, 4096.0])  # scenarios/README.md defaults
    return ox, oy, ox + sx, oy + sy


def outside_flags(run):
    x0, y0, x1, y1 = world_bounds(run.document())
    path = run.camera_path()
    if len(path) != len(run.series("s_time")):
        raise DataError(f"run {run.id}: camera path and series differ in length")
    return [not (x0 <= p[0] <= x1 and y0 <= p[1] <= y1) for p in path]


def window_facts(run, windows, runs_by_scenario):
    facts = []
    t = run.series("s_time")
    d = run.series("s_de_mean")
    n = len(t)
    duration = round(run.value("duration_s"), 6)
    for w in windows:
        if w == "worst_1s":
            best = None
            for k in range(int(math.floor(duration + EPS))):
                m = mean([d[i] for i in range(n) if k - EPS <= t[i] < k + 1 - EPS])
                if not math.isnan(m) and (best is None or m > best[0]):
                    best = (m, k)
            if best:
                facts.append(f"worst 1-s dE {de(best[0])} at {best[1]}-{best[1] + 1} s")
        elif w == "cuts":
            cuts = cut_times(run.document(), duration)
            if not cuts:
                raise DataError(f"run {run.id}: the scenario has no cuts")
            early, late = [], []
            for i in range(n):
                before = [c for c in cuts if c <= t[i] + EPS]
                if not before:
                    continue
                since = t[i] - before[-1]
                if since < CUT_FIRST_S - EPS:
                    early.append(d[i])
                elif CUT_LATE_S[0] - EPS <= since < CUT_LATE_S[1] - EPS:
                    late.append(d[i])
            facts.append(f"dE {de(mean(early))} in the {CUT_FIRST_S:g} s after a cut, "
                         f"{de(mean(late))} {CUT_LATE_S[0]:g}-{CUT_LATE_S[1]:g} s after")
        elif w == "segments":
            segs = run.document().get("frames", {}).get("segments")
            if not segs:
                raise DataError(f"run {run.id}: the scenario has no frame-rate segments")
            parts = []
            for j, s in enumerate(segs):
                end = segs[j + 1]["from_s"] if j + 1 < len(segs) else math.inf
                m = mean([d[i] for i in range(n) if s["from_s"] - EPS <= t[i] < end - EPS])
                parts.append(f"{de(m)} at {s['fps']:g} fps")
            facts.append("dE " + ", ".join(parts))
        elif w == "bounds":
            out = outside_flags(run)
            fg = run.series("s_faces_granted")
            inside = mean([d[i] for i in range(n) if not out[i]])
            outside = mean([d[i] for i in range(n) if out[i]])
            faces_out = sum(fg[i] for i in range(n) if out[i])
            facts.append(f"dE {de(inside)} inside, {de(outside)} outside the world "
                         f"({faces_out:.0f} faces granted outside)")
        elif w == "halves":
            b = run.series("s_bytes")
            half = duration / 2
            first = max(b[i] for i in range(n) if t[i] < half - EPS)
            second = max(b[i] for i in range(n) if t[i] >= half - EPS)
            facts.append(f"peak bytes {first:.0f} / {second:.0f} (1st / 2nd half)")
        elif isinstance(w, tuple) and w[0] == "same_as":
            facts.append(same_as_fact(run, w[1], runs_by_scenario))
        else:
            raise DataError(f"unknown window {w!r}")
    return facts


def same_as_fact(run, other_scenario, runs_by_scenario):
    """Compare with the other scenario's run of the same label: every summary.csv field, the
    largest per-frame dE difference, and whether the per-frame counts are identical."""
    label = run.field("label")
    other = next((r for r in runs_by_scenario.get(other_scenario, [])
                  if r.field("label") == label), None)
    if other is None:
        raise DataError(f"no {other_scenario} run of {label} to compare {run.id} with")
    skip = set(FIELDS["run"] + FIELDS["scenario"]) | {"scenario_hash"}
    diff = [k for k in run.row if k not in skip and run.row[k] != other.row.get(k)]
    if not diff:
        parts = [f"summary.csv row identical to {other_scenario}'s"]
    elif len(diff) <= SAME_AS_NAMED_FIELDS:
        parts = [f"summary.csv row identical to {other_scenario}'s but for "
                 + ", ".join(f"{k} ({run.row[k]} vs {other.row.get(k)})" for k in diff)]
    else:
        parts = [f"summary differs from {other_scenario}'s in {len(diff)} fields"]

    worst = 0.0
    for key in ("s_de_mean", "s_de_max"):
        a, b = run.series(key), other.series(key)
        if len(a) != len(b) or any((x is None) != (y is None) for x, y in zip(a, b)):
            worst = math.inf
            break
        worst = max([worst] + [abs(x - y) for x, y in zip(a, b) if x is not None])
    counts_same = all(run.series(k) == other.series(k)
                      for k in ("s_live", "s_bytes", "s_faces_granted", "s_pops"))
    counts = "probe counts, bytes, faces and pops"
    if worst == 0.0 and counts_same:
        parts.append(f"per-frame dE, {counts} identical")
    else:
        parts.append("per-frame dE identical" if worst == 0.0 else
                     f"per-frame dE within {worst:.1g}")
        parts.append(f"{counts} {'identical' if counts_same else 'differ'}")
    return "; ".join(parts)


def failure_mode(run, scenario, runs_by_scenario):
    facts = general_facts(run)
    facts += window_facts(run, SCENARIO_WINDOWS.get(scenario, []), runs_by_scenario)
    return "; ".join(facts)


# --- Blocks ----------------------------------------------------------------------------------
def table(runs, scenario, runs_by_scenario):
    head = ["planner"] + [c[0] for c in COLUMNS] + [FAILURE_HEADER]
    lines = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * len(COLUMNS) + "---|"]
    for r in runs:
        cells = [r.field("label")]
        for _, key, fmt in COLUMNS:
            x = r.value(key)
            cells.append(NAN_CELL if math.isnan(x) else fmt.format(x))
        cells.append(failure_mode(r, scenario, runs_by_scenario))
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def caption(runs, scenario):
    """A generated line above the table, for windows that need one."""
    if "bounds" in SCENARIO_WINDOWS.get(scenario, []):
        r = runs[0]
        out = outside_flags(r)
        t = r.series("s_time")
        if True in out:
            first = t[out.index(True)]
            return [f"The camera is outside the world's extent from {first:.2f} s on "
                    f"({sum(out)} of {len(out)} frames).", ""]
        return ["The camera never leaves the world's extent.", ""]
    return []


def checks_block(sweeps):
    total = sum(len(runs) for runs in sweeps.values())
    bad = []
    no_stale = 0
    no_view = 0
    for runs in sweeps.values():
        for r in runs:
            unseen = r.value("viewed_minutes") == 0
            no_view += unseen
            for k, v in r.row.items():
                if k.startswith(MAY_BE_NAN) or (unseen and k.startswith(VIEWED)):
                    continue
                try:
                    x = float(v)
                except ValueError:
                    continue  # names, labels, parameters
                if not math.isfinite(x):
                    bad.append(f"{r.id} {k}")
            if math.isnan(num(r.row.get("staleness.mean"))):
                no_stale += 1
            for k, col in r.result["series"].items():
                if k in SERIES_MAY_BE_NULL:
                    continue
                if any(x is None or not math.isfinite(x) for x in col):
                    bad.append(f"{r.id} series {k}")
    counts = " and ".join(f"{len(runs)} in the {name} sweep" for name, runs in sweeps.items())
    lines = [f"- **{total} runs** ({counts}), each with its `result.json`."]
    if bad:
        shown = ", ".join(bad[:5]) + (f" and {len(bad) - 5} more" if len(bad) > 5 else "")
        lines.append(f"- **NaN, Inf or null where a value is defined: {len(bad)} cases** "
                     f"({shown}).")
    else:
        lines.append("- **No NaN or Inf** in any `summary.csv` field that is defined, and no "
                     "null in any per-frame series value that is defined (`staleness_mean` is "
                     "null on a fallback, `change_max` on a receiver's first frame; "
                     f"`staleness.*` is NaN in the {no_stale} runs whose receiver lookups fell "
                     f"back the whole run, `error.viewed.*` and `pops.viewed.*` in the {no_view} "
                     "runs whose receiver is never in view, `viewed_receiver_minutes` 0).")
    return lines


def generate(key, stress, stress_bl, stress_by_scenario):
    if key == "checks":
        return checks_block({"stress": stress, "budget/lifetime": stress_bl})
    m = re.fullmatch(r"budget (\S+)", key)
    if m:
        b = float(m.group(1))
        runs = [r for r in stress_bl if r.value("faces_per_frame") == b]
        if not runs:
            raise DataError(f"block '{key}': no runs at {m.group(1)} faces per frame in the "
                            "budget/lifetime sweep")
        scenarios = {r.field("scenario") for r in runs}
        if len(scenarios) != 1:
            raise DataError(f"block '{key}': runs of several scenarios ({sorted(scenarios)})")
        return table(runs, "", {})
    runs = stress_by_scenario.get(key)
    if not runs:
        raise DataError(f"block '{key}': no runs of scenario {key} in the stress sweep")
    return caption(runs, key) + table(runs, key, stress_by_scenario)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("stress_dir")
    ap.add_argument("stress_bl_dir")
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--doc", default=os.path.join(here, "..", "docs", "STABILITY.md"))
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit 1 if the doc differs from what the runs give")
    a = ap.parse_args()
    try:
        stress = [Run(a.stress_dir, row) for row in read_summary(a.stress_dir)]
        stress_bl = [Run(a.stress_bl_dir, row) for row in read_summary(a.stress_bl_dir)]
        by_scenario = {}
        for r in stress:
            by_scenario.setdefault(r.field("scenario"), []).append(r)
        with open(a.doc, encoding="utf-8") as f:
            doc = f.read()
        keys = [m.group(2) for m in MARKER.finditer(doc)]
        if not keys:
            raise DataError(f"{a.doc}: no <!-- stability-table: ... --> blocks")
        if len(set(keys)) != len(keys):
            raise DataError(f"{a.doc}: a block key appears twice")
        if len(START.findall(doc)) != len(keys) or any(
                START.search(m.group(3)) for m in MARKER.finditer(doc)):
            raise DataError(f"{a.doc}: a stability-table marker without its end marker")
        for sc in by_scenario:
            if sc not in keys:
                raise DataError(f"{a.doc}: scenario {sc} of the stress sweep has no block")
        for b in sorted({r.value("faces_per_frame") for r in stress_bl}):
            if f"budget {b:g}" not in keys:
                raise DataError(f"{a.doc}: budget {b:g} of the budget/lifetime sweep has no "
                                "block")

        def replace(m):
            # Blank lines around the generated text keep the markers out of tables and lists.
            lines = [""] + generate(m.group(2), stress, stress_bl, by_scenario) + [""]
            return m.group(1) + "\n".join(lines) + "\n" + m.group(4)

        new = MARKER.sub(replace, doc)
    except (DataError, OSError, ValueError, KeyError, TypeError) as e:
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        sys.exit(f"stability_tables: {msg}")
    if a.check:
        if new != doc:
            sys.exit(f"stability_tables: {a.doc} is not what the runs give (rerun without "
                     "--check)")
        return
    if new != doc:
        tmp = a.doc + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(new)
        os.replace(tmp, a.doc)


if __name__ == "__main__":
    main()
