#!/usr/bin/env bash
# Recorded paths through the real binary: `run --record-camera` writes the camera of every frame
# as CSV; a scenario whose "recorded" camera names that file (next to it) replays to the same
# summary and frames; recorded receivers are lit from their first to their last sample; and a
# changed recording changes the scenario's hash, so `sweep --resume` reruns its runs.
# Usage: recorded.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
good="$src/tests/data/small_drive.json"
mkdir -p "$tmp/rec"

"$bin" run "$good" --planner nearest --out "$tmp/scripted" --record-camera "$tmp/rec/flight.csv" \
  --quiet || fail "run --record-camera"
[ "$(head -1 "$tmp/rec/flight.csv")" = "time,x,y,z,vx,vy,vz,cut" ] || fail "header: $(head -1 "$tmp/rec/flight.csv")"
[ "$(wc -l <"$tmp/rec/flight.csv")" -eq 61 ] || fail "expected 60 frames and a header"

# The same scenario with the recorded camera, and again with recorded receivers: two cyclists
# riding along the first second of the flight, 5 m to its side.
python3 - "$good" "$tmp/rec" <<'PY' || fail "writing the replay scenarios"
import csv, json, sys
d = json.load(open(sys.argv[1]))
d["camera"] = {"type": "recorded", "file": "flight.csv"}
json.dump(d, open(sys.argv[2] + "/replay.json", "w"))
rows = list(csv.DictReader(open(sys.argv[2] + "/flight.csv")))
with open(sys.argv[2] + "/bikes.csv", "w") as out:
    out.write("id,time,x,y,z\n")
    for k in (0, 15, 30):
        r = rows[k]
        out.write("bike_a,%s,%s,%.6f,%s\n" % (r["time"], r["x"], float(r["y"]) + 5, r["z"]))
    for k in (10, 20):
        r = rows[k]
        out.write("bike_b,%s,%s,%.6f,%s\n" % (r["time"], r["x"], float(r["y"]) - 5, r["z"]))
d["receivers"]["recorded"] = {"file": "bikes.csv", "size_m": 1.5}
json.dump(d, open(sys.argv[2] + "/replay_bikes.json", "w"))
PY
"$bin" run "$tmp/rec/replay.json" --planner nearest --out "$tmp/replayed" --quiet || fail "replay"
cmp -s "$tmp/scripted/frames.csv" "$tmp/replayed/frames.csv" || fail "frames.csv differs on replay"
summary() { python3 -c "import json,sys; print(json.dumps(json.load(open(sys.argv[1]))['summary'], sort_keys=True))" "$1"; }
[ "$(summary "$tmp/scripted/result.json")" = "$(summary "$tmp/replayed/result.json")" ] ||
  fail "summary differs on replay"

"$bin" run "$tmp/rec/replay_bikes.json" --planner nearest --out "$tmp/bikes" --quiet || fail "bikes"
frames_of() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['summary']['receiver_frames'])" "$1"; }
# bike_a is live on frames 0..30 (31), bike_b on frames 10..20 (11).
[ "$(frames_of "$tmp/bikes/result.json")" -eq $(($(frames_of "$tmp/replayed/result.json") + 42)) ] ||
  fail "recorded receivers: $(frames_of "$tmp/bikes/result.json") receiver-frames"

# sweep --resume keeps runs whose recording is unchanged and reruns them when it changes.
printf '{"scenarios": ["replay_bikes.json"], "planners": ["constant"]}' >"$tmp/rec/s.json"
"$bin" sweep "$tmp/rec/s.json" --out "$tmp/s" -j1 2>/dev/null || fail "sweep"
"$bin" sweep "$tmp/rec/s.json" --out "$tmp/s" -j1 --resume 2>"$tmp/err" || fail "resume"
grep -q "0 run, 1 resumed" "$tmp/err" || fail "unchanged resume: $(tail -1 "$tmp/err")"
sed -i 's/^bike_b,\([^,]*\),\([^,]*\),/bike_b,\1,\21,/' "$tmp/rec/bikes.csv"
"$bin" sweep "$tmp/rec/s.json" --out "$tmp/s" -j1 --resume 2>"$tmp/err" || fail "resume after edit"
grep -q "1 run, 0 resumed" "$tmp/err" || fail "a changed recording must rerun: $(tail -1 "$tmp/err")"
echo ok
