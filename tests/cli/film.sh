#!/usr/bin/env bash
# `ambisim film`: ffprobe reads the MP4 with the expected size, frame count and duration; the
# contact sheet lies beside it; no temporary file is left; the same runs give the same bytes.
# Runs under Xvfb (ctest is). Usage: film.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
scen="$src/tests/data/small_drive.json"
fail() { echo "FAIL $*"; exit 1; }
command -v ffprobe >/dev/null || fail "ffprobe missing (Debian package ffmpeg; scripts/setup.sh installs it)"

"$bin" run "$scen" --planner ambisim --out "$tmp/a" --quiet || fail "run ambisim"
"$bin" run "$scen" --planner nearest --out "$tmp/n" --quiet || fail "run nearest"
# Two runs and the truth: 3 panels of 160 x 90; 0.5..2 s at 20 fps = 30 frames, 1.5 s.
"$bin" film "$tmp/a" "$tmp/n" --out "$tmp/f.mp4" --from 0.5 --to 2 --size 160x90 --fps 20 \
  >/dev/null || fail "film"
[ -s "$tmp/f_contact.png" ] || fail "no contact sheet beside the film"
probe() {
  ffprobe -v error -select_streams v:0 -count_frames \
    -show_entries "stream=$1" -of default=noprint_wrappers=1:nokey=1 "$tmp/f.mp4"
}
[ "$(probe codec_name)" = "h264" ] || fail "codec $(probe codec_name), expected h264"
[ "$(probe width)" = "480" ] || fail "width $(probe width), expected 480"
[ "$(probe height)" = "90" ] || fail "height $(probe height), expected 90"
[ "$(probe pix_fmt)" = "yuv420p" ] || fail "pix_fmt $(probe pix_fmt), expected yuv420p"
[ "$(probe nb_read_frames)" = "30" ] || fail "frames $(probe nb_read_frames), expected 30"
[ "$(probe r_frame_rate)" = "20/1" ] || fail "rate $(probe r_frame_rate), expected 20/1"
duration="$(probe duration)"
python3 -c "import sys; d = float(sys.argv[1]); sys.exit(0 if abs(d - 1.5) < 1e-3 else 1)" \
  "$duration" || fail "duration $duration, expected 1.5"
leftovers="$(find "$tmp" -name '*.tmp.*')"
[ -z "$leftovers" ] || fail "temporary files left: $leftovers"

# Deterministic: the same runs give a byte-identical film and contact sheet.
"$bin" film "$tmp/a" "$tmp/n" --out "$tmp/g.mp4" --from 0.5 --to 2 --size 160x90 --fps 20 \
  >/dev/null || fail "second film"
cmp -s "$tmp/f.mp4" "$tmp/g.mp4" || fail "the same runs gave different films"
cmp -s "$tmp/f_contact.png" "$tmp/g_contact.png" || fail "the same runs gave different sheets"

# An existing film is kept without --force and replaced with it.
before="$(sha256sum "$tmp/f.mp4")"
"$bin" film "$tmp/a" --out "$tmp/f.mp4" --size 160x90 >/dev/null 2>"$tmp/err"
[ "$?" -eq 2 ] || fail "existing film: expected exit 2"
[ "$before" = "$(sha256sum "$tmp/f.mp4")" ] || fail "existing film changed without --force"
"$bin" film "$tmp/a" --out "$tmp/f.mp4" --size 160x90 --force >/dev/null || fail "--force"
[ "$(probe width)" = "320" ] || fail "--force did not replace the film"
echo "ok: film (ffprobe: h264 480x90 yuv420p, 30 frames at 20/1, ${duration} s; deterministic)"
