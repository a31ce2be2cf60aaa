#!/bin/sh
# Builds the libFuzzer target for the codec and node logic with clang++ and runs it for a bounded
# time on the committed corpus (read-only; new inputs go to a temporary directory).
#   run_fuzz.sh BUILD_DIR [SECONDS]       exit 0: no crash; 1: crash (reproducer in BUILD_DIR)
set -eu
build=$1
seconds=${2:-20}
src=$(cd "$(dirname "$0")/../../.." && pwd)
out="$build/can_fuzz"
mkdir -p "$out"
clang++ -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I"$src" \
  "$src/tests/can/fuzz/codec_node_fuzz.cpp" \
  "$src/firmware_protocol/codec/codec.cpp" \
  "$src/firmware_protocol/codec/frame_timing.cpp" \
  "$src/firmware_protocol/node/parameter_store.cpp" \
  -o "$out/codec_node_fuzz"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cd "$out"
./codec_node_fuzz -max_total_time="$seconds" -max_len=512 -timeout=10 -rss_limit_mb=1024 \
  -print_final_stats=1 "$scratch" "$src/tests/can/fuzz/corpus"
