#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the vcan tests directly on this machine (ctest: vcan.host). Needs Linux with the vcan module and
# root (CAP_NET_ADMIN). Creates two vcan interfaces of its own, jcan0 (classic CAN, MTU 16) and
# jcanfd0 (CAN FD, MTU 72), runs the test binary on them and deletes them again.
# Exits 77 (ctest: skipped) when they cannot be created: no vcan/CAN in the kernel (this CI machine:
# socket(PF_CAN) fails with EAFNOSUPPORT), or not root. scripts/vm-test.sh runs the same tests in a VM.
#   tests/vm/run-on-host.sh build/tests/vm/jacobid-vcan-link build/tests/vm/test_hal_vcan [gtest args]
set -uo pipefail
link="$1"; test_bin="$2"; shift 2
classic="${JACOBID_HOST_VCAN:-jcan0}"
fd="${JACOBID_HOST_VCANFD:-jcanfd0}"
if [ "$(id -u)" -ne 0 ]; then
  echo "vcan.host: SKIPPED: creating vcan interfaces needs root (or run scripts/vm-test.sh)"
  exit 77
fi
modprobe -q vcan 2>/dev/null || true
modprobe -q can-raw 2>/dev/null || true
# The usual reason on CI machines and containers: a kernel built without CONFIG_CAN (no /proc/net/can
# even after modprobe; socket(PF_CAN) fails with EAFNOSUPPORT). Say so rather than a generic failure.
if [ ! -d /proc/net/can ]; then
  if [ -d "/lib/modules/$(uname -r)" ]; then modules="modules in /lib/modules/$(uname -r), none loads 'can'"
  else modules="no /lib/modules/$(uname -r) to load can/vcan from"; fi
  echo "vcan.host: SKIPPED: kernel $(uname -r) has no SocketCAN (no /proc/net/can; $modules): socket(PF_CAN) fails with EAFNOSUPPORT"
  echo "vcan.host: run the same tests in a VM with Debian's kernel: scripts/vm-test.sh"
  exit 77
fi
created=()
cleanup() { for i in "${created[@]}"; do "$link" del "$i" >/dev/null 2>&1 || true; done; }
trap cleanup EXIT
for spec in "$classic:16" "$fd:72"; do
  name="${spec%%:*}" mtu="${spec##*:}"
  [ -e "/sys/class/net/$name" ] && "$link" del "$name" >/dev/null 2>&1  # left over from an interrupted run
  if ! out="$("$link" add "$name" --mtu "$mtu" 2>&1)"; then
    echo "vcan.host: SKIPPED: cannot create a vcan interface here ($out); kernel $(uname -r)"
    echo "vcan.host: run the same tests in a VM with Debian's kernel: scripts/vm-test.sh"
    exit 77
  fi
  created+=("$name")
done
echo "vcan.host: running on $classic and $fd (kernel $(uname -r))"
JACOBID_VCAN="$classic" JACOBID_VCANFD="$fd" "$test_bin" "$@"
