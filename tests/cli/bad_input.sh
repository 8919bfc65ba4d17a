#!/usr/bin/env bash
# Bad input: one line naming the file and JSON path, exit code 2, and nothing written: the
# output path does not appear, or an existing output directory is byte-for-byte unchanged.
# Covers run, sweep, world, probe, compare, plot, viz and film. Usage: bad_input.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$1"
src="$(cd "$2" && pwd)"
tmp="$(mktemp -d)"
trap 'chmod -R u+rwx "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
fail=0
cases=0
skipped=0
good="$src/tests/data/small_drive.json"
# chmod does not stop root from reading or writing: those cases are skipped, not failed.
as_root=0
[ "$(id -u)" -eq 0 ] && as_root=1

# Every file under a directory with its checksum (empty for a missing path).
fingerprint() {
  [ -e "$1" ] || return 0
  (cd "$1" 2>/dev/null && find . -type f -exec sha256sum {} + | sort) || sha256sum "$1"
}

# expect_error NAME EXPECTED_SUBSTRING OUTPUT_PATH -- ARGS...
# OUTPUT_PATH must not exist afterwards, or must be unchanged if it existed before.
expect_error() {
  local name="$1" want="$2" out="$3"
  shift 4
  cases=$((cases + 1))
  local before
  before="$(fingerprint "$out")"
  local existed=0
  [ -e "$out" ] && existed=1
  "$bin" "$@" >"$tmp/stdout" 2>"$tmp/stderr" </dev/null
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
  elif [ "$existed" -eq 0 ] && [ -e "$out" ]; then
    echo "FAIL $name: output $out written despite the error"
    fail=1
  elif [ "$existed" -eq 1 ] && [ "$before" != "$(fingerprint "$out")" ]; then
    echo "FAIL $name: existing output $out changed despite the error"
    fail=1
  else
    echo "ok   $name: $err"
  fi
}

skip() {
  skipped=$((skipped + 1))
  echo "skip $1: $2"
}

# mutate NAME PYTHON_STATEMENTS: writes $tmp/NAME.json from the good scenario (as d).
mutate() {
  python3 - "$good" "$tmp/$1.json" "$2" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(d, open(sys.argv[2], "w"))
PY
}

# run_error NAME EXPECTED: `ambisim run $tmp/NAME.json` must fail and write nothing.
run_error() {
  expect_error "$1" "$2" "$tmp/out_$1" -- run "$tmp/$1.json" --planner constant --out "$tmp/out_$1"
}

# ---------------------------------------------------------------- scenario files (`run`)
printf '' >"$tmp/empty.json"
printf ' \n\t\n' >"$tmp/blank.json"
printf '{"world": ' >"$tmp/broken.json"
printf '{"world": {}, "camera": {"speed_mps": 3,}}' >"$tmp/trailing_comma.json"
head -c 64 /dev/urandom >"$tmp/garbage.json" 2>/dev/null || printf '\x00\x01\xff' >"$tmp/garbage.json"
printf '\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR' >"$tmp/binary.json"
printf '[1, 2, 3]' >"$tmp/top_array.json"
printf '{"world": {"seed": 1e999}}' >"$tmp/overflow.json"

mutate unknown_top 'd["colour"] = "red"'
mutate unknown_key 'd["camera"]["sped_mps"] = 3'
mutate unknown_depth3 'd["world"]["terrain"] = {"amplitde_m": 100}'
mutate unknown_depth4 'del d["camera"]["speed_mps"]; d["camera"]["speed_profile"] = [{"time_s": 0, "speed_mps": 20, "spede": 1}]'
mutate unknown_traffic 'd["receivers"]["traffic"]["max_alive"] = 6'
mutate negative_speed 'd["camera"]["speed_mps"] = -3'
mutate wrong_type 'd["frames"]["fps"] = "sixty"'
mutate world_not_object 'd["world"] = 5'
mutate size_wrong_type 'd["world"]["size_m"] = "big"'
mutate face_fraction 'd["budget"]["face_size"] = 16.5'
mutate missing_camera 'del d["camera"]'
mutate missing_frames 'del d["frames"]'
mutate missing_points 'd["camera"] = {"type": "keyframes", "speed_mps": 5}'
mutate zero_size 'd["world"]["size_m"] = [0, 512]'
mutate huge_world 'd["world"]["size_m"] = [1e9, 1e9]'
mutate too_many_cells 'd["world"]["size_m"] = [16384, 16384]; d["world"]["cell_m"] = 1'
mutate zero_cell 'd["world"]["cell_m"] = 0'
mutate canopy_inverted 'd["world"]["terrain"] = {"canopy_min_m": 20, "canopy_max_m": 10}'
mutate huge_colour 'd["world"]["sky"] = {"model": "gradient", "zenith": [1e300, 1, 1]}'
mutate zero_fps 'd["frames"]["fps"] = 0'
mutate negative_fps 'd["frames"]["fps"] = -30'
mutate huge_fps 'd["frames"]["fps"] = 1e9'
mutate zero_duration 'd["frames"]["duration_s"] = 0'
mutate huge_duration 'd["frames"]["duration_s"] = 1e12'
mutate too_many_frames 'd["frames"]["duration_s"] = 3600; d["frames"]["fps"] = 1000'
mutate huge_face 'd["budget"]["face_size"] = 1000000'
mutate zero_face 'd["budget"]["face_size"] = 0'
mutate bad_budget 'd["budget"]["faces_per_frame"] = -1'
mutate huge_budget 'd["budget"]["faces_per_frame"] = 1e9'
mutate huge_reference_face 'd["reference"]["face_size"] = 1000000'
mutate huge_traffic_rate 'd["receivers"]["traffic"]["rate_per_s"] = 1e9'
mutate huge_max_live 'd["receivers"]["traffic"]["max_live"] = 1000000000'
mutate crowd_unknown_key 'd["receivers"]["crowd"] = {"centre": [0, 0, 0], "cout": 20}'
mutate crowd_huge 'd["receivers"]["crowd"] = {"centre": [0, 0, 0], "count": 20000}'
mutate crowd_no_centre 'd["receivers"]["crowd"] = {"count": 20}'
mutate sample_stride_zero 'd["reference"]["sample_stride"] = 0'
mutate negative_seed 'd["receivers"]["seed"] = -5'
mutate same_points 'd["camera"] = {"points": [[10, 10, 50], [10, 10, 50]], "speed_mps": 5}'
mutate huge_point 'd["camera"] = {"points": [[-1e300, 10, 50], [1e300, 10, 50]], "speed_mps": 5}'
mutate tiny_cut_period 'd["camera"]["periodic_cut"] = {"every_s": 1e-9, "jump_ahead_m": 50}'
mutate road_disabled 'd["world"]["road"]["enabled"] = False; del d["receivers"]["traffic"]'
mutate traffic_without_road 'd["world"]["road"]["enabled"] = False; d["camera"] = {"points": [[10, 10, 50], [100, 100, 50]], "speed_mps": 5}'
mutate start_beyond_road 'd["camera"]["start_arc_length_m"] = 1e9'
# Lighting that changes: the sun's path, the sky, clouds, lamps and height fog.
mutate sun_no_such_day 'd["world"]["sun"] = {"path": dict({"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}, date="2026-02-30")}'
mutate sun_date_format 'd["world"]["sun"] = {"path": dict({"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}, date="21/06/2026")}'
mutate sun_latitude 'd["world"]["sun"] = {"path": dict({"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}, latitude_deg=91)}'
mutate sun_longitude 'd["world"]["sun"] = {"path": dict({"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}, longitude_deg=-200)}'
mutate sun_utc_offset 'd["world"]["sun"] = {"path": dict({"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}, utc_offset_h=20)}'
mutate sun_start_hour 'd["world"]["sun"] = {"path": dict({"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}, start="25:00")}'
mutate sun_time_scale 'd["world"]["sun"] = {"path": dict({"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}, time_scale=-1)}'
mutate sun_path_type 'd["world"]["sun"] = {"path": {"type": "lunar"}}'
mutate sun_path_and_fixed 'd["world"]["sun"] = {"elevation_deg": 30, "path": {"type": "solar", "date": "2026-06-21", "latitude_deg": 57.7, "longitude_deg": 12, "start": "12:00"}}'
mutate sun_keys_order 'd["world"]["sun"] = {"path": {"type": "keyframes", "keys": [{"time_s": 10, "elevation_deg": 10, "azimuth_deg": 100}, {"time_s": 5, "elevation_deg": 5, "azimuth_deg": 100}]}}'
mutate sun_key_elevation 'd["world"]["sun"] = {"path": {"type": "keyframes", "keys": [{"time_s": 0, "elevation_deg": 100, "azimuth_deg": 100}]}}'
mutate sun_keys_empty 'd["world"]["sun"] = {"path": {"type": "keyframes", "keys": []}}'
mutate sun_colour_preetham 'd["world"]["sky"] = {"model": "preetham"}; d["world"]["sun"] = {"colour": [1, 0.9, 0.8]}'
mutate sky_model 'd["world"]["sky"] = {"model": "hosek"}'
mutate sky_turbidity 'd["world"]["sky"] = {"model": "preetham", "turbidity": 50}'
mutate sky_turbidity_gradient 'd["world"]["sky"] = {"model": "gradient", "turbidity": 3}'
mutate sky_zenith_preetham 'd["world"]["sky"] = {"zenith": [0.2, 0.4, 1]}'
mutate cloud_coverage 'd["world"]["clouds"] = {"coverage": 1.5}'
mutate cloud_scale 'd["world"]["clouds"] = {"scale_m": 0}'
mutate cloud_softness 'd["world"]["clouds"] = {"softness": -0.1}'
mutate cloud_wind 'd["world"]["clouds"] = {"wind_mps": 1e9}'
mutate cloud_opacity 'd["world"]["clouds"] = {"opacity": 2}'
mutate cloud_key 'd["world"]["clouds"] = {"coverge": 0.4}'
mutate lamp_spacing 'd["world"]["lamps"] = {"spacing_m": 0}'
mutate lamp_cone 'd["world"]["lamps"] = {"cone_deg": 95}'
mutate lamp_intensity 'd["world"]["lamps"] = {"intensity_kcd": -3}'
mutate lamp_colour 'd["world"]["lamps"] = {"colour": [1, -1, 1]}'
mutate lamp_schedule_order 'd["world"]["lamps"] = {"schedule": [{"time_s": 5, "on": True}, {"time_s": 2, "on": False}]}'
mutate lamp_schedule_type 'd["world"]["lamps"] = {"schedule": [{"time_s": 5, "on": "yes"}]}'
mutate lamp_schedule_and_photocell 'd["world"]["lamps"] = {"schedule": [{"time_s": 5, "on": True}], "on_below_elevation_deg": 2}'
mutate lamps_without_road 'd["world"]["road"]["enabled"] = False; d["camera"] = {"points": [[10, 10, 50], [100, 100, 50]], "speed_mps": 5}; del d["receivers"]["traffic"]; d["world"]["lamps"] = {}'
mutate fog_keys_order 'd["world"]["fog"] = {"height": {"keys": [{"time_s": 10, "density_per_m": 0.01, "base_m": 0}, {"time_s": 5, "density_per_m": 0.01, "base_m": 0}]}}'
mutate fog_density 'd["world"]["fog"] = {"height": {"density_per_m": -0.01}}'
mutate fog_falloff 'd["world"]["fog"] = {"height": {"falloff_m": 0, "density_per_m": 0.01}}'
mutate fog_keys_empty 'd["world"]["fog"] = {"height": {"keys": []}}'
mutate fog_keys_and_density 'd["world"]["fog"] = {"height": {"keys": [{"time_s": 0, "density_per_m": 0.01, "base_m": 0}], "density_per_m": 0.02}}'

expect_error missing "nope.json: no such file" "$tmp/out_missing" -- run "$tmp/nope.json" --out "$tmp/out_missing"
expect_error directory "is a directory" "$tmp/out_directory" -- run "$tmp" --out "$tmp/out_directory"
run_error empty "empty.json: is empty"
run_error blank "blank.json: is empty"
run_error broken "broken.json: invalid JSON at line 1"
run_error trailing_comma "trailing_comma.json: invalid JSON at line 1, column 41"
run_error garbage "garbage.json: "
run_error binary "binary.json: invalid JSON at line 1, column 1"
run_error top_array "top_array.json: /: must be an object, got array"
run_error overflow "overflow.json: invalid JSON: number overflow"
run_error unknown_top "unknown_top.json: /colour: unknown key; valid keys:"
run_error unknown_key "unknown_key.json: /camera/sped_mps: unknown key"
run_error unknown_depth3 "unknown_depth3.json: /world/terrain/amplitde_m: unknown key"
run_error unknown_depth4 "unknown_depth4.json: /camera/speed_profile/0/spede: unknown key"
run_error unknown_traffic "/receivers/traffic/max_alive: unknown key"
run_error negative_speed "/camera/speed_mps: must be >= 0, got -3"
run_error wrong_type "/frames/fps: must be a number, got string"
run_error world_not_object "/world: must be an object, got number"
run_error size_wrong_type "/world/size_m: must be an array of 2 numbers"
run_error face_fraction "/budget/face_size: must be an integer"
run_error missing_camera "/camera: required object is missing"
run_error missing_frames "/frames: required object is missing"
run_error missing_points "/camera/points: required array"
run_error zero_size "/world/size_m/0: must be >= 16, got 0"
run_error huge_world "/world/size_m/0: must be <= 65536, got 1000000000"
run_error too_many_cells "/world/cell_m: too small for size_m: at most 67108864"
run_error zero_cell "/world/cell_m: must be >= 0.05, got 0"
run_error canopy_inverted "/world/terrain/canopy_max_m: must be >= canopy_min_m"
run_error huge_colour "/world/sky/zenith/0: must be <= 1000000"
run_error sun_no_such_day "sun_no_such_day.json: /world/sun/path/date: no such day: 2026-02-30"
run_error sun_date_format "sun_date_format.json: /world/sun/path/date: must be a date \"YYYY-MM-DD\""
run_error sun_latitude "sun_latitude.json: /world/sun/path/latitude_deg: must be <= 90"
run_error sun_longitude "sun_longitude.json: /world/sun/path/longitude_deg: must be >= -180"
run_error sun_utc_offset "sun_utc_offset.json: /world/sun/path/utc_offset_h: must be <= 14"
run_error sun_start_hour "sun_start_hour.json: /world/sun/path/start: must be a local time"
run_error sun_time_scale "sun_time_scale.json: /world/sun/path/time_scale: must be >= 0"
run_error sun_path_type "sun_path_type.json: /world/sun/path/type: unknown value \"lunar\"; valid: solar, keyframes"
run_error sun_path_and_fixed "sun_path_and_fixed.json: /world/sun/path: give either a path or a fixed"
run_error sun_keys_order "sun_keys_order.json: /world/sun/path/keys/1/time_s: must be greater than the previous"
run_error sun_key_elevation "sun_key_elevation.json: /world/sun/path/keys/0/elevation_deg: must be <= 90"
run_error sun_keys_empty "sun_keys_empty.json: /world/sun/path/keys: needs at least one key"
run_error sun_colour_preetham "sun_colour_preetham.json: /world/sun/colour: only the gradient sky"
run_error sky_model "sky_model.json: /world/sky/model: unknown value \"hosek\"; valid: preetham, gradient"
run_error sky_turbidity "sky_turbidity.json: /world/sky/turbidity: must be <= 10"
run_error sky_turbidity_gradient "sky_turbidity_gradient.json: /world/sky/turbidity: only the Preetham sky"
run_error sky_zenith_preetham "sky_zenith_preetham.json: /world/sky/zenith: only the gradient sky"
run_error cloud_coverage "cloud_coverage.json: /world/clouds/coverage: must be <= 1"
run_error cloud_scale "cloud_scale.json: /world/clouds/scale_m: must be >= 10"
run_error cloud_softness "cloud_softness.json: /world/clouds/softness: must be >= 0.01"
run_error cloud_wind "cloud_wind.json: /world/clouds/wind_mps: must be <= 200"
run_error cloud_opacity "cloud_opacity.json: /world/clouds/opacity: must be <= 1"
run_error cloud_key "cloud_key.json: /world/clouds/coverge: unknown key; valid keys:"
run_error lamp_spacing "lamp_spacing.json: /world/lamps/spacing_m: must be >= 2"
run_error lamp_cone "lamp_cone.json: /world/lamps/cone_deg: must be <= 90"
run_error lamp_intensity "lamp_intensity.json: /world/lamps/intensity_kcd: must be >= 0"
run_error lamp_colour "lamp_colour.json: /world/lamps/colour/1: must be >= 0"
run_error lamp_schedule_order "lamp_schedule_order.json: /world/lamps/schedule/1/time_s: must be greater than the previous"
run_error lamp_schedule_type "lamp_schedule_type.json: /world/lamps/schedule/0/on: must be true or false"
run_error lamp_schedule_and_photocell "lamp_schedule_and_photocell.json: /world/lamps/schedule: give either a schedule or on_below_elevation_deg"
run_error lamps_without_road "lamps_without_road.json: /world/lamps: street lamps stand along the road"
run_error fog_keys_order "fog_keys_order.json: /world/fog/height/keys/1/time_s: must be greater than the previous"
run_error fog_density "fog_density.json: /world/fog/height/density_per_m: must be >= 0"
run_error fog_falloff "fog_falloff.json: /world/fog/height/falloff_m: must be >= 0.1"
run_error fog_keys_empty "fog_keys_empty.json: /world/fog/height/keys: needs at least one key"
run_error fog_keys_and_density "fog_keys_and_density.json: /world/fog/height/keys: give either keys or one density_per_m"
run_error zero_fps "/frames/fps: must be > 0, got 0"
run_error negative_fps "/frames/fps: must be > 0, got -30"
run_error huge_fps "/frames/fps: must be <= 10000, got 1000000000"
run_error zero_duration "/frames/duration_s: must be > 0, got 0"
run_error huge_duration "/frames/duration_s: must be <= 86400, got 1e+12"
run_error too_many_frames "/frames/duration_s: gives 3600000 frames at this frame rate; at most 1000000"
run_error huge_face "/budget/face_size: must be <= 1024, got 1000000"
run_error zero_face "/budget/face_size: must be >= 1, got 0"
run_error bad_budget "/budget/faces_per_frame: must be >= 0, got -1"
run_error huge_budget "/budget/faces_per_frame: must be <= 96"
run_error huge_reference_face "/reference/face_size: must be <= 256"
run_error huge_traffic_rate "/receivers/traffic/rate_per_s: must be <= 10000"
run_error huge_max_live "/receivers/traffic/max_live: must be <= 10000"
run_error crowd_unknown_key "/receivers/crowd/cout: unknown key"
run_error crowd_huge "/receivers/crowd/count: must be <= 10000"
run_error crowd_no_centre "/receivers/crowd/centre"
run_error sample_stride_zero "/reference/sample_stride: must be >= 1"
run_error negative_seed "/receivers/seed: must be a non-negative integer, got -5"
run_error same_points "/camera/points: needs at least 2 distinct points"
run_error huge_point "/camera/points/0/0: must be in [-1e10, 1e10] m"
run_error tiny_cut_period "/camera/periodic_cut/every_s: must be >= 0.01"
run_error road_disabled "road_disabled.json: /camera/type: \"road\" needs the world's road"
run_error traffic_without_road "traffic_without_road.json: /receivers/traffic: needs the world's road"
run_error start_beyond_road "start_beyond_road.json: /camera/start_arc_length_m: is beyond the end of the road"

# ---------------------------------------------------------------- recorded telemetry (CSV next to the scenario)
# recorded NAME CAMERA_CSV [RECEIVERS_CSV]: $tmp/NAME.json replays $tmp/NAME.csv (and the
# receivers in $tmp/NAME.cars.csv); printf-style escapes in the texts.
recorded() {
  printf "$2" >"$tmp/$1.csv"
  local cars=""
  if [ $# -ge 3 ]; then
    printf "$3" >"$tmp/$1.cars.csv"
    cars="d['receivers']['recorded'] = {'file': '$1.cars.csv'}"
  fi
  mutate "$1" "d['camera'] = {'type': 'recorded', 'file': '$1.csv'}; $cars"
}
rec_ok='time,x,y,z\n0,100,200,90\n1,110,200,90\n'
recorded rec_empty ''
recorded rec_header_only 'time,x,y,z\n'
recorded rec_no_header '0,100,200,90\n1,110,200,90\n'
recorded rec_missing_column 'time,x,y\n0,100,200\n'
recorded rec_unknown_column 'time,x,y,z,speed\n0,100,200,90,3\n'
recorded rec_not_number 'time,x,y,z\n0,100,200,90\n1,110,abc,90\n'
recorded rec_non_monotonic 'time,x,y,z\n0,100,200,90\n1,110,200,90\n1,120,200,90\n'
recorded rec_bad_cut 'time,x,y,z,cut\n0,100,200,90,0\n1,110,200,90,yes\n'
recorded rec_field_count 'time,x,y,z\n0,100,200,90\n1,110,200\n'
recorded rec_half_velocity 'time,x,y,z,vx\n0,100,200,90,1\n'
recorded rec_cars_missing_id "$rec_ok" 'time,x,y,z\n0,100,200,90\n'
recorded rec_cars_non_monotonic "$rec_ok" 'id,time,x,y,z\nbus,0,100,200,90\nvan,0,1,2,3\nbus,0,101,200,90\n'
recorded rec_cars_empty "$rec_ok" ''
recorded rec_speed_key "$rec_ok"
mutate rec_speed_key 'd["camera"] = {"type": "recorded", "file": "rec_speed_key.csv", "speed_mps": 3}'
recorded rec_cars_size "$rec_ok" 'id,time,x,y,z\nbus,0,100,200,90\n'
mutate rec_cars_size 'd["camera"] = {"type": "recorded", "file": "rec_cars_size.csv"}; d["receivers"]["recorded"] = {"file": "rec_cars_size.cars.csv", "size_m": 0}'
mutate rec_missing_file 'd["camera"] = {"type": "recorded", "file": "nope.csv"}'
mutate rec_directory 'd["camera"] = {"type": "recorded", "file": "."}'
run_error rec_missing_file "rec_missing_file.json: /camera/file: no such file: $tmp/nope.csv"
run_error rec_directory "rec_directory.json: /camera/file: is a directory, not a CSV file"
run_error rec_empty "rec_empty.csv: is empty; expected a header line time,x,y,z[,cut][,vx,vy,vz] and samples"
run_error rec_header_only "rec_header_only.csv: line 1: a header and no samples"
run_error rec_no_header "rec_no_header.csv: line 1: expected a header line time,x,y,z[,cut][,vx,vy,vz], got numbers"
run_error rec_missing_column "rec_missing_column.csv: line 1: missing column 'z'"
run_error rec_unknown_column "rec_unknown_column.csv: line 1: unknown column 'speed'; valid columns: time, x, y, z, cut, vx, vy, vz"
run_error rec_not_number "rec_not_number.csv: line 3: y: not a number: 'abc'"
run_error rec_non_monotonic "rec_non_monotonic.csv: line 4: time 1 is not after the previous sample's 1"
run_error rec_bad_cut "rec_bad_cut.csv: line 3: cut: not a number: 'yes'"
run_error rec_field_count "rec_field_count.csv: line 3: has 3 fields, the header has 4"
run_error rec_half_velocity "rec_half_velocity.csv: line 1: missing column 'vy'; a velocity needs all of vx, vy, vz"
run_error rec_cars_missing_id "rec_cars_missing_id.cars.csv: line 1: missing column 'id'"
run_error rec_cars_non_monotonic "rec_cars_non_monotonic.cars.csv: line 4: time 0 is not after the previous sample's 0 of id bus"
run_error rec_cars_empty "rec_cars_empty.cars.csv: is empty; expected a header line id,time,x,y,z[,vx,vy,vz]"
run_error rec_speed_key "rec_speed_key.json: /camera/speed_mps: unknown key; valid keys: file, type, view"
run_error rec_cars_size "rec_cars_size.json: /receivers/recorded/size_m: must be > 0, got 0"
mutate rec_good 'd["camera"] = {"type": "recorded", "file": "rec_good.csv"}'
printf "$rec_ok" >"$tmp/rec_good.csv"
printf '{"scenarios": ["rec_good.json"], "planners": ["constant"], "speed_scales": [1, 2]}' >"$tmp/rec_speed_scales.sweep.json"
expect_error rec_sweep_speed_scales "rec_speed_scales.sweep.json: /speed_scales: small_drive has a recorded camera: its speed cannot be scaled" "$tmp/sout_rec_speed_scales" -- sweep "$tmp/rec_speed_scales.sweep.json" --out "$tmp/sout_rec_speed_scales" -j1
expect_error record_camera_no_dir "nodir/flight.csv: directory does not exist" "$tmp/out_record_no_dir" -- run "$good" --planner constant --out "$tmp/out_record_no_dir" --record-camera "$tmp/nodir/flight.csv"
printf 'keep me\n' >"$tmp/kept_flight.csv"
expect_error record_camera_exists "kept_flight.csv: already exists (use --force" "$tmp/kept_flight.csv" -- run "$good" --planner constant --out "$tmp/out_record_exists" --record-camera "$tmp/kept_flight.csv"

# ---------------------------------------------------------------- planners and the command line
expect_error unknown_planner "valid planners: oracle" "$tmp/out_unknown_planner" -- run "$good" --planner octopus --out "$tmp/out_unknown_planner"
expect_error unknown_param "valid parameters" "$tmp/out_unknown_param" -- run "$good" --planner nearest --set spacing=3 --out "$tmp/out_unknown_param"
expect_error bad_param "must be a number > 0" "$tmp/out_bad_param" -- run "$good" --planner nearest --set spacing_m=-1 --out "$tmp/out_bad_param"
expect_error unknown_preset "--preset: unknown preset \"tunde\"; valid presets: tuned" "$tmp/out_unknown_preset" -- run "$good" --planner nearest --preset tunde --out "$tmp/out_unknown_preset"
expect_error set_without_value "--set spacing_m: expected key=value" "$tmp/out_set_without_value" -- run "$good" --planner nearest --set spacing_m --out "$tmp/out_set_without_value"
expect_error missing_out "--out is required" "$tmp/out_missing_out" -- run "$good"

# ---------------------------------------------------------------- output paths
long="$(printf 'a%.0s' $(seq 1 300))"  # longer than a file name may be (255)
printf 'x' >"$tmp/a_file"
expect_error out_name_too_long "cannot be used as the output directory: File name too long" "$tmp/out_name_too_long" -- run "$good" --planner constant --out "$tmp/$long"
expect_error out_is_file "a_file: exists and is not a directory" "$tmp/a_file" -- run "$good" --planner constant --out "$tmp/a_file"
expect_error out_under_file "cannot be created: $tmp/a_file is not a directory" "$tmp/a_file" -- run "$good" --planner constant --out "$tmp/a_file/sub"
if [ "$as_root" -eq 1 ]; then
  skip unreadable "running as root: chmod 000 does not stop root from reading"
  skip unwritable_out "running as root: chmod 555 does not stop root from writing"
else
  cp "$good" "$tmp/unreadable.json" && chmod 000 "$tmp/unreadable.json"
  run_error unreadable "unreadable.json: cannot be opened for reading"
  mkdir -p "$tmp/locked" && chmod 555 "$tmp/locked"
  expect_error unwritable_out "is not writable" "$tmp/locked/out" -- run "$good" --planner constant --out "$tmp/locked/out"
fi
# A finished run: the same output directory again is refused, byte for byte unchanged.
"$bin" run "$good" --planner constant --out "$tmp/done" --quiet >/dev/null 2>&1 || { echo "FAIL setup: run"; fail=1; }
expect_error used_out_dir "result.json: already exists (use --force" "$tmp/done" -- run "$good" --planner nearest --out "$tmp/done"

# ---------------------------------------------------------------- sweep files
# sweep_file NAME JSON: writes $tmp/NAME.sweep.json ($good is "SCEN").
sweep_file() { printf '%s' "${2//SCEN/$good}" >"$tmp/$1.sweep.json"; }
sweep_error() {
  expect_error "sweep_$1" "$2" "$tmp/sout_$1" -- sweep "$tmp/$1.sweep.json" --out "$tmp/sout_$1" -j1
}
sweep_file empty ''
sweep_file broken '{"scenarios": ["SCEN"], "planners": ["constant"'
head -c 48 /dev/urandom >"$tmp/garbage.sweep.json" 2>/dev/null || printf '\xff\xfe' >"$tmp/garbage.sweep.json"
sweep_file unknown_top '{"scenarios": ["SCEN"], "planners": ["constant"], "budget": [1]}'
sweep_file unknown_in_planner '{"scenarios": ["SCEN"], "planners": [{"name": "nearest", "parms": {}}]}'
sweep_file unknown_planner '{"scenarios": ["SCEN"], "planners": ["constant", "octopus"]}'
sweep_file unknown_param '{"scenarios": ["SCEN"], "planners": [{"name": "nearest", "params": {"spacing": 3}}]}'
sweep_file bad_param '{"scenarios": ["SCEN"], "planners": [{"name": "nearest", "params": {"spacing_m": -1}}]}'
sweep_file unknown_preset '{"scenarios": ["SCEN"], "planners": [{"name": "nearest", "preset": "tunde"}]}'
sweep_file params_not_object '{"scenarios": ["SCEN"], "planners": [{"name": "nearest", "params": [1]}]}'
sweep_file no_scenarios '{"planners": ["constant"]}'
sweep_file missing_scenario '{"scenarios": ["nope.json"], "planners": ["constant"]}'
sweep_file scenario_not_string '{"scenarios": [42], "planners": ["constant"]}'
sweep_file empty_planners '{"scenarios": ["SCEN"], "planners": []}'
sweep_file duplicate_label '{"scenarios": ["SCEN"], "planners": ["nearest", "nearest"]}'
sweep_file negative_budget '{"scenarios": ["SCEN"], "planners": ["constant"], "budgets": [1, -2]}'
sweep_file budgets_not_array '{"scenarios": ["SCEN"], "planners": ["constant"], "budgets": 1}'
sweep_file empty_budgets '{"scenarios": ["SCEN"], "planners": ["constant"], "budgets": []}'
sweep_file huge_fps '{"scenarios": ["SCEN"], "planners": ["constant"], "fps": [1e9]}'
sweep_file huge_duration '{"scenarios": ["SCEN"], "planners": ["constant"], "duration_s": 1e12}'
sweep_file too_many_frames '{"scenarios": ["SCEN"], "planners": ["constant"], "fps": [30, 5000], "duration_s": 3600}'
sweep_file fractional_seed '{"scenarios": ["SCEN"], "planners": ["constant"], "seeds": [1.5]}'
sweep_file override_unknown '{"scenarios": ["SCEN"], "planners": ["constant"], "overrides": {"/camera/sped_mps": 3}}'
sweep_file override_out_of_range '{"scenarios": ["SCEN"], "planners": ["constant"], "overrides": {"/budget/face_size": 1000000}}'
sweep_file override_through_number '{"scenarios": ["SCEN"], "planners": ["constant"], "overrides": {"/world/seed/x": 1}}'
sweep_file long_scenario_path "{\"scenarios\": [\"$long.json\"], \"planners\": [\"constant\"]}"
sweep_file label_with_slash '{"scenarios": ["SCEN"], "planners": [{"name": "constant", "label": "../../escape"}]}'
sweep_file name_with_slash '{"scenarios": ["SCEN"], "planners": ["constant"], "overrides": {"/name": "../../escape"}}'
sweep_file beyond_road '{"scenarios": ["SCEN"], "planners": ["constant"], "overrides": {"/camera/start_arc_length_m": 1e9}}'

expect_error sweep_missing "nope.sweep.json: no such file" "$tmp/sout_missing" -- sweep "$tmp/nope.sweep.json" --out "$tmp/sout_missing"
expect_error sweep_directory "is a directory" "$tmp/sout_directory" -- sweep "$tmp" --out "$tmp/sout_directory"
sweep_error empty "empty.sweep.json: is empty"
sweep_error broken "broken.sweep.json: invalid JSON at line 1"
sweep_error garbage "garbage.sweep.json: "
sweep_error unknown_top "unknown_top.sweep.json: /budget: unknown key"
sweep_error unknown_in_planner "unknown_in_planner.sweep.json: /planners/0/parms: unknown key"
sweep_error unknown_planner "unknown_planner.sweep.json: /planners/1: unknown planner \"octopus\"; valid planners: oracle"
sweep_error unknown_param "unknown_param.sweep.json: /planners/0/params/spacing"
sweep_error bad_param "bad_param.sweep.json: /planners/0/params/spacing_m"
sweep_error unknown_preset "unknown_preset.sweep.json: /planners/0/preset: unknown preset \"tunde\"; valid presets: tuned"
sweep_error params_not_object "params_not_object.sweep.json: /planners/0/params: must be an object"
sweep_error no_scenarios "no_scenarios.sweep.json: /scenarios: required list of scenario files is missing"
sweep_error missing_scenario "missing_scenario.sweep.json: /scenarios/0: no such file"
sweep_error scenario_not_string "scenario_not_string.sweep.json: /scenarios/0: must be a file path string"
sweep_error empty_planners "empty_planners.sweep.json: /planners: must be a non-empty array"
sweep_error duplicate_label "duplicate_label.sweep.json: /planners/1: duplicate planner label"
sweep_error negative_budget "negative_budget.sweep.json: /budgets/1: must be >= 0, got -2"
sweep_error budgets_not_array "budgets_not_array.sweep.json: /budgets: must be an array of numbers"
sweep_error empty_budgets "empty_budgets.sweep.json: /budgets: must not be empty"
sweep_error huge_fps "huge_fps.sweep.json: /fps/0: must be <= 10000"
sweep_error huge_duration "huge_duration.sweep.json: /duration_s: must be <= 86400"
sweep_error too_many_frames "too_many_frames.sweep.json: /duration_s: with fps 5000 gives 18000000 frames"
sweep_error fractional_seed "fractional_seed.sweep.json: /seeds: seeds must be whole numbers"
sweep_error override_unknown "small_drive.json: /camera/sped_mps: unknown key"
sweep_error override_out_of_range "small_drive.json: /budget/face_size: must be <= 1024"
sweep_error override_through_number "override_through_number.sweep.json: /world/seed: is not an object"
sweep_error long_scenario_path "long_scenario_path.sweep.json: /scenarios/0: no such file"
sweep_error label_with_slash "label_with_slash.sweep.json: /planners/0/label: must be 1..100 characters without '/'"
sweep_error name_with_slash "small_drive.json: /name: names the run directories"
sweep_error beyond_road "small_drive.json: /camera/start_arc_length_m: is beyond the end of the road"
sweep_file tiny '{"scenarios": ["SCEN"], "planners": ["constant"], "duration_s": 0.5}'
expect_error sweep_bad_shard "--shard: expects K/N" "$tmp/sout_bad_shard" -- sweep "$tmp/tiny.sweep.json" --out "$tmp/sout_bad_shard" --shard 3/2
expect_error sweep_bad_jobs "--jobs" "$tmp/sout_bad_jobs" -- sweep "$tmp/tiny.sweep.json" --out "$tmp/sout_bad_jobs" -j 0
expect_error sweep_out_under_file "a_file" "$tmp/a_file" -- sweep "$tmp/tiny.sweep.json" --out "$tmp/a_file/sub"
if [ "$as_root" -eq 1 ]; then
  skip sweep_unwritable_out "running as root: chmod 555 does not stop root from writing"
else
  expect_error sweep_unwritable_out "cannot create output directory" "$tmp/locked/sweep" -- sweep "$tmp/tiny.sweep.json" --out "$tmp/locked/sweep"
fi
# A finished sweep: running it again into the same directory is refused, unchanged.
"$bin" sweep "$tmp/tiny.sweep.json" --out "$tmp/swept" -j1 >/dev/null 2>&1 || { echo "FAIL setup: sweep"; fail=1; }
expect_error sweep_used_out_dir "result.json: already exists (use --resume" "$tmp/swept" -- sweep "$tmp/tiny.sweep.json" --out "$tmp/swept" -j1

# ---------------------------------------------------------------- imported levels (images next to the scenario)
# The shipped level and its flyover, copied; each case breaks one file or key.
mkdir -p "$tmp/lv/levels"
cp -r "$src/scenarios/levels/lakeside" "$tmp/lv/levels/"
level_case() {
  python3 - "$src/scenarios/level_flyover.json" "$tmp/lv/$1.json" "$2" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
L = d["world"]["level"]
exec(sys.argv[3])
json.dump(d, open(sys.argv[2], "w"))
PY
}
level_error() {
  expect_error "level_$1" "$2" "$tmp/lout_$1" -- run "$tmp/lv/$1.json" --planner constant --out "$tmp/lout_$1"
}
lv="$tmp/lv/levels/lakeside"
printf 'this is not a png\n' >"$lv/text.png"
head -c 3000 "$lv/height.png" >"$lv/truncated.png"
head -c 1000 /dev/zero >"$lv/short.raw"
# A 32 x 32 level: images of another size than the lakeside's 256 x 256.
mkdir -p "$tmp/lv/levels/small"
"$bin" world "$good" --export-level "$tmp/lv/levels/small" --region 0,0,64,64 >/dev/null 2>&1 ||
  { echo "FAIL setup: world --export-level"; fail=1; }
level_case ok ''
"$bin" run "$tmp/lv/ok.json" --planner constant --out "$tmp/lout_ok" >/dev/null 2>&1 ||
  { echo "FAIL setup: the copied level does not run"; fail=1; }
level_case missing 'L["heightmap"] = "levels/lakeside/nope.png"'
level_error missing "missing.json: /world/level/heightmap: no such file: $tmp/lv/levels/lakeside/nope.png"
level_case not_png 'L["albedo"] = "levels/lakeside/text.png"'
level_error not_png "not_png.json: /world/level/albedo: $tmp/lv/levels/lakeside/text.png: not a PNG file"
level_case eight_bit 'L["heightmap"] = "levels/lakeside/water.png"'
level_error eight_bit "eight_bit.json: /world/level/heightmap: $tmp/lv/levels/lakeside/water.png: 8-bit: a heightmap must be 16-bit greyscale"
level_case sizes 'L["canopy"] = "levels/small/canopy.png"'
level_error sizes "sizes.json: /world/level/canopy: $tmp/lv/levels/small/canopy.png: 32 x 32 pixels, but the heightmap is 256 x 256"
level_case truncated 'L["heightmap"] = "levels/lakeside/truncated.png"'
level_error truncated "truncated.json: /world/level/heightmap: $tmp/lv/levels/lakeside/truncated.png: corrupt or truncated PNG"
level_case raw_count 'L["heightmap"] = "levels/lakeside/short.raw"; L["heightmap_size"] = [256, 256]'
level_error raw_count "raw_count.json: /world/level/heightmap: $tmp/lv/levels/lakeside/short.raw: 1000 bytes, but a 256 x 256 RAW 16-bit heightmap has 131072"
level_case raw_no_size 'L["heightmap"] = "levels/lakeside/short.raw"'
level_error raw_no_size "raw_no_size.json: /world/level/heightmap: $tmp/lv/levels/lakeside/short.raw: a RAW heightmap needs /heightmap_size"
level_case unknown_key 'L["albdo"] = L.pop("albedo")'
level_error unknown_key "unknown_key.json: /world/level/albdo: unknown key"
level_case zero_cell 'L["cell_m"] = 0'
level_error zero_cell "zero_cell.json: /world/level/cell_m: must be > 0"
level_case negative_cell 'L["cell_m"] = -4'
level_error negative_cell "negative_cell.json: /world/level/cell_m: must be > 0"
level_case no_scale 'del L["height_scale_m"]'
level_error no_scale "no_scale.json: /world/level/height_scale_m: required number is missing"
level_case canopy_scale_alone 'del L["canopy"]'
level_error canopy_scale_alone "canopy_scale_alone.json: /world/level/canopy_scale_m: only with a canopy map"
level_case with_size 'd["world"]["size_m"] = [1024, 1024]'
level_error with_size "with_size.json: /world/size_m: not with an imported level"
level_case with_terrain 'd["world"]["terrain"] = {"amplitude_m": 10}'
level_error with_terrain "with_terrain.json: /world/terrain: not with an imported level"
level_case with_road 'd["world"]["road"] = {"enabled": True}'
level_error with_road "with_road.json: /world/road: an imported level (/world/level) has no road"
level_case road_camera 'd["camera"] = {"type": "road", "speed_mps": 30}'
level_error road_camera "road_camera.json: /camera/type: \"road\" needs the world's road (an imported level (/world/level) has no road)"
level_case traffic 'd["receivers"]["traffic"] = {"rate_per_s": 5}'
level_error traffic "traffic.json: /receivers/traffic: needs the world's road (an imported level (/world/level) has no road)"
level_case lamps 'd["world"]["lamps"] = {"enabled": True}'
level_error lamps "lamps.json: /world/lamps: street lamps stand along the road: an imported level (/world/level) has none"
level_case road_landmark 'd["camera"]["points"][0] = {"landmark": "road.deepest_cutting", "offset": [0, 0, 50]}'
level_error road_landmark "road_landmark.json: /camera/points/0"
expect_error level_export_not_dir "--export-level: not a directory" "$tmp/nolevel" -- world "$good" --export-level "$tmp/nolevel"
mkdir -p "$tmp/lvx"
expect_error level_export_region "--region/--stride: the region must be a non-empty part of the world's grid" "$tmp/lvx" -- world "$good" --export-level "$tmp/lvx" --region 0,0,1e6,64
expect_error level_export_existing "height.png: already exists (use --force" "$tmp/lv/levels/small" -- world "$good" --export-level "$tmp/lv/levels/small" --region 0,0,64,64

# ---------------------------------------------------------------- world and probe
world_only() { printf '%s' "$2" >"$tmp/$1.world.json"; }
world_only bad_world_key '{"world": {"terrain": {"roughnes": 0.5}}}'
world_only no_world '{"camera": {}}'
world_only huge_world '{"world": {"size_m": [1e9, 1e9]}}'
expect_error world_unknown_key "bad_world_key.world.json: /world/terrain/roughnes: unknown key" "$tmp/w1.png" -- world "$tmp/bad_world_key.world.json" --png "$tmp/w1.png"
expect_error world_missing_section "no_world.world.json: /world: required object is missing" "$tmp/w2.png" -- world "$tmp/no_world.world.json" --png "$tmp/w2.png"
expect_error world_huge "huge_world.world.json: /world/size_m/0: must be <= 65536" "$tmp/w3.png" -- world "$tmp/huge_world.world.json" --png "$tmp/w3.png"
expect_error world_garbage "garbage.json: " "$tmp/w4.png" -- world "$tmp/garbage.json" --png "$tmp/w4.png"
expect_error world_missing_dir "nodir/w.png: directory does not exist" "$tmp/nodir" -- world "$good" --png "$tmp/nodir/w.png"
expect_error world_bad_size "--size" "$tmp/w5.png" -- world "$good" --png "$tmp/w5.png" --size 100000
printf 'not a png' >"$tmp/existing.png"
mkdir -p "$tmp/pngdir" && cp "$tmp/existing.png" "$tmp/pngdir/"
expect_error world_existing_png "existing.png: already exists (use --force" "$tmp/pngdir" -- world "$good" --png "$tmp/pngdir/existing.png"
expect_error probe_unknown_key "bad_world_key.world.json: /world/terrain/roughnes: unknown key" "$tmp/c1.png" -- probe "$tmp/bad_world_key.world.json" --at 10,10,2 --cube "$tmp/c1.png"
expect_error probe_nan "--at: coordinates must be finite" "$tmp/c2.png" -- probe "$good" --at nan,10,2 --cube "$tmp/c2.png"
expect_error probe_huge "--at: coordinates must be finite and within" "$tmp/c3.png" -- probe "$good" --at 1e300,10,2 --cube "$tmp/c3.png"
expect_error probe_two_coords "--at: expects X,Y,Z" "$tmp/c4.png" -- probe "$good" --at 10,10 --cube "$tmp/c4.png"
expect_error probe_zero_size "--size" "$tmp/c5.png" -- probe "$good" --at 10,10,2 --size 0 --cube "$tmp/c5.png"
expect_error probe_existing_cube "existing.png: already exists (use --force" "$tmp/pngdir" -- probe "$good" --at 10,10,2 --cube "$tmp/pngdir/existing.png"

# ---------------------------------------------------------------- plot and viz
expect_error plot_not_dir "a_file: not a directory" "$tmp/a_file" -- plot "$tmp/a_file"
expect_error plot_not_sweep "summary.csv: missing: not a sweep output directory" "$tmp/pngdir" -- plot "$tmp/pngdir"
expect_error viz_not_dir "a_file: not a directory" "$tmp/a_file" -- viz "$tmp/a_file"
expect_error viz_not_run "views.json: missing: not a run output directory" "$tmp/pngdir" -- viz "$tmp/pngdir"
run_dir="$(ls -d "$tmp"/swept/runs/*/ 2>/dev/null | head -1)"
if [ -n "$run_dir" ] && "$bin" plot "$tmp/swept" >/dev/null 2>&1; then
  expect_error plot_unknown_run "unknown run id 'nope'" "$tmp/swept" -- plot "$tmp/swept" --run nope --force
  expect_error plot_existing_charts "already exists (use --force" "$tmp/swept" -- plot "$tmp/swept"
else
  echo "FAIL setup: plot of a finished sweep"
  fail=1
fi
expect_error compare_not_dir "a_file: not a directory" "$tmp/a_file" -- compare "$tmp/a_file" --baseline constant
expect_error compare_not_sweep "summary.csv: missing: not a sweep output directory" "$tmp/pngdir" -- compare "$tmp/pngdir" --baseline constant
if [ -f "$tmp/swept/summary.csv" ]; then
  expect_error compare_unknown_baseline "no planner \"nope\" in the sweep; planners:" "$tmp/cmp.csv" -- compare "$tmp/swept" --baseline nope --csv "$tmp/cmp.csv"
  expect_error compare_unknown_metric "no metric column \"error.p95\"; valid metrics:" "$tmp/cmp.csv" -- compare "$tmp/swept" --baseline constant --metric error.p95 --csv "$tmp/cmp.csv"
  printf 'keep me\n' >"$tmp/kept.csv"
  expect_error compare_existing_csv "kept.csv: already exists (use --force" "$tmp/kept.csv" -- compare "$tmp/swept" --baseline constant --csv "$tmp/kept.csv"
fi
if [ -n "$run_dir" ] && "$bin" viz "${run_dir%/}" --frames 0 >/dev/null 2>&1; then
  expect_error viz_existing_views "already exists (use --force" "$tmp/swept" -- viz "${run_dir%/}" --frames 0
else
  echo "FAIL setup: viz of a finished run"
  fail=1
fi

# ---------------------------------------------------------------- film
expect_error film_not_dir "a_file: is not a run directory" "$tmp/film.mp4" -- film "$tmp/a_file" --out "$tmp/film.mp4"
expect_error film_not_run "result.json: missing" "$tmp/film.mp4" -- film "$tmp/pngdir" --out "$tmp/film.mp4"
if "$bin" run "$good" --planner constant --out "$tmp/film_a" --quiet >/dev/null 2>&1; then
  expect_error film_after_end "the time range 1.000..99.000 s is not inside the run (0..2.000 s)" "$tmp/film.mp4" -- film "$tmp/film_a" --out "$tmp/film.mp4" --from 1 --to 99
  expect_error film_empty_range "the time range 1.500..1.000 s is not inside the run" "$tmp/film.mp4" -- film "$tmp/film_a" --out "$tmp/film.mp4" --from 1.5 --to 1
  expect_error film_odd_size "--size: must be WxH, even" "$tmp/film.mp4" -- film "$tmp/film_a" --out "$tmp/film.mp4" --size 161x90
  expect_error film_bad_fps "--fps: must be 1..240, got 0" "$tmp/film.mp4" -- film "$tmp/film_a" --out "$tmp/film.mp4" --fps 0
  printf 'keep me\n' >"$tmp/kept.mp4"
  expect_error film_existing "kept.mp4: already exists (use --force" "$tmp/kept.mp4" -- film "$tmp/film_a" --out "$tmp/kept.mp4"
  mutate film_other_world 'd["world"]["seed"] = 4'
  if "$bin" run "$tmp/film_other_world.json" --planner constant --out "$tmp/film_b" --quiet >/dev/null 2>&1; then
    expect_error film_other_scenario "a run of another scenario" "$tmp/film.mp4" -- film "$tmp/film_a" "$tmp/film_b" --out "$tmp/film.mp4"
  else
    echo "FAIL setup: run of another world for film"
    fail=1
  fi
  # A result the re-run does not reproduce is refused, not filmed.
  mkdir -p "$tmp/film_edited" && cp "$tmp/film_a"/* "$tmp/film_edited/"
  python3 -c 'import json,sys; p=sys.argv[1]; d=json.load(open(p)); d["summary"]["frames"] += 1; json.dump(d, open(p, "w"))' "$tmp/film_edited/result.json"
  expect_error film_not_reproduced "the re-run does not reproduce this result" "$tmp/film.mp4" -- film "$tmp/film_edited" --out "$tmp/film.mp4"
else
  echo "FAIL setup: run for film"
  fail=1
fi

echo "$cases cases, $skipped skipped"
exit $fail
