#!/usr/bin/env bash
# Installs what is missing, builds into build/, and runs every test (ctest). The VTK tests
# render, so the whole suite runs under a virtual X server.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
ambisim_setup
cd "$AMBISIM_BUILD"
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
