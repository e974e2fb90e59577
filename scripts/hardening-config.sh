# SPDX-License-Identifier: MIT
# Sourced by scripts/sanitize-test.sh and scripts/fuzz-test.sh: the one build both run from (build-hardening).
#
# One clang build serves both: the test suite under ASan + UBSan, and the libFuzzer targets, which need
# the same sanitizers plus coverage instrumentation (fuzzer-no-link) on the parsers they call. Building
# the tree once instead of twice is a third of the CI budget.
#  - clang, not gcc: with sanitizers it compiles the tree about 2.5 times faster (docs/reliability.md).
#  - -O2: the simulated-identification tests do dense Eigen work that is 50 times slower at -O1 under ASan;
#    ASan and UBSan lose no checks at -O2. That work is in the libraries (jacobid::host); the test
#    executables' own sources are compiled at -O1 (tests/CMakeLists.txt, JACOBID_TEST_OPTIMIZATION).
#  - no benchmarks, no examples: the sanitizer run does not run them (scripts/sanitize-test.sh).
#  - shared libraries (JACOBID_SHARED_LIBRARIES, CMakeLists.txt): a change to one library source relinks that
#    library only, not the ~150 ASan test executables that link it.
#  - unity batches of 4 sources (JACOBID_UNITY_BATCH_SIZE; the native build's are 16): a changed source recompiles
#    with 3 neighbours. In a batch of 16 it recompiled all 16: identify/report/report.cpp alone takes 4.6 s of CPU,
#    its batch of 16 52 s (219 s of wall in a warm CI run, beside the emulated steps). Without batches a clean
#    sanitizer build took 1 299 s instead of ~880 s (docs/performance.md, "Build time (CI)").
#  - Debug build type without NDEBUG: assert() and Eigen's index and size checks stay on.
#  - lld links (-fuse-ld=lld): about 200 executables and libraries are linked in every fresh clone (links are not
#    cached), 0.55 s each with GNU ld against 0.18 s with lld (test_identify_cli, libjacobid_host.so).
#  - -gline-tables-only: file:line in every stack trace without the full debug info's compile time.
#  - -fno-sanitize-recover=all: every UBSan finding aborts (fails its test or its fuzz run).
#  - fuzz/ubsan-ignorelist.txt: no UBSan checks inside Eigen's own functions (they cost a factor 100 on the
#    simulation tests, see the file); ASan still covers them.
#  - fuzz/coverage-ignorelist.txt: the fuzzer's coverage instrumentation (fuzzer-no-link) only where a fuzz target
#    parses: not in the numerical code (identification, simulation, the core's robot dynamics, Eigen) nor in the test
#    programs, where it made the tests 1.7x slower and guided no fuzz target (see the file).
hardening_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$hardening_root/scripts/ccache-env.sh"
hardening_sanitizers="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
hardening_sanitizers+=" -fsanitize-ignorelist=$hardening_root/fuzz/ubsan-ignorelist.txt"
# ccache 4.7 hashes a -fsanitize-blacklist= file but not an -fsanitize-ignorelist= or -fsanitize-coverage-ignorelist=
# one: hash them explicitly (':' separates the files). Ninja does not see them either: after editing one, rebuild
# the hardening build from clean (`ninja -t clean`).
export CCACHE_EXTRAFILES="$hardening_root/fuzz/ubsan-ignorelist.txt:$hardening_root/fuzz/coverage-ignorelist.txt"

# configure_hardening <source-dir> <build-dir>
configure_hardening() {
  local src="$1" build="$2"
  local flags="-fsanitize=fuzzer-no-link -fsanitize-coverage-ignorelist=$hardening_root/fuzz/coverage-ignorelist.txt $hardening_sanitizers"
  cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_CXX_FLAGS_DEBUG="-O2 -gline-tables-only" -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="$flags -fuse-ld=lld" -DCMAKE_SHARED_LINKER_FLAGS="$flags -fuse-ld=lld" \
    -DJACOBID_BUILD_FUZZERS=ON -DJACOBID_BUILD_BENCHMARKS=OFF -DJACOBID_BUILD_EXAMPLES=OFF -DJACOBID_VM_TESTS=OFF -DJACOBID_UNITY_HOST_TOOLS=ON -DJACOBID_UNITY_BATCH_SIZE=4 -DJACOBID_PYTHON=OFF -DJACOBID_SHARED_LIBRARIES=ON >/dev/null
}

# Leaks inside system libraries we cannot fix (urdfdom on a cyclic URDF), each documented in the file.
export LSAN_OPTIONS="suppressions=$hardening_root/fuzz/lsan-suppressions.txt:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
