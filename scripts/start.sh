#!/usr/bin/env bash
# README command 1: set up, build, and start the trainer in the default scenario with simulated
# (keyboard/mouse) instruments. Extra arguments go to vesica-trainer (see --help).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
. "$here/scripts/openblas_env.sh"
"$here/scripts/setup.sh" release
exec "$here/build/release/app/trainer/vesica-trainer" "$@"
