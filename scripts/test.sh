#!/usr/bin/env bash
# README command 2 (and .ci/run): set up, build, and run the whole test suite through CTest:
# the release build (all labels: mesh scenario app fem bem can), then the ASan+UBSan build of the
# unit tests that need no display (physics, firmware_protocol, device).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
. "$here/scripts/openblas_env.sh"
cd "$here"
start=$(date +%s)
"$here/scripts/setup.sh" release
ctest --preset release -j "$(nproc)"
"$here/scripts/setup.sh" asan
ctest --preset asan -j "$(nproc)"
echo "test.sh: all suites passed in $(( $(date +%s) - start )) s"
