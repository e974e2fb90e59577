#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang with ASan + UBSan) in build-fuzz and runs each for a fixed
# time from its seed corpus (fuzz/corpus/<target>/). Fails on any crash, hang (-timeout), leak, sanitizer
# report or violated property; the input that did it is saved in build-fuzz/artifacts/<target>/.
#
#   scripts/fuzz-test.sh [seconds-per-target]      default 20; two targets at a time (FUZZ_JOBS=2)
#   FUZZ_TARGETS="csv_log candump_log" scripts/fuzz-test.sh 600    only these targets
#   FUZZ_JOBS=1 scripts/fuzz-test.sh 600                           the documented 10-minute run, one at a time
#
# New inputs that reach new code go to build-fuzz/corpus/<target>/ (kept between runs), never into the
# checked-in seeds. A reproducer is re-run with: build-fuzz/fuzz/fuzz_<target> <crash-file>.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-20}"
jobs="${FUZZ_JOBS:-2}"
build="${JACOBID_FUZZ_BUILD_DIR:-$root/build-fuzz}"
start=$(date +%s)

# The whole tree gets coverage instrumentation (fuzzer-no-link) so that libFuzzer sees the parsers'
# branches; only the fuzz targets link the libFuzzer main. -O1 -g: fast enough, readable stack traces.
sanitize="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link $sanitize" \
  -DCMAKE_EXE_LINKER_FLAGS="$sanitize" \
  -DJACOBID_BUILD_FUZZERS=ON -DJACOBID_BUILD_TESTS=OFF -DJACOBID_BUILD_BENCHMARKS=OFF >/dev/null
mapfile -t all_targets < <(grep -v '^$' "$build/fuzz/fuzzers.txt")
read -r -a targets <<< "${FUZZ_TARGETS:-${all_targets[*]}}"
nice -n 10 cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
echo "fuzz-test: built ${#targets[@]} targets in $(( $(date +%s) - start )) s"

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=1:symbolize=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Leaks inside system libraries we cannot fix (each documented in the file).
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan-suppressions.txt:print_suppressions=0"

run_one() {
    local name="$1" seconds="$2" build="$3" root="$4"
    local corpus="$build/corpus/$name" artifacts="$build/artifacts/$name/" log="$build/logs/$name.log"
    mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
    # -timeout: one input taking more than 10 s is a hang; -rss_limit_mb: runaway allocation is a finding.
    if "$build/fuzz/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
         -print_final_stats=1 -artifact_prefix="$artifacts" "$corpus" "$root/fuzz/corpus/$name" >"$log" 2>&1; then
        local execs cov ft
        execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
        cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
        ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
        printf 'fuzz-test: %-20s ok   %5s s  %10s execs  corpus %5s files  cov %5s  ft %6s\n' \
            "$name" "$seconds" "$execs" "$(find "$corpus" -type f | wc -l)" "$cov" "$ft"
    else
        echo "fuzz-test: $name FAILED (log $log, input in $artifacts):"
        grep -E 'ERROR|SUMMARY|property violated|Test unit written|timeout|deadly signal' "$log" | head -20
        return 1
    fi
}
export -f run_one

status=0
printf '%s\n' "${targets[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ {} "$seconds" "$build" "$root" || status=1
echo "fuzz-test: ${#targets[@]} targets x ${seconds} s finished in $(( $(date +%s) - start )) s"
exit $status
