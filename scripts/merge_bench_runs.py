#!/usr/bin/env python3
"""Merges Google Benchmark JSON outputs of separate runs of one program into one file whose
every benchmark is the median over the runs.

Usage: scripts/merge_bench_runs.py RUN.json RUN.json [RUN.json ...] --out MERGED.json

Why: on the virtual machine the docs are measured on, one benchmark can differ by up to 1.7x
between two runs of the same binary minutes apart (the repetitions inside one run agree to a
few per cent), so one run's medians cannot tell a target met from one missed. Each input is
what `--benchmark_repetitions=N --benchmark_report_aggregates_only=true --benchmark_out=FILE
--benchmark_out_format=json` writes; from each the median aggregate of every benchmark is taken
(or its single iteration where there are no aggregates), and the output holds, per benchmark,
the median over the runs of its times and of every counter, written as a median aggregate, so
the tools that read one run (perf_planners.py, perf_game_load.py, `ambisim bench-chart`) read
the merge unchanged. Counters that are the same in every run (live probes, bytes) stay as they
are; `runs` and `run_times` say what went in. A benchmark missing from any run is an error: a
median over fewer runs would not be the same statistic.

The output's context is the first run's, with `merged_runs` listing each input's date and file.
Writes nothing unless every input reads. Standard library only.
"""
import argparse
import json
import math
import os
import statistics
import sys

TIME_KEYS = ("real_time", "cpu_time")
# Per-entry fields that are bookkeeping, not measurements.
SKIP_KEYS = {"name", "run_name", "run_type", "aggregate_name", "aggregate_unit", "family_index",
             "per_family_instance_index", "repetitions", "repetition_index", "threads",
             "iterations", "time_unit", "label", "error_occurred", "error_message"}


def read_run(path):
    """(context, {run name: entry}) of one output; exits with code 2 naming the file on bad input."""
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)  # Google Benchmark writes NaN for a constant counter's spread
        benchmarks = doc["benchmarks"]
    except (OSError, ValueError, KeyError, TypeError) as e:
        print(f"{path}: not a Google Benchmark JSON output ({e})", file=sys.stderr)
        sys.exit(2)
    medians, singles = {}, {}
    for i, b in enumerate(benchmarks):
        if not isinstance(b, dict) or "name" not in b:
            print(f"{path}: benchmarks[{i}] has no name", file=sys.stderr)
            sys.exit(2)
        name = b.get("run_name", b["name"])
        if b.get("aggregate_name") == "median":
            medians[name] = b
        elif "aggregate_name" not in b:
            singles.setdefault(name, b)
    return doc.get("context", {}), {**singles, **medians}


def merge(runs):
    """The per-benchmark medians over runs (each a {run name: entry}), in the first run's order."""
    names = list(runs[0][1].keys())
    for path, entries in runs[1:]:
        missing = [n for n in names if n not in entries]
        extra = [n for n in entries if n not in runs[0][1]]
        if missing or extra:
            which = missing[0] if missing else extra[0]
            print(f"{path}: benchmark {which} is not in every run", file=sys.stderr)
            sys.exit(2)
    out = []
    for name in names:
        group = [entries[name] for _, entries in runs]
        first = group[0]
        units = {b.get("time_unit", "ns") for b in group}
        if len(units) != 1:
            print(f"{runs[1][0]}: benchmark {name} changes its time unit", file=sys.stderr)
            sys.exit(2)
        merged = {"name": f"{name}_median", "run_name": name, "run_type": "aggregate",
                  "aggregate_name": "median", "repetitions": first.get("repetitions", 1),
                  "threads": first.get("threads", 1), "iterations": first.get("iterations", 1),
                  "time_unit": first.get("time_unit", "ns"), "runs": len(group),
                  "run_times": [b["real_time"] for b in group]}
        for key in TIME_KEYS:
            merged[key] = statistics.median(b[key] for b in group)
        for key, value in first.items():
            if key in SKIP_KEYS or key in TIME_KEYS or not isinstance(value, (int, float)):
                continue
            values = [b.get(key) for b in group]
            if any(not isinstance(v, (int, float)) or math.isnan(v) for v in values):
                merged[key] = value
            else:
                merged[key] = statistics.median(values)
        out.append(merged)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="Google Benchmark JSON outputs, one per run")
    parser.add_argument("--out", required=True, help="the merged JSON to write")
    args = parser.parse_args(argv)
    if len(args.runs) < 2:
        parser.error("give at least two runs")
    out_path = os.path.abspath(args.out)
    if out_path in {os.path.abspath(p) for p in args.runs}:
        parser.error("--out must not be one of the runs")
    runs = [(p, read_run(p)) for p in args.runs]
    context = dict(runs[0][1][0])
    context["merged_runs"] = [{"file": os.path.basename(p), "date": c.get("date", "")}
                              for p, (c, _) in runs]
    benchmarks = merge([(p, entries) for p, (_, entries) in runs])
    tmp = out_path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump({"context": context, "benchmarks": benchmarks}, f, indent=2)
        f.write("\n")
    os.replace(tmp, out_path)


if __name__ == "__main__":
    main()
