#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/excite.md, "Is the predicted std honest?": a design of `jacobid excite` played RUNS times on the
# simulated robot with fresh torque noise (the same motion every time: the noise is the only thing that
# changes), each log identified; per base parameter the spread of the estimates against the std the design
# predicted (its JSON's predicted.parameters.<NAME>.std, for the same noise).
#   [IDENTIFY_ARGS=...] [ENCODER_COUNTS=262144] bash scripts/measure_excite_honesty.sh BUILD_DIR OUT_DIR ROBOT.yaml RUNS NOISE [EXCITE_ARGS...]
# ENCODER_COUNTS: the simulated encoders' counts per revolution (0: no quantization). A design already in OUT_DIR
# (design.csv and design.json) is kept, so that one design can be measured under several settings.
set -euo pipefail
build=$1 out=$2 robot=$3 runs=$4 noise=$5
shift 5
J="$build/host-tools/jacobid"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
mkdir -p "$out"
if [ ! -f "$out/design.json" ] || [ ! -f "$out/design.csv" ]; then
  "$J" excite --robot "$robot" --torque-noise "$noise" -o "$out/design.csv" --json "$out/design.json" --quiet "$@"
fi
for k in $(seq 1 "$runs"); do
  "$J" simulate --robot "$robot" --trajectory "$out/design.csv" --torque-noise "$noise" --noise-seed "$((100 + k))" --encoder-counts "${ENCODER_COUNTS:-262144}" \
      --quiet -o "$out/run$k.csv"
  "$J" identify --robot "$robot" ${IDENTIFY_ARGS:-} --in "$out/run$k.csv" --format json --quiet > "$out/run$k.json"
  rm -f "$out/run$k.csv"
done
$PY - "$out" "$runs" <<'PY'
import json, math, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
design = json.load(open(f"{out}/design.json"))["predicted"]["parameters"]
runs_json = [json.load(open(f"{out}/run{k}.json")) for k in range(1, runs + 1)]
ratios = []
print(f"{'parameter':<10} {'predicted std':>14} {'spread':>12} {'ratio':>7}")
for name, p in design.items():
    values = [r["parameters"][name]["value"] for r in runs_json if r["parameters"][name]["value"] is not None]
    spread = statistics.stdev(values)
    ratios.append(spread / p["std"])
    print(f"{name:<10} {p['std']:>14.4g} {spread:>12.4g} {spread / p['std']:>7.3f}")
inside = sum(0.8 <= r <= 1.25 for r in ratios)
print(f"spread / predicted: median {statistics.median(ratios):.3f}, range {min(ratios):.3f} .. {max(ratios):.3f}; "
      f"{inside} of {len(ratios)} within 0.8 .. 1.25 (the sampling error of a std from {runs} runs is about {100 / math.sqrt(2 * (runs - 1)):.0f} %)")
PY
