#!/bin/sh
# Runs a test program against a real SocketCAN stack with a vcan0 interface.
#   run_in_uml.sh [--candump LOGFILE] PROGRAM [ARGS...]
# If this kernel already has vcan0 (or can create it), PROGRAM runs directly. Otherwise Debian's
# user-mode Linux (package user-mode-linux) boots this machine's own file system through hostfs,
# loads can, can-raw, can-dev and vcan, creates vcan0 (MTU 72 for CAN FD) and runs PROGRAM there.
# Exit status: PROGRAM's, or 2 if user-mode Linux could not run it. With --candump, can-utils'
# candump records vcan0 in its log format (-L) to LOGFILE while PROGRAM runs.
set -u
candump_log=""
if [ "${1:-}" = "--candump" ]; then candump_log=$2; shift 2; fi
[ $# -ge 1 ] || { echo "usage: $0 [--candump LOG] PROGRAM [ARGS...]" >&2; exit 2; }
program=$(readlink -f "$1"); shift

# 1. A kernel with CAN: run directly (creating vcan0 needs root and the vcan module).
if ip link show vcan0 >/dev/null 2>&1 || { ip link add dev vcan0 type vcan 2>/dev/null && ip link set vcan0 mtu 72 && ip link set up vcan0; }; then
  echo "run_in_uml: vcan0 available on this kernel, running directly"
  VESICA_REQUIRE_CAN=1 exec "$program" "$@"
fi

# 2. User-mode Linux.
uml=$(command -v linux.uml) || { echo "run_in_uml: linux.uml not found (apt-get install user-mode-linux)" >&2; exit 2; }
moddir=$(ls -d /usr/lib/uml/modules/*/kernel 2>/dev/null | head -n1)
[ -n "$moddir" ] || { echo "run_in_uml: no modules under /usr/lib/uml/modules" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/vesica-uml.XXXXXX")
trap 'rm -rf "$work"' EXIT
status_file="$work/status"
log="$work/output.log"

# Arguments are passed through a file, one per line, so spaces survive.
: > "$work/args"
for a in "$@"; do printf '%s\n' "$a" >> "$work/args"; done

cat > "$work/init" <<INIT
#!/bin/sh
export PATH=/usr/sbin:/usr/bin:/sbin:/bin
export HOME=/tmp CI=\${CI:-true} VESICA_CAN_INTERFACE=vcan0 VESICA_REQUIRE_CAN=1
mount -t proc proc /proc 2>/dev/null
mount -t sysfs sys /sys 2>/dev/null
# insmod from kmod when installed; otherwise finit_module(2) through python3 (x86-64 syscall 313).
load_module() {
  if command -v insmod >/dev/null 2>&1; then insmod "\$1"; else
    python3 -c 'import ctypes,os,sys; fd=os.open(sys.argv[1],os.O_RDONLY); libc=ctypes.CDLL(None,use_errno=True); r=libc.syscall(313,fd,b"",0); sys.exit(0 if r==0 else ctypes.get_errno())' "\$1"
  fi
}
for m in net/can/can.ko net/can/can-raw.ko net/can/can-bcm.ko drivers/net/can/dev/can-dev.ko drivers/net/can/vcan.ko; do
  load_module $moddir/\$m >>$log 2>&1 || echo "insmod \$m failed" >> $log
done
ip link add dev vcan0 type vcan >> $log 2>&1
ip link set vcan0 mtu 72 >> $log 2>&1
ip link set up vcan0 >> $log 2>&1
ip link set up lo >> $log 2>&1
if [ -n "$candump_log" ] && command -v candump >/dev/null 2>&1; then
  candump -L vcan0 > "$candump_log" 2>>$log &
  dump_pid=\$!
  sleep 0.2
fi
set --
while IFS= read -r a; do set -- "\$@" "\$a"; done < $work/args
cd "$(pwd)"
"$program" "\$@" >> $log 2>&1
echo \$? > $status_file
[ -n "\${dump_pid:-}" ] && { sleep 0.2; kill \$dump_pid 2>/dev/null; }
sync
poweroff -f
INIT
chmod +x "$work/init"

# VESICA_UML_PRELOAD: tests/uml/xstate_shim.cpp's library (CTest sets it), which lets this UML
# restore floating-point state on hosts with a larger XSAVE area (AMX) than it was built for.
preload=""
if [ -n "${VESICA_UML_PRELOAD:-}" ]; then
  [ -r "$VESICA_UML_PRELOAD" ] || { echo "run_in_uml: VESICA_UML_PRELOAD=$VESICA_UML_PRELOAD not readable" >&2; exit 2; }
  preload=$VESICA_UML_PRELOAD
fi
if [ -n "$preload" ]; then set -- env LD_PRELOAD="$preload" "$uml"; else set -- "$uml"; fi
timeout 300 "$@" mem=256M root=/dev/root rootfstype=hostfs rootflags=/ rw \
  init="$work/init" con=null con0=fd:0,fd:1 < /dev/null > "$work/uml-console.log" 2>&1
cat "$log" 2>/dev/null; [ -n "${VESICA_UML_VERBOSE:-}" ] && cat "$work/uml-console.log"
if [ ! -s "$status_file" ]; then
  echo "run_in_uml: user-mode Linux did not report an exit status; console:" >&2
  tail -n 30 "$work/uml-console.log" >&2
  exit 2
fi
exit "$(cat "$status_file")"
