#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Instructions per streaming tick (6 joints x 3 channels x 211 taps + torque delay) of the
# DifferentiatorBank and of the straightforward baseline, counted by valgrind --tool=callgrind: stable
# where timings are noisy. Each implementation runs twice (BASE and BASE + TICKS ticks); the difference of
# the instruction totals divided by TICKS is the cost of one tick, set-up and kernel design cancelled.
#
# Usage: benchmarks/run_callgrind.sh [BUILD_DIR] [TICKS]     (defaults: build-default, 10000)
# BUILD_DIR must not be built with AVX-512 (-DJACOBID_MARCH=native on this machine): valgrind 3.19 does
# not decode AVX-512 and stops with SIGILL. Use the default flags or -DJACOBID_MARCH=x86-64-v3 (AVX2+FMA).
set -euo pipefail

build=${1:-build-default}
ticks=${2:-10000}
base=1000
exe="$build/benchmarks/bench_streaming_bank"
[[ -x "$exe" ]] || { echo "$exe not found: build the benchmarks first" >&2; exit 1; }
command -v valgrind >/dev/null || { echo "valgrind not found" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Total instructions (Ir) of one run of the driver.
instructions() {
    if ! valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$exe" --driver="$1" --ticks="$2" >"$tmp/stdout" 2>"$tmp/log"; then
        cat "$tmp/log" >&2
        if grep -q "Unrecognised instruction" "$tmp/log"; then
            echo "valgrind cannot decode this build (AVX-512?): use a build without -DJACOBID_MARCH=native" >&2
        fi
        exit 1
    fi
    awk '/^(summary|totals):/ { print $2; exit }' "$tmp/out"
}

declare -A per_tick
for impl in bank_double naive_double bank_float naive_float; do
    short=$(instructions "$impl" "$base")
    long=$(instructions "$impl" "$((base + ticks))")
    per_tick[$impl]=$(( (long - short) / ticks ))
done

echo "callgrind, $exe, $ticks ticks"
printf '%-8s %16s %16s %10s\n' scalar "bank Ir/tick" "naive Ir/tick" "ratio"
for scalar in double float; do
    b=${per_tick[bank_$scalar]}
    n=${per_tick[naive_$scalar]}
    printf '%-8s %16d %16d %9.1fx\n' "$scalar" "$b" "$n" "$(awk -v n="$n" -v b="$b" 'BEGIN { print n / b }')"
done
