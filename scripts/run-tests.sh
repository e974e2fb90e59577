#!/usr/bin/env bash
# README command 2: installs the dependencies, builds, and runs every test: the native suite through ctest
# (unit, integration, install/consume), then the cross builds (aarch64 and armhf unit tests under
# qemu-user, Cortex-M no-heap link) and the SocketCAN/GPIO tests in qemu VMs with Debian's kernels.
# JACOBID_SKIP_EMULATED=1 runs the native suite only (a quick local run).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
ctest --test-dir "${JACOBID_BUILD_DIR:-$root/build}" -j "$(nproc)" --output-on-failure --timeout 600
if [ "${JACOBID_SKIP_EMULATED:-0}" != "1" ]; then
  step=$(date +%s)
  bash "$root/scripts/cross-test.sh"
  echo "run-tests: cross-test finished in $(( $(date +%s) - step )) s"
  step=$(date +%s)
  bash "$root/scripts/vm-test.sh"
  echo "run-tests: vm-test finished in $(( $(date +%s) - step )) s"
fi
