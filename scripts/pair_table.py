#!/usr/bin/env python3
"""Rewrites a doc block comparing two planner labels of one sweep, scenario by scenario.

Usage: scripts/pair_table.py SWEEP_DIR --doc FILE --block NAME --labels A B [--check]

The block is the text between `<!-- pair-table: NAME -->` and `<!-- end pair-table -->`. One
row per scenario in the sweep's order (the first seed and budget of each: one run per label),
with viewed p95 and mean dE00 and viewed and uniform pops per minute of A and of B. Only
deterministic results go in, so the same sweep always gives the same table. --check exits 1
(writing nothing) when the doc differs from what the runs give. Standard library only.
"""
import argparse
import csv
import math
import os
import sys

from doc_block import rewrite_block

COLUMNS = [
    ("viewed p95 dE00", "error.viewed.de2000.p95"),
    ("viewed mean dE00", "error.viewed.de2000.mean"),
    ("viewed pops/min", "pops.viewed.per_min"),
    ("pops/min", "pops.uniform.per_min"),
]


def number(text):
    try:
        x = float(text)
    except ValueError:
        return "–"
    if math.isnan(x):
        return "–"
    return f"{x:.3g}" if abs(x) < 100 else f"{x:.0f}"


def table(sweep_dir, a, b):
    path = os.path.join(sweep_dir, "summary.csv")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    by = {}
    order = []
    for r in rows:
        key = r["scenario"]
        if key not in by:
            by[key] = {}
            order.append(key)
        by[key].setdefault(r["label"], r)
    head = "| scenario | " + " | ".join(f"{n}: {a} / {b}" for n, _ in COLUMNS) + " |"
    out = [head, "|---|" + "---:|" * len(COLUMNS)]
    for sc in order:
        if a not in by[sc] or b not in by[sc]:
            sys.exit(f"{path}: scenario {sc} lacks a run of {a} or {b}")
        cells = [f"{number(by[sc][a][k])} / {number(by[sc][b][k])}" for _, k in COLUMNS]
        out.append(f"| {sc} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--doc", required=True)
    ap.add_argument("--block", required=True)
    ap.add_argument("--labels", nargs=2, required=True)
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    ok = rewrite_block(args.doc, f"<!-- pair-table: {args.block} -->", "<!-- end pair-table -->",
                       table(args.sweep_dir, *args.labels), args.check)
    sys.exit(0 if ok else 1)

if __name__ == "__main__":
    main()
