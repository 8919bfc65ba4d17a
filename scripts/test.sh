#!/usr/bin/env bash
# Installs what is missing and runs every test:
#  1. the unit tests built again in build-asan/ with AddressSanitizer + UndefinedBehaviorSanitizer
#     (no VTK, no benchmarks); any sanitizer report fails the script. Tests tagged [heavy] (each
#     reruns every planner over whole scenarios to compare results, 20-400 s under ASan) are left
#     to pass 2; the planner contract and the stress scenarios run in both. The three programs
#     run two at a time. AMBISIM_SANITIZER_PASS=0 skips this pass (e.g. for a quick local run);
#  2. the Release build in build/ and the whole suite through ctest, under a virtual X server
#     because the VTK tests render. ctest's summary is the last thing printed.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
# slurm-wlm and munge are for tests/cli/slurm.sh.
ambisim_install_packages "${AMBISIM_PACKAGES[@]}" "${AMBISIM_SLURM_PACKAGES[@]}"
# Wall time of each phase, printed before ctest (which prints its own total).
phase_start=$SECONDS
phases=()
phase_done() {
  phases+=("$1 $((SECONDS - phase_start)) s")
  phase_start=$SECONDS
}
ambisim_build "$AMBISIM_BUILD"
phase_done "Release build"
jobs="$(nproc 2>/dev/null || echo 2)"

if [ "${AMBISIM_SANITIZER_PASS:-1}" != "0" ]; then
  # -O1 keeps the sanitized tests fast enough; assertions stay on (no NDEBUG); -g1 (line tables)
  # is all a sanitizer's stack trace needs and compiles faster than full debug information.
  asan="$AMBISIM_ROOT/build-asan"
  cmake -S "$AMBISIM_ROOT" -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DAMBISIM_SANITIZE=ON -DAMBISIM_WITH_VIZ=OFF \
    -DAMBISIM_WITH_BENCH=OFF >/dev/null
  cmake --build "$asan" -j "$jobs" --target test_sim test_policies test_system
  phase_done "sanitizer build"
  # Leak checks on, explicitly, so that a restricted environment fails loudly.
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
  echo "sanitizer pass (ASan + UBSan): test_sim, test_policies, test_system, without [heavy]" >&2
  # Catch2 skips hidden tests ([.slow] and the like) unless asked for. Each program writes to
  # its own log, printed whole once it ends, so that the two running at once do not interleave.
  logs="$asan/sanitizer_logs"
  mkdir -p "$logs"
  run_sanitized() {
    local name
    for name in "$@"; do
      "$asan/tests/$name" "~[heavy]" >"$logs/$name.txt" 2>&1 || {
        cat "$logs/$name.txt"
        echo "sanitizer pass: $name failed" >&2
        return 1
      }
      cat "$logs/$name.txt"
    done
  }
  if [ "$jobs" -ge 2 ]; then
    run_sanitized test_policies &
    policies_pid=$!
    status=0
    run_sanitized test_sim test_system || status=1
    wait "$policies_pid" || status=1
    [ "$status" -eq 0 ] || exit 1
  else
    run_sanitized test_sim test_policies test_system
  fi
  unset ASAN_OPTIONS UBSAN_OPTIONS
  phase_done "sanitizer pass"
fi
printf -v phase_list '%s; ' "${phases[@]}"
echo "test.sh phases (wall): ${phase_list%; }" >&2

cd "$AMBISIM_BUILD"
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j "$jobs" "$@"
