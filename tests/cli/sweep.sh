#!/usr/bin/env bash
# Sweeps: identical results for -j1 and -j2, --resume skips finished runs, an existing sweep is
# not overwritten, shards partition the runs.
# Usage: sweep.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
sweep="$src/tests/data/small_sweep.json"
fail() { echo "FAIL $*"; exit 1; }
strip_timing() {
  for f in "$1"/runs/*/result.json; do
    python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d.pop('timing'); print(sys.argv[1].split('/runs/')[1], json.dumps(d, sort_keys=True))" "$f"
  done
}

"$bin" sweep "$sweep" --out "$tmp/a" -j1 2>/dev/null || fail "sweep -j1"
"$bin" sweep "$sweep" --out "$tmp/b" -j2 2>/dev/null || fail "sweep -j2"
[ "$(ls "$tmp/a/runs" | wc -l)" -eq 12 ] || fail "expected 12 runs"
cmp -s "$tmp/a/summary.csv" "$tmp/b/summary.csv" || fail "summary.csv differs between -j1 and -j2"
[ "$(strip_timing "$tmp/a")" = "$(strip_timing "$tmp/b")" ] || fail "run results differ between -j1 and -j2"

"$bin" sweep "$sweep" --out "$tmp/a" -j2 2>"$tmp/err"
[ $? -eq 2 ] || fail "rerun into a finished sweep must refuse"
grep -q "already exists" "$tmp/err" || fail "message: $(cat "$tmp/err")"
rm -r "$tmp/a/runs/small_drive__nearest__b1__v2"
"$bin" sweep "$sweep" --out "$tmp/a" -j2 --resume 2>"$tmp/err" || fail "resume"
grep -q "1 run, 11 resumed" "$tmp/err" || fail "resume counts: $(tail -1 "$tmp/err")"
cmp -s "$tmp/a/summary.csv" "$tmp/b/summary.csv" || fail "resumed summary differs"

"$bin" sweep "$sweep" --out "$tmp/s" --shard 1/2 2>/dev/null || fail "shard 1"
"$bin" sweep "$sweep" --out "$tmp/s" --shard 2/2 2>/dev/null || fail "shard 2"
[ "$(ls "$tmp/s/runs" | wc -l)" -eq 12 ] || fail "shards did not cover every run"
cmp -s "$tmp/s/summary.csv" "$tmp/b/summary.csv" || fail "sharded summary differs"
echo ok
