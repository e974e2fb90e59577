#!/usr/bin/env bash
# README command 2: installs the dependencies, builds, and runs every test: the native suite through ctest
# (unit, integration, install/consume), then the cross builds (aarch64 and armhf unit tests under
# qemu-user, Cortex-M no-heap link) and the SocketCAN/GPIO tests in qemu VMs with Debian's kernels;
# in between, the sanitizer run and the fuzz targets.
# JACOBID_SKIP_EMULATED=1 runs the native suite only (a quick local run).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
step=$(date +%s)
"$root/scripts/build.sh"
echo "run-tests: native build finished in $(( $(date +%s) - step )) s"
step=$(date +%s)
ctest --test-dir "${JACOBID_BUILD_DIR:-$root/build}" -j "$(nproc)" --output-on-failure --timeout 600
echo "run-tests: native tests finished in $(( $(date +%s) - step )) s"
# Hardening (docs/reliability.md): the whole suite again under ASan + UBSan, then every parser's libFuzzer
# target for a short fixed time. JACOBID_SKIP_HARDENING=1 skips both (a quick local run).
if [ "${JACOBID_SKIP_HARDENING:-0}" != "1" ]; then
  step=$(date +%s)
  bash "$root/scripts/sanitize-test.sh"
  echo "run-tests: sanitize-test finished in $(( $(date +%s) - step )) s"
  step=$(date +%s)
  bash "$root/scripts/fuzz-test.sh" "${JACOBID_FUZZ_SECONDS:-20}"
  echo "run-tests: fuzz-test finished in $(( $(date +%s) - step )) s"
fi
if [ "${JACOBID_SKIP_EMULATED:-0}" != "1" ]; then
  step=$(date +%s)
  bash "$root/scripts/cross-test.sh"
  echo "run-tests: cross-test finished in $(( $(date +%s) - step )) s"
  step=$(date +%s)
  bash "$root/scripts/vm-test.sh"
  echo "run-tests: vm-test finished in $(( $(date +%s) - step )) s"
fi
