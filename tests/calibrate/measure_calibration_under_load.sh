#!/usr/bin/env bash
# A calibration session over UDP under load (docs/protocol.md section 11, "Watchdog in a
# calibration session"): BUSY busy-loop processes (each ended by `timeout`), a minute for the
# 1-minute load average to climb, then RUNS whole-arm calibrations of vesica-armsim --random-arm
# SEED.. in real time, one after the other.
# PRIO > 0 runs the tool and vesica-armsim (its child) at SCHED_FIFO priority PRIO (chrt).
#   tests/calibrate/measure_calibration_under_load.sh BUILD_DIR [RUNS=3] [BUSY=8] [LOSS_MS=1000] [SEED=1] [PRIO=0]
set -eu
build=${1:?usage: $0 BUILD_DIR [RUNS] [BUSY] [LOSS_MS] [SEED] [PRIO]}
runs=${2:-3}
busy=${3:-8}
loss_ms=${4:-1000}
seed=${5:-1}
prio=${6:-0}
tool=$build/tests/calibrate/calibration_under_load
armsim=$build/app/armsim/vesica-armsim
[ -x "$tool" ] && [ -x "$armsim" ] || { echo "build calibration_under_load and vesica-armsim in $build first" >&2; exit 2; }
pids=()
for _ in $(seq "$busy"); do
  timeout $((runs * 150 + 75)) sh -c 'while :; do :; done' &
  pids+=($!)
done
trap 'kill "${pids[@]}" 2>/dev/null || true' EXIT
[ "$busy" -gt 0 ] && sleep 60
echo "cores $(nproc), load average before: $(cut -d' ' -f1-3 /proc/loadavg), busy loops $busy, SCHED_FIFO priority $prio"
rt=()
[ "$prio" -gt 0 ] && rt=(chrt -f "$prio")
status=0
for k in $(seq 0 $((runs - 1))); do
  echo "--- run $((k + 1)): seed $((seed + k))"
  "${rt[@]}" "$tool" "$armsim" $((seed + k)) "$loss_ms" || status=1
done
exit $status
