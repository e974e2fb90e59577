#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 2: installs the dependencies, builds, and runs every test: the native suite through ctest
# (unit, integration, install/consume), then the sanitizer run and the fuzz targets, and beside them the
# cross builds (aarch64 and armhf unit tests under qemu-user, Cortex-M no-heap link) and the SocketCAN/GPIO
# tests in qemu VMs with Debian's kernels. Each step prints how long it took (`run-tests: ... finished in N s`).
# JACOBID_SKIP_EMULATED=1 JACOBID_SKIP_HARDENING=1 runs the native suite only (a quick local run).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
source "$root/scripts/ccache-env.sh"  # also for the builds ctest starts (the install/consume test)
# scipy's reference values, computed once per run by the native tests and read by the sanitizer run and the
# qemu-user unit tests (tests/reference/scipy_reference.hpp); a fresh folder each run.
if [ -z "${JACOBID_REFERENCE_CACHE:-}" ]; then
  export JACOBID_REFERENCE_CACHE="$root/build-reference-cache"
  rm -rf "$JACOBID_REFERENCE_CACHE"
fi
step=$(date +%s)
"$root/scripts/build.sh"
echo "run-tests: native build finished in $(( $(date +%s) - step )) s"
step=$(date +%s)
# ctest starts the longest tests first when it knows their durations (Testing/Temporary/CTestCostData.txt); a fresh
# clone has none, and a 25 s test that starts last runs alone on one core. The previous run's durations are kept
# beside the compiler cache (outside the clone) and given to a build folder that has none.
native_build="${JACOBID_BUILD_DIR:-$root/build}"
costs_kept="${JACOBID_TEST_COSTS:-${CCACHE_DIR:+$CCACHE_DIR-test-costs}}"
costs="$native_build/Testing/Temporary/CTestCostData.txt"
if [ -n "$costs_kept" ] && [ -f "$costs_kept/native.txt" ] && [ ! -f "$costs" ]; then
  mkdir -p "$(dirname "$costs")" && cp "$costs_kept/native.txt" "$costs"
fi
ctest --test-dir "$native_build" -j "$(nproc)" --output-on-failure --timeout 600
if [ -n "$costs_kept" ] && [ -f "$costs" ]; then mkdir -p "$costs_kept" && cp "$costs" "$costs_kept/native.txt"; fi
echo "run-tests: native tests finished in $(( $(date +%s) - step )) s"
# Hardening (docs/reliability.md): the whole suite again under ASan + UBSan, then every parser's libFuzzer
# target for a short fixed time. JACOBID_SKIP_HARDENING=1 skips both (a quick local run).
# The emulated steps (cross builds under qemu-user, the SocketCAN/GPIO VMs) run in the background beside them:
# the VM step's long pole is one qemu thread (the 60 s board load test takes minutes of it), which at the end
# of the run used to leave the second core idle; started first, it runs beside the sanitizer and fuzz steps,
# which fill the other core. The guests' clocks follow their own instructions (-icount sleep=off), so the work
# beside them changes wall times only; each fuzz target runs for a fixed time, so beside them it gets through
# fewer inputs in that time. JACOBID_SKIP_EMULATED=1 skips the emulated steps.
hardening=1; [ "${JACOBID_SKIP_HARDENING:-0}" != "1" ] || hardening=0
emulated=1; [ "${JACOBID_SKIP_EMULATED:-0}" != "1" ] || emulated=0
if [ "$emulated" = 1 ]; then
  # Packages, sysroots, VM kernels and the cross-built GoogleTest first, one at a time (apt and dpkg take
  # locks, and both steps below share the aarch64 GoogleTest); all of them are cached, so the two steps'
  # own calls find them done. Their output is shown when the steps are done.
  step=$(date +%s)
  bash "$root/scripts/cross-deps.sh"
  bash "$root/scripts/vm-deps.sh"
  for arch in aarch64 armhf; do bash "$root/scripts/cross-gtest.sh" "$arch" >/dev/null; done
  echo "run-tests: cross and VM dependencies ready in $(( $(date +%s) - step )) s"
  emulated_start=$(date +%s)
  cross_log="$root/build-cross-test.log"
  ( status=0; bash "$root/scripts/cross-test.sh" || status=$?
    echo "run-tests: cross-test finished in $(( $(date +%s) - emulated_start )) s"; exit $status ) > "$cross_log" 2>&1 &
  cross_pid=$!
  vm_log="$root/build-vm-test.log"
  ( status=0; bash "$root/scripts/vm-test.sh" || status=$?
    echo "run-tests: vm-test finished in $(( $(date +%s) - emulated_start )) s"; exit $status ) > "$vm_log" 2>&1 &
  vm_pid=$!
  echo "run-tests: cross-test and vm-test started in the background (output: $cross_log, $vm_log)"
fi
hardening_status=0
if [ "$hardening" = 1 ]; then
  step=$(date +%s)
  bash "$root/scripts/sanitize-test.sh" || hardening_status=$?
  echo "run-tests: sanitize-test finished in $(( $(date +%s) - step )) s (status $hardening_status)"
  step=$(date +%s)
  bash "$root/scripts/fuzz-test.sh" ${JACOBID_FUZZ_SECONDS:+"$JACOBID_FUZZ_SECONDS"} || hardening_status=$?
  echo "run-tests: fuzz-test finished in $(( $(date +%s) - step )) s (status $hardening_status)"
fi
if [ "$emulated" = 1 ]; then
  cross_status=0 vm_status=0
  wait "$vm_pid" || vm_status=$?
  echo "run-tests: vm-test output ($vm_log):"
  cat "$vm_log"
  wait "$cross_pid" || cross_status=$?
  echo "run-tests: cross-test output ($cross_log):"
  cat "$cross_log"
  echo "run-tests: the emulated steps finished $(( $(date +%s) - emulated_start )) s after they started (cross status $cross_status, vm status $vm_status)"
  [ "$cross_status" -eq 0 ] && [ "$vm_status" -eq 0 ]
fi
[ "$hardening_status" -eq 0 ]
