#!/usr/bin/env bash
# Bad input: one line naming the file and JSON path, exit code 2, and nothing written.
# Usage: bad_input.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail=0
good="$src/tests/data/small_drive.json"

# expect_error NAME EXPECTED_SUBSTRING -- ARGS...
expect_error() {
  local name="$1" want="$2"
  shift 3
  local out="$tmp/out_$name"
  "$bin" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local code=$?
  local err
  err="$(cat "$tmp/stderr")"
  if [ "$code" -ne 2 ]; then
    echo "FAIL $name: exit $code, expected 2 ($err)"
    fail=1
  elif ! grep -qF -- "$want" "$tmp/stderr"; then
    echo "FAIL $name: message '$err' lacks '$want'"
    fail=1
  elif [ "$(wc -l <"$tmp/stderr")" -ne 1 ]; then
    echo "FAIL $name: expected one line, got: $err"
    fail=1
  elif [ -e "$out" ]; then
    echo "FAIL $name: output written despite the error"
    fail=1
  else
    echo "ok   $name: $err"
  fi
}

# mutate NAME PYTHON_EXPRESSION: writes $tmp/NAME.json from the good scenario.
mutate() {
  python3 - "$good" "$tmp/$1.json" "$2" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(d, open(sys.argv[2], "w"))
PY
}

printf '' >"$tmp/empty.json"
printf '{"world": ' >"$tmp/broken.json"
head -c 64 /dev/urandom >"$tmp/garbage.json" 2>/dev/null || printf '\x00\x01\xff' >"$tmp/garbage.json"
mutate unknown_key 'd["camera"]["sped_mps"] = 3'
mutate negative_speed 'd["camera"]["speed_mps"] = -3'
mutate wrong_type 'd["frames"]["fps"] = "sixty"'
mutate missing_camera 'del d["camera"]'
mutate zero_size 'd["world"]["size_m"] = [0, 512]'
mutate bad_budget 'd["budget"]["faces_per_frame"] = -1'
mutate huge_face 'd["budget"]["face_size"] = 100000'

expect_error missing "no such file" -- run "$tmp/nope.json" --out "$tmp/out_missing"
expect_error directory "is a directory" -- run "$tmp" --out "$tmp/out_directory"
expect_error empty "empty.json: is empty" -- run "$tmp/empty.json" --out "$tmp/out_empty"
expect_error broken "invalid JSON at line 1" -- run "$tmp/broken.json" --out "$tmp/out_broken"
expect_error garbage "garbage.json" -- run "$tmp/garbage.json" --out "$tmp/out_garbage"
expect_error unknown_key "unknown_key.json: /camera/sped_mps: unknown key" -- run "$tmp/unknown_key.json" --out "$tmp/out_unknown_key"
expect_error negative_speed "/camera/speed_mps: must be >= 0, got -3" -- run "$tmp/negative_speed.json" --out "$tmp/out_negative_speed"
expect_error wrong_type "/frames/fps: must be a number" -- run "$tmp/wrong_type.json" --out "$tmp/out_wrong_type"
expect_error missing_camera "/camera: required object is missing" -- run "$tmp/missing_camera.json" --out "$tmp/out_missing_camera"
expect_error zero_size "/world/size_m" -- run "$tmp/zero_size.json" --out "$tmp/out_zero_size"
expect_error bad_budget "/budget/faces_per_frame" -- run "$tmp/bad_budget.json" --out "$tmp/out_bad_budget"
expect_error huge_face "/budget/face_size" -- run "$tmp/huge_face.json" --out "$tmp/out_huge_face"
expect_error unknown_planner "valid planners: oracle" -- run "$good" --planner octopus --out "$tmp/out_unknown_planner"
expect_error unknown_param "valid parameters" -- run "$good" --planner nearest --set spacing=3 --out "$tmp/out_unknown_param"
expect_error bad_param "must be a number > 0" -- run "$good" --planner nearest --set spacing_m=-1 --out "$tmp/out_bad_param"
exit $fail
