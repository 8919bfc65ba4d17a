#!/usr/bin/env python3
"""Rewrites docs/PERFORMANCE.md's game's-load table from a bench_planners JSON output.

Usage: scripts/perf_game_load.py BENCH_JSON [--doc docs/PERFORMANCE.md] [--check]

The block between `<!-- game-load-table -->` and `<!-- end game-load-table -->` becomes one
row per target of SPEC section 8 for the default planner (`ambisim`): what was measured (the
median of the repetitions, or the single run), the naive path of the same run where there is
one, the target and whether it is met. BENCH_JSON is what
`bench_planners --benchmark_out=FILE` writes (all of it, or only
`--benchmark_filter='ambisim|BM_LookupNaive'`).
Google Benchmark writes NaN for the spread of a constant counter: read leniently.
Standard library only.
"""
import json
import re
import sys

from doc_block import doc_table_args, rewrite_block


def load(path):
    text = open(path).read()
    text = re.sub(r"\b-?nan\b", "null", text, flags=re.I)
    return json.loads(text)["benchmarks"]


def pick(benchmarks, name):
    """The median aggregate of `name` if there is one, else the single run."""
    runs = [b for b in benchmarks if b.get("run_name", b["name"]) == name]
    for b in runs:
        if b.get("aggregate_name") == "median":
            return b
    plain = [b for b in runs if "aggregate_name" not in b]
    if not plain:
        sys.exit(f"no benchmark {name} in the input")
    return plain[0]


def ns(b):
    unit = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
    return b["real_time"] * unit


def fmt_time(t_ns):
    if t_ns < 1e3:
        return f"{t_ns:.0f} ns"
    if t_ns < 1e6:
        return f"{t_ns / 1e3:.1f} µs"
    return f"{t_ns / 1e6:.2f} ms"


def table(benchmarks):
    look = {n: pick(benchmarks, f"BM_Lookup/ambisim/{n}") for n in (1000, 10000, 100000)}
    near = {n: pick(benchmarks, f"BM_LookupNearProbes/ambisim/{n}") for n in (1000, 10000, 100000)}
    ref = {n: pick(benchmarks, f"BM_LookupReference/ambisim/{n}") for n in (1000, 10000)}
    frame = pick(benchmarks, "BM_Frame/ambisim/1000/iterations:600")
    frame_r = pick(benchmarks, "BM_FrameReceivers/ambisim/1000/iterations:600")
    many = pick(benchmarks, "BM_LookupMany/ambisim/10000/iterations:3")
    many_ref = pick(benchmarks, "BM_LookupManyReference/ambisim/10000/iterations:1")
    growth = ns(look[100000]) / ns(look[1000])
    bpp = look[10000]["bytes_per_probe"]

    def live(b):
        return f"{int(round(b['live'])):,}"

    def far(b):
        return f"{100 * b.get('far_share', float('nan')):.0f} %"

    rows = [
        ("lookup at 1e4 live probes",
         f"**{fmt_time(ns(look[10000]))}** ({live(look[10000])} live; {far(look[10000])} of the "
         f"points mix in the far field)", fmt_time(ns(ref[10000])), "≤ 150 ns",
         ns(look[10000]) <= 150),
        ("lookup at 1e4, points within 1 m of a probe",
         f"**{fmt_time(ns(near[10000]))}** ({live(near[10000])} live; far field {far(near[10000])}); "
         f"{fmt_time(ns(near[1000]))} at {live(near[1000])}, {fmt_time(ns(near[100000]))} at "
         f"{live(near[100000])}", "", "≤ 150 ns", ns(near[10000]) <= 150),
        ("lookup growth 1e3 → 1e5",
         f"**{growth:.2f}x** ({fmt_time(ns(look[1000]))}, {live(look[1000])} live, far field "
         f"{far(look[1000])} → {fmt_time(ns(look[100000]))}, {live(look[100000])} live, far field "
         f"{far(look[100000])})", f"{fmt_time(ns(ref[1000]))} at 1e3", "≤ 1.5x", growth <= 1.5),
        ("planner work per frame, 1e3 probes, 8 receivers",
         f"**{frame['real_time']:.1f} µs** (update {frame['update_us']:.1f} µs)", "", "≤ 20 µs",
         frame["real_time"] <= 20),
        ("planner work per frame, 1e3 probes, 1e3 receivers",
         f"**{frame_r['real_time']:.1f} µs** (update {frame_r['update_us']:.1f} µs)", "",
         "≤ 20 µs", frame_r["real_time"] <= 20),
        ("lookup_many, 1e4 receivers per frame, 1e4 probes",
         f"**{fmt_time(ns(many))}**", fmt_time(ns(many_ref)), "≤ 1.5 ms", ns(many) <= 1.5e6),
        ("memory per probe at 1e4, structure included", f"**{bpp:.0f} B**", "", "≤ 256 B",
         bpp <= 256),
    ]
    out = ["| target (SPEC 8) | ambisim, index | naive: linear scan, same probes | target | met |",
           "|---|---|---|---|:-:|"]
    for what, got, naive, target, met in rows:
        out.append(f"| {what} | {got} | {naive} | {target} | {'yes' if met else '**no**'} |")
    return "\n".join(out)


def main():
    args = doc_table_args(__doc__.splitlines()[0])
    ok = rewrite_block(args.doc, "<!-- game-load-table -->", "<!-- end game-load-table -->",
                       table(load(args.bench_json)), args.check)
    sys.exit(0 if ok else 1)

if __name__ == "__main__":
    main()
