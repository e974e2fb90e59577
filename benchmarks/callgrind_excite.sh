#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Instructions per optimizer evaluation of `jacobid excite` (docs/excite.md, "Speed"): bench_excite's case
# FILTER under callgrind, counting only inside ExcitationProblem::criterion and ::constraint_values (the
# benchmark's loop body: set-up and the benchmark's own bookkeeping left out), divided by the number of
# criterion calls. Instruction counts do not move with the machine's load; the benchmark's CPU times do.
#
# Usage: benchmarks/callgrind_excite.sh BUILD_DIR [FILTER]
#   FILTER default: BM_ExciteEvaluationUr5Like/box:0/route:2/torque:1 (a torque limit on every joint)
# BUILD_DIR must not be built with AVX-512 (valgrind 3.19 stops with SIGILL on it): -DJACOBID_MARCH=x86-64-v3,
# e.g. JACOBID_BUILD_DIR=build-v3 JACOBID_MARCH=x86-64-v3 bash scripts/build.sh bench_excite.
set -euo pipefail

build=$1
filter=${2:-BM_ExciteEvaluationUr5Like/box:0/route:2/torque:1}
exe="$build/benchmarks/bench_excite"
[[ -x "$exe" ]] || { echo "$exe not found: build bench_excite first" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

valgrind --tool=callgrind --callgrind-out-file="$tmp/out" --compress-strings=no \
    --toggle-collect='jacobid::excite::ExcitationProblem::criterion(*' \
    --toggle-collect='jacobid::excite::ExcitationProblem::constraint_values(*' \
    "$exe" --benchmark_filter="^${filter}\$" --benchmark_min_time=3 >"$tmp/stdout" 2>"$tmp/log" || { cat "$tmp/log" >&2; exit 1; }
total=$(awk '/^(summary|totals):/ { print $2; exit }' "$tmp/out")
# The benchmark's calls of criterion() (each iteration also calls constraint_values once): the calls= line after
# each cfn= line naming it (--compress-strings=no writes the name every time).
calls=$(awk '/^cfn=jacobid::excite::ExcitationProblem::criterion\(/ { getline; sub("calls=", "", $1); n += $1 } END { print n + 0 }' "$tmp/out")
[[ "$calls" -gt 0 ]] || { echo "no call of ExcitationProblem::criterion counted" >&2; exit 1; }
echo "$filter: $total instructions in $calls evaluations: $((total / calls)) per evaluation"
