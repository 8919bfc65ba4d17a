#!/usr/bin/env bash
# `ambisim bench-chart`: a PNG from bench_planners JSON; bad input is one line and exit 2, an
# existing chart is kept without --force.
# Usage: bench_chart.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }

cat >"$tmp/bench.json" <<'JSON'
{"context": {"num_cpus": 2}, "benchmarks": [
 {"name": "BM_LookupNaive/1000", "run_name": "BM_LookupNaive/1000", "run_type": "iteration",
  "real_time": 800, "time_unit": "ns", "live": 1000},
 {"name": "BM_LookupNaive/100000", "run_name": "BM_LookupNaive/100000", "run_type": "iteration",
  "real_time": 80000, "time_unit": "ns", "live": 100000},
 {"name": "BM_Lookup/shgraph/1000", "run_name": "BM_Lookup/shgraph/1000", "run_type": "iteration",
  "real_time": 120, "time_unit": "ns", "live": 1003},
 {"name": "BM_Lookup/shgraph/100000", "run_name": "BM_Lookup/shgraph/100000", "run_type": "iteration",
  "real_time": 150, "time_unit": "ns", "live": 100021},
 {"name": "BM_Frame/shgraph/1000/iterations:600", "run_name": "BM_Frame/shgraph/1000/iterations:600",
  "run_type": "iteration", "real_time": 12, "time_unit": "us", "live": 1010},
 {"name": "BM_Frame/shgraph/10000/iterations:600", "run_name": "BM_Frame/shgraph/10000/iterations:600",
  "run_type": "iteration", "real_time": 95, "time_unit": "us", "live": 10012}
]}
JSON

"$bin" bench-chart "$tmp/bench.json" --out "$tmp/chart.png" >/dev/null || fail "chart"
[ "$(head -c 8 "$tmp/chart.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
  fail "not a PNG"
before="$(sha256sum "$tmp/chart.png" | cut -d' ' -f1)"
"$bin" bench-chart "$tmp/bench.json" --out "$tmp/chart.png" 2>"$tmp/err"
code=$?
[ "$code" -eq 2 ] || fail "overwrite without --force: exit $code, expected 2"
grep -q "already exists" "$tmp/err" || fail "message: $(cat "$tmp/err")"
[ "$before" = "$(sha256sum "$tmp/chart.png" | cut -d' ' -f1)" ] || fail "chart overwritten"
"$bin" bench-chart "$tmp/bench.json" --out "$tmp/chart.png" --force >/dev/null || fail "--force"

expect_2() {
  local what="$1"
  shift
  "$bin" bench-chart "$@" 2>"$tmp/err" >/dev/null
  local code=$?
  [ "$code" -eq 2 ] || fail "$what: exit $code, expected 2"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "$what: not one line: $(cat "$tmp/err")"
}
expect_2 "missing file" "$tmp/none.json" --out "$tmp/a.png"
echo '{"format": "ambisim-run"}' >"$tmp/run.json"
expect_2 "not benchmark JSON" "$tmp/run.json" --out "$tmp/a.png"
echo '{"benchmarks": [' >"$tmp/broken.json"
expect_2 "invalid JSON" "$tmp/broken.json" --out "$tmp/a.png"
expect_2 "no --out" "$tmp/bench.json"
[ ! -e "$tmp/a.png" ] || fail "a PNG was written for bad input"
echo "ok"
