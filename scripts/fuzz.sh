#!/usr/bin/env bash
# Fuzzes the scenario and sweep parsers and the level loader (PNG/RAW images) with libFuzzer (ASan + UBSan) for MINUTES each.
# Usage: scripts/fuzz.sh [MINUTES]   (default 10 per target)
# Installs clang-14 if missing, configures build-fuzz/ with CC=clang-14 CXX=clang++-14
# -DAMBISIM_FUZZ=ON, seeds from tests/fuzz/corpus/<target>/ (committed; never written) and
# keeps what the fuzzer finds in build-fuzz/corpus/<target>/. A crash, a sanitizer report or
# an exception other than ambisim::InputError stops the target and leaves the input in
# build-fuzz/artifacts/; the script then fails. Reproduce with build-fuzz/tests/fuzz/TARGET FILE.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
minutes="${1:-10}"
seconds=$((minutes * 60))
build="$AMBISIM_ROOT/build-fuzz"

# Not in the default package list: only fuzzing needs clang and its runtime libraries.
ambisim_install_packages cmake ninja-build pkg-config libglm-dev libeigen3-dev \
  nlohmann-json3-dev libpng-dev clang-14 libclang-rt-14-dev

CC=clang-14 CXX=clang++-14 cmake -S "$AMBISIM_ROOT" -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAMBISIM_FUZZ=ON -DAMBISIM_WITH_VIZ=OFF \
  -DAMBISIM_WITH_BENCH=OFF -DBUILD_TESTING=OFF >/dev/null
cmake --build "$build" -j "${AMBISIM_FUZZ_BUILD_JOBS:-$(nproc 2>/dev/null || echo 2)}" \
  --target fuzz_scenario fuzz_sweep fuzz_level

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}"
status=0
for target in fuzz_scenario fuzz_sweep fuzz_level; do
  corpus="$build/corpus/$target"
  mkdir -p "$corpus" "$build/artifacts"
  echo "== $target: $minutes min" >&2
  # The JSON dictionary helps the parsers; the level target reads binary images.
  dict=(-dict="$AMBISIM_ROOT/tests/fuzz/json.dict")
  max_len=4096
  if [ "$target" = fuzz_level ]; then
    dict=()
    max_len=16384
  fi
  if ! "$build/tests/fuzz/$target" "$corpus" "$AMBISIM_ROOT/tests/fuzz/corpus/${target#fuzz_}" \
    "${dict[@]}" -max_total_time="$seconds" -max_len="$max_len" \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$target-" 2>"$build/$target.log"; then
    status=1
    echo "FINDING in $target: see $build/$target.log and $build/artifacts/" >&2
  fi
  grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' \
    "$build/$target.log" >&2 || true
  tail -n 3 "$build/$target.log" | grep -E 'cov:|Done' >&2 || true
done
exit $status
