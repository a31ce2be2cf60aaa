#!/usr/bin/env bash
# The arm link under load (docs/protocol.md, "Link timing on a loaded host"): BUSY busy-loop
# processes (each ended by `timeout`), a minute for the 1-minute load average to climb, then two
# vesica-armsim processes and one 1 kHz bridge thread over loopback for SECONDS.
#   tests/device/measure_link_under_load.sh BUILD_DIR [SECONDS=60] [BUSY=8] [LOSS_MS=100] [WATCHDOG_MS=60]
set -eu
build=${1:?usage: $0 BUILD_DIR [SECONDS] [BUSY] [LOSS_MS] [WATCHDOG_MS]}
seconds=${2:-60}
busy=${3:-8}
loss_ms=${4:-100}
watchdog_ms=${5:-60}
tool=$build/tests/device/arm_link_under_load
armsim=$build/app/armsim/vesica-armsim
[ -x "$tool" ] && [ -x "$armsim" ] || { echo "build arm_link_under_load and vesica-armsim in $build first" >&2; exit 2; }
pids=()
for _ in $(seq "$busy"); do
  timeout $((seconds + 75)) sh -c 'while :; do :; done' &
  pids+=($!)
done
trap 'kill "${pids[@]}" 2>/dev/null || true' EXIT
[ "$busy" -gt 0 ] && sleep 60
echo "cores $(nproc), load average before: $(cut -d' ' -f1-3 /proc/loadavg), busy loops $busy"
"$tool" "$armsim" "$seconds" "$loss_ms" "$watchdog_ms"
