#!/usr/bin/env bash
# An existing result is never overwritten without --force, and a run leaves no temporary files.
# Usage: no_overwrite.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
scen="$src/tests/data/small_drive.json"
fail() { echo "FAIL $*"; exit 1; }

"$bin" run "$scen" --planner constant --out "$tmp/r" --quiet || fail "first run"
[ -s "$tmp/r/result.json" ] && [ -s "$tmp/r/frames.csv" ] || fail "outputs missing"
before="$(sha256sum "$tmp/r/result.json" | cut -d' ' -f1)"
"$bin" run "$scen" --planner nearest --out "$tmp/r" --quiet 2>"$tmp/err"
code=$?
[ "$code" -eq 2 ] || fail "second run exit $code, expected 2"
grep -q "already exists (use --force" "$tmp/err" || fail "message: $(cat "$tmp/err")"
after="$(sha256sum "$tmp/r/result.json" | cut -d' ' -f1)"
[ "$before" = "$after" ] || fail "result overwritten without --force"
"$bin" run "$scen" --planner nearest --out "$tmp/r" --quiet --force || fail "forced run"
grep -q '"name": "nearest"' "$tmp/r/result.json" || fail "forced run did not replace the result"
leftovers="$(find "$tmp/r" -name '*.tmp.*' | wc -l)"
[ "$leftovers" -eq 0 ] || fail "temporary files left behind"
# The same run twice gives byte-identical results (the timing section aside).
"$bin" run "$scen" --planner nearest --out "$tmp/r2" --quiet || fail "rerun"
strip() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d.pop('timing'); print(json.dumps(d))" "$1"; }
[ "$(strip "$tmp/r/result.json")" = "$(strip "$tmp/r2/result.json")" ] || fail "results differ between reruns"
cmp -s "$tmp/r/frames.csv" "$tmp/r2/frames.csv" || fail "frames.csv differs between reruns"
echo "ok"
