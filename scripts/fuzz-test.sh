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
# New inputs that reach new code go to build-hardening/corpus/<target>/, never into the checked-in seeds, and
# after a clean run also to a corpus kept outside the clone, beside the compiler cache (JACOBID_FUZZ_CORPUS,
# default ${CCACHE_DIR}-fuzz-corpus; empty: none). A run that finds a kept corpus resumes from it: every input
# an earlier run found is replayed first (each path reached before is checked again) and the exploration goes on
# from there, for half the default time (FUZZ_RESUME_SECONDS, default 10 s; the one-frame decoders half theirs).
# Times given explicitly (the seconds argument, FUZZ_FRAME_SECONDS) are always run in full.
# A fresh machine (CI's) has none and fuzzes from the seeds for the full time.
# A reproducer is re-run with: build-hardening/fuzz/fuzz_<target> <crash-file>.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-20}"
seconds_given=$#
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
kept="${JACOBID_FUZZ_CORPUS-${CCACHE_DIR:+$CCACHE_DIR-fuzz-corpus}}"
if [ -n "$kept" ] && [ -n "$(ls -A "$kept" 2>/dev/null)" ]; then
  echo "fuzz-test: resuming from the corpus kept in $kept"
  if [ "$seconds_given" -eq 0 ]; then
    seconds="${FUZZ_RESUME_SECONDS:-$(( seconds / 2 ))}"
    [ -n "${FUZZ_FRAME_SECONDS:-}" ] || frame_seconds=$(( (frame_seconds + 1) / 2 ))
  fi
fi
configure_hardening "$root" "$build"
mapfile -t all_targets < <(grep -v '^$' "$build/fuzz/fuzzers.txt" | cut -d' ' -f1)
mapfile -t frame_targets < <(grep ' frame$' "$build/fuzz/fuzzers.txt" | cut -d' ' -f1)
read -r -a targets <<< "${FUZZ_TARGETS:-${all_targets[*]}}"
nice -n 10 cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
echo "fuzz-test: built ${#targets[@]} targets in $(( $(date +%s) - start )) s"

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=1:symbolize=1"

run_one() {
    local name="$1" seconds="$2" build="$3" root="$4" seed="$5" kept="$6"
    local corpus="$build/corpus/$name" artifacts="$build/artifacts/$name/" log="$build/logs/$name.log"
    mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
    local inputs=("$corpus" "$root/fuzz/corpus/$name")
    [ -z "$kept" ] || [ ! -d "$kept/$name" ] || inputs+=("$kept/$name")
    # -timeout: one input taking more than 10 s is a hang; -rss_limit_mb: runaway allocation is a finding.
    if "$build/fuzz/fuzz_$name" -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
         -print_final_stats=1 -artifact_prefix="$artifacts" "${inputs[@]}" >"$log" 2>&1; then
        # libFuzzer names an input by its SHA-1: copying without overwriting merges the corpora.
        # Past 4000 inputs the kept corpus is minimised (-merge=1 keeps the smallest set with the same coverage).
        if [ -n "$kept" ]; then
            mkdir -p "$kept/$name" && { cp -n "$corpus"/* "$kept/$name"/ 2>/dev/null || true; }
            if [ "$(find "$kept/$name" -type f | wc -l)" -gt 4000 ]; then
                rm -rf "$kept/$name.merged" && mkdir -p "$kept/$name.merged" &&
                    "$build/fuzz/fuzz_$name" -merge=1 -timeout=10 -rss_limit_mb=2048 -max_len=8192 "$kept/$name.merged" "$kept/$name" >>"$log" 2>&1 &&
                    rm -rf "$kept/$name" && mv "$kept/$name.merged" "$kept/$name"
            fi
        fi
        local execs cov ft
        execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
        cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
        ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
        printf 'fuzz-test: %-20s ok   %5s s  %10s execs  corpus %5s files (kept %5s)  cov %5s  ft %6s\n' \
            "$name" "$seconds" "$execs" "$(find "$corpus" -type f | wc -l)" "$( [ -n "$kept" ] && find "$kept/$name" -type f | wc -l || echo -)" "$cov" "$ft"
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
printf '%s\n' "${plan[@]}" | xargs -P "$jobs" -L1 bash -c 'run_one "$5" "$6" "$1" "$2" "$3" "$4"' _ "$build" "$root" "$seed" "$kept" || status=1
echo "fuzz-test: ${#targets[@]} targets (parsers ${seconds} s, one-frame decoders ${frame_seconds} s) finished in $(( $(date +%s) - start )) s"
exit $status
