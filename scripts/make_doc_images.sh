#!/usr/bin/env bash
# Regenerates the laparoscope pictures in docs/images from the release build: the default
# scenario's first frame (default-view.png) and the committed dissection at 9 s, the hook at the
# membrane (mid-dissection.png); Calot's triangle's standard variant's first frame
# (calot-standard.png). Needs an X server: without a display it starts its own Xvfb.
#   ./scripts/make_doc_images.sh            (after ./scripts/setup.sh release)
#   VESICA_BUILD_DIR=build/other ./scripts/make_doc_images.sh   (another build of vesica-trainer and vesica-replay)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin="$(cd "$here" && realpath "${VESICA_BUILD_DIR:-build/release}")/app"
out="$here/docs/images"
x=()
[ -n "${DISPLAY:-}" ] || x=(xvfb-run -a -s "-screen 0 1280x720x24")
. "$here/scripts/openblas_env.sh"
"${x[@]}" "$bin/trainer/vesica-trainer" --headless --width 1280 --height 720 --screenshot "$out/default-view.png"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"${x[@]}" "$bin/replay/vesica-replay" "$here/data/recordings/dissection.csv" --png-dir "$tmp" --png-every-s 9 \
  --width 1280 --height 720 --progress none >/dev/null
cp "$tmp/frame_00001.png" "$out/mid-dissection.png"
echo "wrote $out/default-view.png and $out/mid-dissection.png"
# Calot's triangle (docs/calot.md): the standard variant's first frame, a one-row recording (the
# committed dissection's first input) replayed in data/scenarios/calot-standard.toml.
head -n 4 "$here/data/recordings/dissection.csv" >"$tmp/first-input.csv"
"${x[@]}" "$bin/replay/vesica-replay" -s "$here/data/scenarios/calot-standard.toml" "$tmp/first-input.csv" \
  --any-scenario --png-dir "$tmp/calot" --width 1280 --height 720 --progress none >/dev/null
cp "$tmp/calot/frame_00000.png" "$out/calot-standard.png"
echo "wrote $out/calot-standard.png"
