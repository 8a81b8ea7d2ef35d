#!/usr/bin/env bash
# Runs a command inside a QEMU guest with real kernel CAN and exits with its exit code. The
# guest is Debian's kernel under TCG emulation (guest_image.sh builds it into the build tree),
# its root is the host's root over 9p, and our init (guest_init.cpp) brings up lo and the vcan
# interfaces first. The guest's /run and /dev/shm are its own tmpfs, and its TMPDIR is
# /run/tmp; everything else, the build tree and /tmp included, is the host's (a build tree may
# well be under /tmp). The command's output and the guest's console go to
# standard output as they come, and the runner says where the time went: boot, the command,
# power-off.
#
#   tests/socketcan/qemu_run.sh [--guest DIR] [--can vcan0,vcan1] [--time-limit S] COMMAND [ARG...]
# --guest       the guest image (default: build/socketcan-guest of this source tree)
# --can         the vcan interfaces to bring up (default vcan0)
# --time-limit  seconds (default 840, under ctest's 900): past it the guest is stopped and the
#               runner says how far it got; exit code 2, as for every failure of its own
# QEMU_ACCEL    the emulation (default tcg; kvm boots only where it is shown to, not here:
#               docs/decisions.md 30)
set -euo pipefail

source_dir=$(cd "$(dirname "$0")/../.." && pwd)
guest=$source_dir/build/socketcan-guest
buses=vcan0
limit=840
while [ $# -gt 0 ]; do
  case $1 in
    --guest) guest=$2; shift 2 ;;
    --can) buses=$2; shift 2 ;;
    --time-limit) limit=$2; shift 2 ;;
    --) shift; break ;;
    *) break ;;
  esac
done
[[ $limit =~ ^[1-9][0-9]*$ ]] || { echo "qemu_run: --time-limit takes whole seconds, not '$limit'" >&2; exit 2; }
[ $# -gt 0 ] || { echo "usage: qemu_run.sh [--guest DIR] [--can LIST] [--time-limit S] COMMAND [ARG...]" >&2; exit 2; }

say() { echo "qemu_run: $*" >&2; }
[ -d "$guest" ] || { say "no kernel CAN: no guest image in $guest (built with the tests)"; exit 2; }
guest=$(cd "$guest" && pwd)  # the guest sees the host's root: absolute paths only
# The work folder's path goes on the kernel command line, which splits at white space.
[[ $guest != *[[:space:]]* ]] || { say "the guest image's path may not hold white space: $guest"; exit 2; }
[[ $buses =~ ^[a-z0-9]+(,[a-z0-9]+)*$ ]] || { say "--can takes interface names separated by commas, not '$buses'"; exit 2; }
if [ -f "$guest/missing" ]; then
  say "no kernel CAN: $(cat "$guest/missing")"
  exit 2
fi
for f in vmlinuz initrd.img; do
  [ -f "$guest/$f" ] || { say "no kernel CAN: $guest/$f is missing (built with the tests)"; exit 2; }
done
qemu=$(command -v qemu-system-x86_64 || true)
[ -n "$qemu" ] || { say "no kernel CAN: qemu-system-x86_64 not found (package qemu-system-x86)"; exit 2; }

work=$(mktemp -d "$guest/run-XXXXXX")
qemu_pid=
# No guest outlives the runner: timeout leads a process group of its own with QEMU in it.
cleanup() {
  if [ -n "$qemu_pid" ] && kill -0 "$qemu_pid" 2>/dev/null; then
    kill -KILL -- "-$qemu_pid" 2>/dev/null || kill -KILL "$qemu_pid" 2>/dev/null || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT
trap 'say "stopped by a signal"; exit 2' INT TERM

# The command, as the caller would have run it here: its directory, its PATH and the
# variables of ours and of the DDS libraries.
{
  printf 'cd %q || exit 126\n' "$PWD"
  printf 'export PATH=%q\n' "$PATH"
  while IFS='=' read -r -d '' name value; do
    case $name in
      MCNC_*|FASTRTPS_*|FASTDDS_*|CYCLONEDDS_*|IOX_*|*SAN_OPTIONS|LANG|LC_*) printf 'export %s=%q\n' "$name" "$value" ;;
    esac
  done < <(env -0)
  printf 'exec'
  printf ' %q' "$@"
  printf '\n'
} > "$work/command"
# Made here, so that the guest only writes into it: with passthrough, a file the guest
# creates is given the guest's owner (root), which QEMU run by another user cannot do.
: > "$work/status"

# What our processes name their shared memory (Fast DDS, iceoryx): none may appear here.
ours() { ls -A /dev/shm 2>/dev/null | grep -E '^(fastrtps_|sem\.fastrtps_|fast_datasharing_|iox_)' | sort || true; }
shm_before=$(ours)
now() { echo "${EPOCHREALTIME/,/.}"; }
since() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
t_start=$(now)
t_command=
t_ended=
# The console line by line: the command's output, our init's lines, the kernel's errors.
exec 3< <(exec timeout --kill-after=5 "$limit" "$qemu" -accel "${QEMU_ACCEL:-tcg}" \
  -m 2048 -smp 2 -nodefaults -no-user-config -display none -serial stdio -no-reboot \
  -kernel "$guest/vmlinuz" -initrd "$guest/initrd.img" \
  -append "console=ttyS0 panic=-1 quiet rdinit=/init mcnc.work=$work mcnc.can=$buses" \
  -fsdev local,id=hostroot,path=/,security_model=passthrough,multidevs=remap \
  -device virtio-9p-pci,fsdev=hostroot,mount_tag=hostroot < /dev/null 2>&1)
qemu_pid=$!
while IFS= read -r line <&3 || [ -n "$line" ]; do
  line=${line%$'\r'}
  printf '%s\n' "$line"
  case $line in
    "mcnc-guest: up at "*) t_command=$(now) ;;
    "mcnc-guest: the command ended "*) t_ended=$(now) ;;
  esac
done
wait "$qemu_pid" 2>/dev/null && qemu_rc=0 || qemu_rc=$?
qemu_pid=
t_off=$(now)

if [ -n "$t_command" ]; then
  report="boot $(since "$t_start" "$t_command") s"
  if [ -n "$t_ended" ]; then
    report+=", the command $(since "$t_command" "$t_ended") s, power-off $(since "$t_ended" "$t_off") s"
  else
    report+=", the command $(since "$t_command" "$t_off") s and unfinished"
  fi
else
  report="no boot to the command in $(since "$t_start" "$t_off") s"
fi
say "$report (accel ${QEMU_ACCEL:-tcg})"

status=
[ -s "$work/status" ] && status=$(cat "$work/status")
elapsed=$(since "$t_start" "$t_off")
if [ "$qemu_rc" -eq 124 ] || { [ "$qemu_rc" -eq 137 ] && [ "${elapsed%.*}" -ge "$limit" ]; }; then
  say "the guest was stopped at the time limit of $limit s; its console is above"
  exit 2
fi
if [ -z "$status" ]; then
  if [ -z "$t_command" ]; then
    say "no kernel CAN: the guest did not come up (qemu exit $qemu_rc); its console is above"
  else
    say "the command left no exit code (qemu exit $qemu_rc); the guest's console is above"
  fi
  exit 2
fi

# Nothing of the guest's stays behind: its shared memory was its own tmpfs.
left=$(comm -13 <(printf '%s\n' "$shm_before") <(ours) || true)
if [ -n "$left" ]; then
  say "left behind in /dev/shm: $(echo $left)"
  exit 2
fi
exit "$status"
