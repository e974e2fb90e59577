#!/usr/bin/env bash
# The whole native test suite once more under AddressSanitizer + UndefinedBehaviorSanitizer (gcc, the
# project's compiler), in its own build directory (build-sanitize). Any sanitizer report fails the run:
# -fno-sanitize-recover=all turns every UBSan finding into an abort, ASan halts on the first error, and
# LeakSanitizer reports leaks at exit.
#
#   scripts/sanitize-test.sh            configure, build, run ctest; prints the time of each step
#   JACOBID_SANITIZE_BUILD_DIR=dir ...  another build directory
#
# Left out, and why:
#  - tests/vm (ctest labels vcan, vm, gpio): those executables are linked -static for the VM initramfs,
#    and ASan's runtime cannot be linked statically; they run unsanitized in scripts/vm-test.sh.
#  - benchmarks: ctest does not run them, and timings under ASan mean nothing.
# -O1: ASan's recommended level (usable stack traces, about half the run time of -O0).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${JACOBID_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
jobs="$(nproc)"
start=$(date +%s)

flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# Debug keeps assert() on; CMAKE_CXX_FLAGS_DEBUG replaces its -O0 -g.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" \
  -DJACOBID_BUILD_BENCHMARKS=OFF -DJACOBID_VM_TESTS=OFF -DJACOBID_BUILD_FUZZERS=OFF >/dev/null

# Every executable except the static ones in tests/vm (ninja lists each output with its rule).
mapfile -t executables < <(ninja -C "$build" -t targets all | grep -E ': CXX_EXECUTABLE_LINKER' | cut -d: -f1 | grep -v '^tests/vm/')
nice -n 10 ninja -C "$build" -j "$jobs" "${executables[@]}"
built=$(date +%s)
echo "sanitize-test: built ${#executables[@]} executables in $(( built - start )) s"

# halt_on_error + abort_on_error: the first report ends the test with a failure; detect_leaks: LSan at exit.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Leaks inside system libraries we cannot fix (urdfdom on a cyclic URDF), each documented in the file.
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan-suppressions.txt:print_suppressions=0"
status=0
ctest --test-dir "$build" -j "$jobs" -LE '^(vcan|vm|gpio)$' --output-on-failure --timeout 900 || status=$?
# A report that did not fail its test (e.g. in a child process whose exit code was not checked) still
# shows in the logs: fail on any.
if grep -lE '^(==[0-9]+==ERROR: |SUMMARY: (Address|Undefined|Leak)Sanitizer|.*runtime error: )' "$build/Testing/Temporary/LastTest.log" >/dev/null 2>&1; then
    echo "sanitize-test: sanitizer report in $build/Testing/Temporary/LastTest.log:"
    grep -E '==[0-9]+==ERROR: |SUMMARY: |runtime error: ' "$build/Testing/Temporary/LastTest.log" | head -20
    status=1
fi
echo "sanitize-test: tests finished in $(( $(date +%s) - built )) s (total $(( $(date +%s) - start )) s), status $status"
exit $status
