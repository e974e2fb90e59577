#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 2: installs the dependencies, builds, and runs every test: the native suite through ctest
# (unit, integration, install/consume), then the cross builds (aarch64 and armhf unit tests under
# qemu-user, Cortex-M no-heap link) and the SocketCAN/GPIO tests in qemu VMs with Debian's kernels;
# in between, the sanitizer run; the fuzz targets run beside the emulated steps.
# JACOBID_SKIP_EMULATED=1 runs the native suite only (a quick local run).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
source "$root/scripts/ccache-env.sh"  # also for the builds ctest starts (the install/consume test)
step=$(date +%s)
"$root/scripts/build.sh"
echo "run-tests: native build finished in $(( $(date +%s) - step )) s"
step=$(date +%s)
ctest --test-dir "${JACOBID_BUILD_DIR:-$root/build}" -j "$(nproc)" --output-on-failure --timeout 600
echo "run-tests: native tests finished in $(( $(date +%s) - step )) s"
# Hardening (docs/reliability.md): the whole suite again under ASan + UBSan, then every parser's libFuzzer
# target for a short fixed time (beside the VM step below, or here when that is skipped).
# JACOBID_SKIP_HARDENING=1 skips both (a quick local run).
hardening=1; [ "${JACOBID_SKIP_HARDENING:-0}" != "1" ] || hardening=0
emulated=1; [ "${JACOBID_SKIP_EMULATED:-0}" != "1" ] || emulated=0
fuzz() { bash "$root/scripts/fuzz-test.sh" "${JACOBID_FUZZ_SECONDS:-20}"; }
if [ "$hardening" = 1 ]; then
  step=$(date +%s)
  bash "$root/scripts/sanitize-test.sh"
  echo "run-tests: sanitize-test finished in $(( $(date +%s) - step )) s"
  if [ "$emulated" = 0 ]; then
    step=$(date +%s)
    fuzz
    echo "run-tests: fuzz-test finished in $(( $(date +%s) - step )) s"
  fi
fi
if [ "$emulated" = 1 ]; then
  # Packages, sysroots, VM kernels and the cross-built GoogleTest first, one at a time (apt and dpkg take
  # locks, and both steps below share the aarch64 GoogleTest); all of them are cached, so the two steps'
  # own calls find them done. Then the qemu-user step (cross-test), the fuzz targets (fuzz-test, built
  # already by sanitize-test) and the qemu-system step (vm-test) run side by side: the VM tests mostly keep
  # one core busy (the 60 s load test alone takes minutes of one qemu thread), and their guests' clocks
  # follow their own instructions (-icount sleep=off), so the work beside them changes wall times only;
  # each fuzz target runs for a fixed time, so beside them it gets through fewer inputs in that time.
  # The cross and fuzz steps' output is shown when all are done.
  step=$(date +%s)
  bash "$root/scripts/cross-deps.sh"
  bash "$root/scripts/vm-deps.sh"
  for arch in aarch64 armhf; do bash "$root/scripts/cross-gtest.sh" "$arch" >/dev/null; done
  echo "run-tests: cross and VM dependencies ready in $(( $(date +%s) - step )) s"
  step=$(date +%s)
  cross_log="$root/build-cross-test.log"
  bash "$root/scripts/cross-test.sh" > "$cross_log" 2>&1 &
  cross_pid=$!
  fuzz_log="$root/build-fuzz-test.log"
  fuzz_status=0
  if [ "$hardening" = 1 ]; then
    ( fuzz_start=$(date +%s); status=0; fuzz || status=$?
      echo "run-tests: fuzz-test finished in $(( $(date +%s) - fuzz_start )) s"; exit $status ) > "$fuzz_log" 2>&1 &
    fuzz_pid=$!
  fi
  vm_status=0
  bash "$root/scripts/vm-test.sh" || vm_status=$?
  echo "run-tests: vm-test finished in $(( $(date +%s) - step )) s (status $vm_status)"
  if [ "$hardening" = 1 ]; then
    wait "$fuzz_pid" || fuzz_status=$?
    echo "run-tests: fuzz-test output ($fuzz_log):"
    cat "$fuzz_log"
  fi
  cross_status=0
  wait "$cross_pid" || cross_status=$?
  echo "run-tests: cross-test output ($cross_log):"
  cat "$cross_log"
  echo "run-tests: cross-test, fuzz-test and vm-test side by side finished in $(( $(date +%s) - step )) s (cross status $cross_status, fuzz status $fuzz_status, vm status $vm_status)"
  [ "$cross_status" -eq 0 ] && [ "$fuzz_status" -eq 0 ] && [ "$vm_status" -eq 0 ]
fi
