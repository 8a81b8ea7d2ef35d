#!/usr/bin/env bash
# Runs a command inside user-mode Linux with real kernel CAN: boots Debian's linux.uml on the
# host's root file system, loads can, can-raw, can-dev and vcan (kmod may be missing: the
# modules are loaded with finit_module), brings up vcan0 (and lo), runs the command there,
# and exits with its exit code; its output goes to standard output. The host kernel has no
# AF_CAN, so this is how the socketcan transport meets a real CAN stack in tests.
#
#   tests/socketcan/uml_run.sh COMMAND [ARG...]
# UML_TIME_LIMIT (seconds, default 840, under ctest's 900): past it, user-mode Linux is killed
# and what the command had printed so far is shown, so that a slow host says where it stood.
set -euo pipefail

uml=$(command -v linux.uml || true)
[ -n "$uml" ] || { echo "uml_run: linux.uml not found (package user-mode-linux)" >&2; exit 2; }
release=$(ls /usr/lib/uml/modules | head -1)
[ -n "$release" ] || { echo "uml_run: no modules in /usr/lib/uml/modules" >&2; exit 2; }

work=$(mktemp -d /tmp/mcnc-uml-XXXXXX)
trap 'rm -rf "$work"' EXIT
printf '%q ' "$@" > "$work/command"
cat > "$work/init" <<INIT
#!/bin/sh
export PATH=/usr/sbin:/usr/bin:/sbin:/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs devtmpfs /dev
mkdir -p /dev/shm && mount -t tmpfs tmpfs /dev/shm
python3 - <<'PY' > "$work/modules.log" 2>&1
import ctypes, os
libc = ctypes.CDLL(None, use_errno=True)
base = "/usr/lib/uml/modules/$release/kernel/"
for m in ["net/can/can.ko", "net/can/can-raw.ko", "drivers/net/can/dev/can-dev.ko",
          "drivers/net/can/vcan.ko"]:
    fd = os.open(base + m, os.O_RDONLY)
    if libc.syscall(313, fd, b"", 0) != 0 and ctypes.get_errno() != 17:  # finit_module, EEXIST
        print("cannot load", m, os.strerror(ctypes.get_errno()))
    os.close(fd)
PY
ip link set lo up
ip link add vcan0 type vcan && ip link set vcan0 up
cd "$PWD"
sh -c "\$(cat $work/command)" > "$work/output" 2>&1
echo \$? > "$work/status"
sync
echo o > /proc/sysrq-trigger
sleep 10
INIT
chmod +x "$work/init"

limit=${UML_TIME_LIMIT:-840}
started=$SECONDS
timeout --kill-after=10 "$limit" "$uml" mem=768M rootfstype=hostfs rootflags=/ rw \
  init="$work/init" con=null con0=fd:0,fd:1 quiet < /dev/null > "$work/console" 2>&1 || true
cat "$work/output" 2>/dev/null || true
if [ ! -s "$work/status" ]; then
  echo "uml_run: the command did not finish inside user-mode Linux" \
    "($((SECONDS - started)) s, limit $limit s)" >&2
  cat "$work/modules.log" "$work/console" >&2 2>/dev/null || true
  exit 2
fi
exit "$(cat "$work/status")"
