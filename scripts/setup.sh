#!/usr/bin/env bash
# Installs what is missing (Debian 12 packages listed in scripts/deps.txt), then configures and
# builds the given CMake preset (default: release). Safe to run again: it installs nothing twice.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
preset=${1:-release}

mapfile -t wanted < <(grep -v '^\s*#' "$here/scripts/deps.txt" | sed '/^\s*$/d')
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} missing package(s): ${missing[*]}"
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cd "$here"
# ccache keys on paths relative to the checkout, so a fresh clone elsewhere (CI's) reuses the
# objects an earlier build on this machine cached.
export CCACHE_BASEDIR="$here"
jobs=$(nproc)
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$jobs"
