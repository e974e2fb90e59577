#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets (fuzz/, clang with ASan + UBSan, in the build the sanitizer suite shares:
# scripts/hardening-config.sh) and runs each for a fixed time from its seed corpus (fuzz/corpus/<target>/).
# Fails on any crash, hang (-timeout), leak, sanitizer report or violated property; the input that did it
# is saved in build-hardening/artifacts/<target>/.
#
#   scripts/fuzz-test.sh [seconds-per-target]      default 20; two targets at a time (FUZZ_JOBS=2)
#   FUZZ_FRAME_SECONDS=20 scripts/fuzz-test.sh 20   the one-frame decoders as long as the parsers
#   FUZZ_TARGETS="csv_log candump_log" scripts/fuzz-test.sh 600    only these targets
#   FUZZ_JOBS=1 scripts/fuzz-test.sh 600                           the documented 10-minute run, one at a time
#   FUZZ_SEED=0 scripts/fuzz-test.sh                               a random seed (default 1: CI's runs repeat)
#
# New inputs that reach new code go to build-hardening/corpus/<target>/ (kept between runs), never into
# the checked-in seeds. A reproducer is re-run with: build-hardening/fuzz/fuzz_<target> <crash-file>.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-20}"
# The targets whose input is one CAN frame or one datagram (fuzz/CMakeLists.txt: FRAME; the four device
# profiles and the estimate datagram) get a quarter of that by default: a few dozen bytes through one
# decoder, they reach in the first 5 s all the coverage 20 s gives (CI's run of 2026-12-05: cov at half
# the executions = cov at the end, for all five), while the parsers of whole files still find new paths
# at 20 s (csv_log 879 -> 938, log_format 1922 -> 1964 over the second half).
frame_seconds="${FUZZ_FRAME_SECONDS:-$(( seconds >= 4 ? seconds / 4 : 1 ))}"
jobs="${FUZZ_JOBS:-2}"
# A fixed seed: CI explores the same inputs in the same order every time, so a finding reproduces and a
# green run stays green; the exploration differs from run to run only in how far it gets in the time.
seed="${FUZZ_SEED:-1}"
build="${JACOBID_HARDENING_BUILD_DIR:-$root/build-hardening}"
start=$(date +%s)
source "$root/scripts/hardening-config.sh"
configure_hardening "$root" "$build"
mapfile -t all_targets < <(grep -v '^$' "$build/fuzz/fuzzers.txt" | cut -d' ' -f1)
mapfile -t frame_targets < <(grep ' frame$' "$build/fuzz/fuzzers.txt" | cut -d' ' -f1)
read -r -a targets <<< "${FUZZ_TARGETS:-${all_targets[*]}}"
nice -n 10 cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
echo "fuzz-test: built ${#targets[@]} targets in $(( $(date +%s) - start )) s"

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=1:symbolize=1"

run_one() {
    local name="$1" seconds="$2" build="$3" root="$4" seed="$5"
    local corpus="$build/corpus/$name" artifacts="$build/artifacts/$name/" log="$build/logs/$name.log"
    mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
    # -timeout: one input taking more than 10 s is a hang; -rss_limit_mb: runaway allocation is a finding.
    if "$build/fuzz/fuzz_$name" -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
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
# Each target with its time, the parsers first (the longest runs start first).
plan=()
for name in "${targets[@]}"; do
    if printf '%s\n' "${frame_targets[@]}" | grep -qx "$name"; then plan+=("$name $frame_seconds"); else plan=("$name $seconds" "${plan[@]}"); fi
done
printf '%s\n' "${plan[@]}" | xargs -P "$jobs" -L1 bash -c 'run_one "$4" "$5" "$1" "$2" "$3"' _ "$build" "$root" "$seed" || status=1
echo "fuzz-test: ${#targets[@]} targets (parsers ${seconds} s, one-frame decoders ${frame_seconds} s) finished in $(( $(date +%s) - start )) s"
exit $status
