#!/usr/bin/env python3
"""Rewrites docs/PERFORMANCE.md's per-planner tables from one bench_planners JSON output.

Usage: scripts/perf_planners.py BENCH_JSON [--doc docs/PERFORMANCE.md] [--check]

Blocks rewritten (each between `<!-- NAME -->` and `<!-- end NAME -->`):
- planner-targets: the summary rows of the lookup, frame and memory targets of issue 7 and
  SPEC section 8, every planner measured;
- planner-cost: lookup and per-frame planner work against live probes, one row per planner,
  and the naive linear scan;
- shgraph-naive: the SHGraph reference paths on the same structures;
- planner-memory: memory per live probe at 1e4 and 1e5, L2/fp32 and L1/fp16.

Every number is the median of the repetitions (or the single run) of the benchmark it names.
BENCH_JSON is what `bench_planners --benchmark_repetitions=3
--benchmark_report_aggregates_only=true --benchmark_out=FILE --benchmark_out_format=json` writes;
Google Benchmark writes NaN for the spread of a constant counter: read leniently.
Standard library only.
"""
import sys

from doc_block import doc_table_args, rewrite_block
from perf_game_load import fmt_time, load, ns

SIZES = (1000, 10000, 100000)
LOOKUP_TARGET_NS = 150.0
FRAME_TARGET_US = 20.0
MEMORY_TARGET_B = 256.0
GROWTH_TARGET = 1.5


def runs_by_name(benchmarks):
    """run name -> the median aggregate, or the single run when there is no aggregate."""
    out = {}
    for b in benchmarks:
        name = b.get("run_name", b["name"])
        if b.get("aggregate_name") == "median" or ("aggregate_name" not in b and name not in out):
            out[name] = b
    return out


def planners_of(runs):
    """Planners in the benchmark's registration order (that of BM_Lookup/<planner>/1000)."""
    seen = []
    for name in runs:
        parts = name.split("/")
        if parts[0] == "BM_Lookup" and len(parts) == 3 and parts[1] not in seen:
            seen.append(parts[1])
    if not seen:
        sys.exit("no BM_Lookup/<planner>/<n> benchmark in the input")
    return seen


def fmt_growth(g):
    return f"{g:.2f}x" if g < 10 else f"{g:.0f}x"


def live(b):
    return f"{int(round(b['live'])):,}"


def frame_cell(b):
    if b is None:
        return "–"
    return f"{ns(b) / 1e3:.1f} ({b['update_us']:.1f}), {live(b)}"


def us(b):
    return ns(b) / 1e3


def cost_table(runs, planners):
    head = ("| planner | lookup @1e3 (live) | @1e4 (live) | @1e5 (live) | growth 1e3 → 1e5 | "
            "@1e4 right after a burst | frame @1e3 µs (update), live at end | "
            "frame @1e4 µs (update), live at end | B/probe @1e4 | B/probe L1/fp16 |")
    rows = [head, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for p in planners:
        look = {n: runs.get(f"BM_Lookup/{p}/{n}") for n in SIZES}
        if any(v is None for v in look.values()):
            sys.exit(f"planner {p}: a BM_Lookup size is missing")
        fresh = runs.get(f"BM_LookupFresh/{p}/10000")
        frame = {n: runs.get(f"BM_Frame/{p}/{n}/iterations:600") for n in SIZES[:2]}
        l1 = runs.get(f"BM_MemoryL1fp16/{p}/10000/iterations:1")
        growth = ns(look[100000]) / ns(look[1000])
        cells = [p]
        cells += [f"{fmt_time(ns(look[n]))} ({live(look[n])})" for n in SIZES]
        cells.append(fmt_growth(growth))
        cells.append(fmt_time(ns(fresh)) if fresh else "–")
        cells += [frame_cell(frame[n]) for n in SIZES[:2]]
        cells.append(f"{look[10000]['bytes_per_probe']:.0f}")
        cells.append(f"{l1['bytes_per_probe']:.0f}" if l1 else "–")
        rows.append("| " + " | ".join(cells) + " |")
    naive = {n: runs.get(f"BM_LookupNaive/{n}") for n in SIZES}
    if all(naive.values()):
        g = ns(naive[100000]) / ns(naive[1000])
        rows.append("| *naive linear scan* | " +
                    " | ".join(f"{fmt_time(ns(naive[n]))} ({live(naive[n])})" for n in SIZES) +
                    f" | {fmt_growth(g)} | | | | | |")
    return "\n".join(rows)


def shgraph_naive_table(runs, planners):
    rows = ["| planner | lookup @1e3 | @1e4 | @1e5 | frame @1e3 µs (update) | "
            "frame @1e4 µs (update) |", "|---|---:|---:|---:|---:|---:|"]
    for p in planners:
        look = {n: runs.get(f"BM_LookupShGraphNaive/{p}/{n}") for n in SIZES}
        if not all(look.values()):
            continue
        frame = {n: runs.get(f"BM_FrameShGraphNaive/{p}/{n}/iterations:600") for n in SIZES[:2]}
        cells = [p] + [fmt_time(ns(look[n])) for n in SIZES]
        cells += [f"{us(frame[n]):.1f} ({frame[n]['update_us']:.1f})" if frame[n] else "–"
                  for n in SIZES[:2]]
        rows.append("| " + " | ".join(cells) + " |")
    return "\n".join(rows)


def memory_table(runs, planners):
    rows = ["| planner | L2/fp32, 1e4 probes | at 1e5 probes (live) | L1/fp16, 1e4 probes |",
            "|---|---:|---:|---:|"]
    for p in planners:
        m4 = runs[f"BM_Lookup/{p}/10000"]
        m5 = runs[f"BM_Lookup/{p}/100000"]
        l1 = runs.get(f"BM_MemoryL1fp16/{p}/10000/iterations:1")
        rows.append(f"| {p} | {m4['bytes_per_probe']:.0f} B | {m5['bytes_per_probe']:.0f} B "
                    f"({live(m5)}) | " + (f"{l1['bytes_per_probe']:.0f} B" if l1 else "–") + " |")
    return "\n".join(rows)


def listing(planners, value, fmt):
    """'`a` 1.0, `b` 2.0': each planner with its value."""
    return ", ".join(f"`{p}` {fmt(value(p))}" for p in planners)


def targets_table(runs, planners):
    def look(p, n=10000):
        return ns(runs[f"BM_Lookup/{p}/{n}"])

    def growth(p):
        return look(p, 100000) / look(p, 1000)

    def frame(p):
        b = runs.get(f"BM_Frame/{p}/1000/iterations:600")
        return us(b) if b else None

    def memory(p):
        return runs[f"BM_Lookup/{p}/10000"]["bytes_per_probe"]

    def verdict(met, total):
        return "yes" if met == total else ("**no**" if met == 0 else "partly")

    rows = ["| what | measured | target | met |", "|---|---|---|:-:|"]
    specs = [
        ("lookup at 1e4 live probes", look, lambda v: v <= LOOKUP_TARGET_NS, fmt_time,
         f"≤ {LOOKUP_TARGET_NS:.0f} ns"),
        ("lookup growth from 1e3 to 1e5 live probes", growth, lambda v: v <= GROWTH_TARGET,
         fmt_growth, f"≤ {GROWTH_TARGET}x"),
        ("planner work per frame at 1e3 live probes", frame, lambda v: v <= FRAME_TARGET_US,
         lambda v: f"{v:.1f} µs", f"≤ {FRAME_TARGET_US:.0f} µs"),
        ("memory per live probe at 1e4, structure included (default formats: L2/fp32, `ambisim` fp16)",
         memory,
         lambda v: v <= MEMORY_TARGET_B, lambda v: f"{v:.0f} B", f"≤ {MEMORY_TARGET_B:.0f} B"),
    ]
    for what, value, ok, fmt, target in specs:
        measured = [p for p in planners if value(p) is not None]
        met = [p for p in measured if ok(value(p))]
        missed = [p for p in measured if p not in met]
        text = ""
        if met:
            text += "met by " + listing(met, value, fmt)
        if missed:
            text += ("; " if text else "") + "**missed** by " + listing(missed, value, fmt)
        rows.append(f"| {what} | {text} | {target} | {verdict(len(met), len(measured))} |")
    return "\n".join(rows)


def main():
    args = doc_table_args(__doc__.splitlines()[0])
    runs = runs_by_name(load(args.bench_json))
    planners = planners_of(runs)
    blocks = {
        "planner-targets": targets_table(runs, planners),
        "planner-cost": cost_table(runs, planners),
        "shgraph-naive": shgraph_naive_table(runs, planners),
        "planner-memory": memory_table(runs, planners),
    }
    fresh = True
    for name, text in blocks.items():
        fresh &= rewrite_block(args.doc, f"<!-- {name} -->", f"<!-- end {name} -->", text,
                               args.check)
    if args.check and not fresh:
        sys.exit(f"{args.doc}: the planner tables differ from {args.bench_json}")


if __name__ == "__main__":
    main()
