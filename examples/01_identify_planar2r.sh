#!/bin/sh
# SPDX-License-Identifier: MIT
# Main job: simulate the paper-like 2R robot (Table II truth, PD on random quintic moves, 1 kHz, encoder
# 2^16 counts/rev, torque noise 0.05 / 0.01 N.m), identify it with the Jacobi pipeline and the
# Butterworth baseline side by side, print the Table II comparison next to the truth, and write a
# Markdown report with PNG plots.
#
# Usage: examples/01_identify_planar2r.sh [JACOBID_BINARY_OR_BUILD_DIR] [OUTPUT_DIR]
#   default binary: build/host-tools/jacobid; default output: out/01_identify_planar2r
set -eu
arg=${1:-build}
if [ -d "$arg" ]; then jacobid="$arg/host-tools/jacobid"; else jacobid="$arg"; fi
[ -x "$jacobid" ] || { echo "01_identify_planar2r.sh: no jacobid executable at '$jacobid'" >&2; exit 2; }
out=${2:-out/01_identify_planar2r}
mkdir -p "$out"

cp "$(dirname "$0")/robots/planar2r.yaml" "$out/robot.yaml"  # the paper's 2R (examples/robots/planar2r.yaml)

"$jacobid" simulate --robot "$out/robot.yaml" --out "$out/log.csv" --truth "$out/truth.json" \
    --duration 60 --rate 1000 --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 1
"$jacobid" simulate --robot "$out/robot.yaml" --out "$out/validation.csv" --truth "$out/validation.truth.json" \
    --duration 30 --rate 1000 --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 2 --noise-seed 3
"$jacobid" identify --robot "$out/robot.yaml" --in "$out/log.csv" --method both --truth "$out/truth.json" \
    --validate "$out/validation.csv" --report "$out/report" | tee "$out/table2.txt"
"$jacobid" identify --robot "$out/robot.yaml" --in "$out/log.csv" --method both --format json > "$out/identification.json"
echo "report: $out/report/report.md"
