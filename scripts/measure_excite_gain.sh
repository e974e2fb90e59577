#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/excite.md, "Does the design beat random moves?": identify's filtered held-out error of a model
# identified from a design of `jacobid excite` against models identified from random moves of the same
# duration within the same limits (5 seeds; the design's log with 5 noise seeds: one noise realisation moves
# the figure by +-15 %), each validated on noise-free motion it was not identified on
# (random moves and a multi-sine, 40 s each). Figure per log: per joint rms_error / torque-noise std, RMS over
# the joints, mean of the two validations (identify's defaults, or IDENTIFY_ARGS for every log alike).
# SEEDS (default 5): logs per side (the design with SEEDS noise seeds, random moves with SEEDS seeds); one noise
# realisation moves a log's figure by +-15 %, so the median of 5 moves by several %: 20 for a tighter comparison.
# KEEP_DESIGN=1 reuses OUT_DIR/design.csv when it is there (a design made with an evaluation budget depends on its
# options and --seed only), e.g. to score it again with more seeds.
#   [IDENTIFY_ARGS="--cutoff 20"] [POSE=q1,..] [SEEDS=20] [KEEP_DESIGN=1] bash scripts/measure_excite_gain.sh BUILD_DIR OUT_DIR ROBOT.yaml DURATION VELOCITY ACCELERATION NOISE ROOM [EXCITE_ARGS...]
# ROOM (rad, one or per joint) bounds the multi-sine's excursion from POSE (default 0): inside the joint limits.
# e.g. bash scripts/measure_excite_gain.sh build out/gain examples/robots/ur5_like.yaml 20 3.15 10 0.15,0.15,0.1,0.03,0.03,0.02 2.4
set -euo pipefail
build=$1 out=$2 robot=$3 duration=$4 vel=$5 acc=$6 noise=$7 room=$8
shift 8
J="$build/host-tools/jacobid"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
joints=$($PY -c "print(len('$noise'.split(',')))")
sim=(--robot "$robot" --encoder-counts 262144 --quiet)
# Validation motion: noise-free, 40 s, other seeds than any identification log.
"$J" simulate "${sim[@]}" --duration 40 --velocity-limit "$vel" --acceleration-limit "$acc" --seed 1000 -o "$out/val_moves.csv"
$PY "$here/multisine_trajectory.py" "$out/multisine.csv" --joints "$joints" --duration 40 --pose "${POSE:-0}" --room "$room" --velocity-limit "$vel" --acceleration-limit "$acc" --seed 7
"$J" simulate "${sim[@]}" --trajectory "$out/multisine.csv" -o "$out/val_multisine.csv"
# The design, then its log; random moves with 5 seeds.
seeds=$(seq 1 "${SEEDS:-5}")
[ "${KEEP_DESIGN:-0}" = 1 ] && [ -f "$out/design.csv" ] || "$J" excite --robot "$robot" --duration "$duration" --velocity-limit "$vel" --acceleration-limit "$acc" --torque-noise "$noise" \
    -o "$out/design.csv" --json "$out/design.json" --quiet "$@"
for s in $seeds; do
  "$J" simulate "${sim[@]}" --trajectory "$out/design.csv" --torque-noise "$noise" --noise-seed $((10 + s)) -o "$out/log_design$s.csv"
done
for s in $seeds; do
  "$J" simulate "${sim[@]}" --duration "$duration" --velocity-limit "$vel" --acceleration-limit "$acc" --seed "$s" --torque-noise "$noise" \
      --noise-seed $((20 + s)) -o "$out/log_moves$s.csv"
done
score() {  # LOG -> the figure
  for v in moves multisine; do
    "$J" identify --robot "$robot" ${IDENTIFY_ARGS:-} --in "$1" --validate "$out/val_$v.csv" --format json --quiet > "$out/$(basename "$1" .csv).$v.json"
  done
  $PY - "$out/$(basename "$1" .csv)" "$noise" <<'PY'
import json, math, sys
noise = [float(x) for x in sys.argv[2].split(",")]
figs = []
for v in ("moves", "multisine"):
    e = json.load(open(f"{sys.argv[1]}.{v}.json"))["validation"]["rms_error"]
    figs.append(math.sqrt(sum((x / s) ** 2 for x, s in zip(e, noise)) / len(e)))
print(f"{figs[0]:.4f} {figs[1]:.4f} {(figs[0] + figs[1]) / 2:.4f}")
PY
}
echo "log: random-move validation, multi-sine validation, mean"
: > "$out/design.txt"
for s in $seeds; do d=$(score "$out/log_design$s.csv"); echo "design noise seed $s $d"; echo "$d" >> "$out/design.txt"; done
: > "$out/moves.txt"
for s in $seeds; do m=$(score "$out/log_moves$s.csv"); echo "moves seed $s $m"; echo "$m" >> "$out/moves.txt"; done
$PY - "$out/moves.txt" "$out/design.txt" <<'PY'
import random, statistics, sys
moves = [float(l.split()[2]) for l in open(sys.argv[1])]
design = [float(l.split()[2]) for l in open(sys.argv[2])]
dm, mm = statistics.median(design), statistics.median(moves)
print(f"median of the design's logs {dm:.4f} ({min(design):.4f}-{max(design):.4f}); of the random moves {mm:.4f} "
      f"({min(moves):.4f}-{max(moves):.4f}); design / random moves = {dm / mm:.3f}")
# How far the ratio of medians moves with the logs drawn: both sides resampled with replacement (bootstrap, 4 000 draws).
rng = random.Random(1)
draws = sorted(statistics.median(rng.choices(design, k=len(design))) / statistics.median(rng.choices(moves, k=len(moves))) for _ in range(4000))
print(f"bootstrap: 90 % of the ratios within {draws[200]:.3f}-{draws[3799]:.3f}; share <= 0.6: {sum(r <= 0.6 for r in draws) / len(draws):.3f}")
PY
