"""Rewrites one marked block of a doc in place (shared by the table scripts).

rewrite_block(doc_path, begin, end, text, check): the text between the lines `begin` and `end`
becomes `text`. With check, nothing is written and the return value says whether the doc is
already up to date; otherwise the doc is replaced atomically when it changes. Exits with one
line naming the doc when the block is missing. Standard library only.
"""
import argparse
import os
import re
import sys


def rewrite_block(doc_path, begin, end, text, check=False):
    doc = open(doc_path).read()
    pattern = re.compile("(" + re.escape(begin) + r"\n)(.*?)(" + re.escape(end) + ")", re.S)
    if not pattern.search(doc):
        sys.exit(f"{doc_path}: no block {begin}")
    new = pattern.sub(lambda m: m.group(1) + text + "\n" + m.group(3), doc)
    if check:
        return new == doc
    if new != doc:
        tmp = doc_path + ".tmp"
        with open(tmp, "w") as f:
            f.write(new)
        os.replace(tmp, doc_path)
    return True


def doc_table_args(description):
    """The command line every table script takes: BENCH_JSON [--doc DOC] [--check]."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("bench_json")
    ap.add_argument("--doc", default="docs/PERFORMANCE.md")
    ap.add_argument("--check", action="store_true",
                    help="only say whether the doc's tables match the input (exit 1 if not)")
    return ap.parse_args()
