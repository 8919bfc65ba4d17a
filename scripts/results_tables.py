#!/usr/bin/env python3
"""Markdown results tables for the README from a sweep directory (summary.csv + timing.csv).

Usage: scripts/results_tables.py SWEEP_DIR [--speed 1] [--budgets 1,0.5]

One table per scenario and budget at the given camera speed scale, one row per planner in
sweep order: dE00 mean/p95, pops/min, coverage, faces used, max live probes, max bytes and the
planner's measured microseconds per frame (from timing.csv: wall clock, noisy, not a result).
Standard library only.
"""
import argparse
import csv
import os
import sys

COLUMNS = [
    ("ΔE00 mean", "error.de2000.mean", "{:.2f}"),
    ("ΔE00 p95", "error.de2000.p95", "{:.2f}"),
    ("pops/min", "pops.per_min", "{:.1f}"),
    ("coverage", "coverage.mean", "{:.3f}"),
    ("faces used", "faces.used", "{:.0f}"),
    ("max live probes", "probes.max_live", "{:.0f}"),
    ("max bytes", "memory.max_bytes", "{:.0f}"),
]


def read_csv(path):
    with open(path, newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    return list(csv.DictReader(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--speed", default="1")
    ap.add_argument("--budgets", default="1,0.5")
    a = ap.parse_args()
    summary = read_csv(os.path.join(a.sweep_dir, "summary.csv"))
    timing_path = os.path.join(a.sweep_dir, "timing.csv")
    timing = {r["run"]: r for r in read_csv(timing_path)} if os.path.exists(timing_path) else {}
    budgets = a.budgets.split(",")
    scenarios = list(dict.fromkeys(r["scenario"] for r in summary))
    for sc in scenarios:
        for b in budgets:
            rows = [r for r in summary
                    if r["scenario"] == sc and r["faces_per_frame"] == b
                    and r["speed_scale"] == a.speed]
            if not rows:
                sys.exit(f"results_tables: no runs for {sc} at budget {b}, speed {a.speed}")
            fps = float(rows[0]["frames"]) / float(rows[0]["duration_s"])  # "fps" 0 = own
            print(f"**{sc}**, budget {b} face/frame = {float(b) * fps:g} faces/s, "
                  f"camera speed x{a.speed} ({float(rows[0]['duration_s']):g} s):\n")
            head = ["planner"] + [c[0] for c in COLUMNS] + ["planner µs/frame"]
            print("| " + " | ".join(head) + " |")
            print("|---|" + "---:|" * (len(head) - 1))
            for r in rows:
                cells = [r["label"]] + [fmt.format(float(r[key])) for _, key, fmt in COLUMNS]
                t = timing.get(r["run"], {}).get("timing.planner_us_per_frame", "")
                cells.append(f"{float(t):.1f}" if t else "")
                print("| " + " | ".join(cells) + " |")
            print()


if __name__ == "__main__":
    main()
