#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The whole native test suite once more under AddressSanitizer + UndefinedBehaviorSanitizer, in the
# clang build that the fuzz targets share (scripts/hardening-config.sh: why clang, -O2, one build).
# Any sanitizer report fails the run: -fno-sanitize-recover=all turns every UBSan finding into an abort,
# ASan halts on the first error, and LeakSanitizer reports leaks at exit.
#
#   scripts/sanitize-test.sh            configure, build (tests and fuzz targets), run ctest; times each step
#   JACOBID_HARDENING_BUILD_DIR=dir ... another build directory
#
# Left out, and why:
#  - tests/vm (ctest labels vcan, vm, gpio): those executables are linked -static for the VM initramfs,
#    and ASan's runtime cannot be linked statically; they run unsanitized in scripts/vm-test.sh.
#  - benchmarks: ctest does not run them, and timings under ASan mean nothing. Not even built.
#  - ctest labels examples and end-to-end (the numbered examples, README's quick start): whole jobs on long
#    logs through the code the unit and integration tests already run here; under ASan they cost minutes
#    of the CI budget and find nothing those tests do not. The native run keeps them. The C++ examples
#    (examples/cpp) are not built here either (hardening-config.sh: JACOBID_BUILD_EXAMPLES=OFF).
#  - three acceptance-scale tests, the longest of the suite (native 21-23 s each, about 6x that under ASan,
#    a fifth of the sanitizer stage's test CPU): SerialIdentify.Puma560MeetsTheIssueAcceptance (a 6-axis
#    log identified to the issue's bars; the 6-axis pipeline runs sanitized in PhysicalIdentify.*,
#    ModelExportCli.* and SerialIdentify's other tests) and DriveGains.SimulatedPairGivesTheGainsBack (the
#    drive-gains fit runs sanitized in DriveGains.SharedUr10ePairValidatesAtLeastAsWellAsTheSourceGains on
#    the shared real logs, which CI has; without them only its bad-input test runs sanitized). The native
#    run keeps both. Likewise Payload.MonteCarloStdCoversTheTruth (8 simulated loaded/unloaded pairs, 23 s
#    natively): the payload estimate runs sanitized in the other Payload.* tests. And excite --payload's two
#    end-to-end tests (each two time-limited designs of 20 s, whose comparison needs the evaluations a native run
#    gets, and 8 simulated runs through jacobid payload: 33-47 s natively): its criterion and projection run
#    sanitized in ExcitePayload.PayloadColumns..., its options in ExcitePayload.BadPayloadOptions....
#    And TorqueDelay.StdMatchesTheSpreadOnDelayFreeLogs (40 simulated logs, each searched for a delay: 19 s
#    natively): the delay's search and its Newey-West std run sanitized in the other TorqueDelay.* tests and in
#    BartlettLongRunVariance.*.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${JACOBID_HARDENING_BUILD_DIR:-$root/build-hardening}"
jobs="$(nproc)"
start=$(date +%s)
source "$root/scripts/hardening-config.sh"
configure_hardening "$root" "$build"

# Every executable except the static ones in tests/vm (ninja lists each output with its rule); the fuzz
# targets too, so that scripts/fuzz-test.sh finds them built.
mapfile -t executables < <(ninja -C "$build" -t targets all | grep -E ': CXX_EXECUTABLE_LINKER' | cut -d: -f1 | grep -v '^tests/vm/')
# Under nice: the emulated steps (scripts/run-tests.sh) run beside it. Without nice (tried, docs/performance.md
# "Issue 37, seventh part") the build ended sooner but its tests then ran beside the VM step's qemu threads, and the
# warm run took 945 s instead of 881 s.
nice -n 10 ninja -C "$build" -j "$jobs" "${executables[@]}"
built=$(date +%s)
echo "sanitize-test: built ${#executables[@]} executables in $(( built - start )) s"

# halt_on_error + abort_on_error: the first report ends the test with a failure; detect_leaks: LSan at exit.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
# Under ASan + UBSan the tests run 4-8x slower than natively. Two things keep that stage short (docs/performance.md):
# the tests that run "on every shared real log" take one log per family (tests/support/realdata.hpp), and
# ctest starts the longest tests first, from the native run's durations when there is one (a fresh build
# directory has none, and the longest test then often starts last and runs alone).
export JACOBID_REALDATA_ONE_PER_FAMILY=1
# The tests' simulated input logs come from the native build's jacobid when there is one (tests/support/command_cache.hpp,
# fixture_executable): what runs under ASan is the code each test checks; simulate is checked sanitized by the tests
# that run it themselves.
native_build="${JACOBID_BUILD_DIR:-$root/build}"
[ -x "$native_build/host-tools/jacobid" ] && export JACOBID_FIXTURE_EXECUTABLE="$native_build/host-tools/jacobid"
native_costs="$native_build/Testing/Temporary/CTestCostData.txt"
if [ -f "$native_costs" ] && [ ! -f "$build/Testing/Temporary/CTestCostData.txt" ]; then
    mkdir -p "$build/Testing/Temporary" && cp "$native_costs" "$build/Testing/Temporary/CTestCostData.txt"
fi
status=0
acceptance_scale='^(SerialIdentify\.Puma560MeetsTheIssueAcceptance|DriveGains\.SimulatedPairGivesTheGainsBack|Payload\.MonteCarloStdCoversTheTruth|ExcitePayload\.DesignGivesThePayloadMoreInformationThanTheArmsDesignOfTheSameDuration|ExcitePayload\.PredictedStdIsTheSpreadOfJacobidPayloadOnSimulatedRuns|TorqueDelay\.StdMatchesTheSpreadOnDelayFreeLogs)$'
ctest --test-dir "$build" -j "$jobs" -LE '^(vcan|vm|gpio|examples|end-to-end)$' -E "$acceptance_scale" --output-on-failure --timeout 900 || status=$?
# A report that did not fail its test (e.g. in a child process whose exit code was not checked) still
# shows in the logs: fail on any.
if grep -lE '^(==[0-9]+==ERROR: |SUMMARY: (Address|Undefined|Leak)Sanitizer|.*runtime error: )' "$build/Testing/Temporary/LastTest.log" >/dev/null 2>&1; then
    echo "sanitize-test: sanitizer report in $build/Testing/Temporary/LastTest.log:"
    grep -E '==[0-9]+==ERROR: |SUMMARY: |runtime error: ' "$build/Testing/Temporary/LastTest.log" | head -20
    status=1
fi
echo "sanitize-test: tests finished in $(( $(date +%s) - built )) s (total $(( $(date +%s) - start )) s), status $status"
exit $status
