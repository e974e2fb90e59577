#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/excite.md, "Is the predicted std honest?": a design of `jacobid excite` played RUNS times on the
# simulated robot with fresh torque noise (the same motion every time: the noise is the only thing that
# changes), each log identified; per base parameter the spread of the estimates against the std the design
# predicted (its JSON's predicted.parameters.<NAME>.std, for the same noise).
#   [IDENTIFY_ARGS=...] [ENCODER_COUNTS=262144] [PREDICTION=std] [KEEP_RUNS=0]
#   bash scripts/measure_excite_honesty.sh BUILD_DIR OUT_DIR ROBOT.yaml RUNS NOISE [EXCITE_ARGS...]
# ENCODER_COUNTS: the simulated encoders' counts per revolution (0: no quantization). A design already in OUT_DIR
# (design.csv and design.json) is kept, so that one design can be measured under several settings.
# PREDICTION: the design's key compared with (std, or std_after_fp: after identify's F_p). KEEP_RUNS=1: a run
# whose JSON is already in OUT_DIR is not simulated again (run k always has noise seed 100 + k, so 100 runs
# extend 20 of the same settings). The summary adds how many parameters a perfect prediction would leave
# outside 0.8-1.25 x with this many runs: (runs - 1) s^2 / sigma^2 is chi^2 with runs - 1 degrees of freedom.
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
  [ "${KEEP_RUNS:-0}" = 1 ] && [ -s "$out/run$k.json" ] && continue
  "$J" simulate --robot "$robot" --trajectory "$out/design.csv" --torque-noise "$noise" --noise-seed "$((100 + k))" --encoder-counts "${ENCODER_COUNTS:-262144}" \
      --quiet -o "$out/run$k.csv"
  "$J" identify --robot "$robot" ${IDENTIFY_ARGS:-} --in "$out/run$k.csv" --format json --quiet > "$out/run$k.json"
  rm -f "$out/run$k.csv"
done
$PY - "$out" "$runs" "${PREDICTION:-std}" <<'PY'
import json, math, statistics, sys
out, runs, key = sys.argv[1], int(sys.argv[2]), sys.argv[3]

def chi2_cdf(x, dof):
    # P(dof / 2, x / 2), the regularized lower incomplete gamma function: its series (converges for every x;
    # x stays below ~2 dof here).
    a, x = dof / 2.0, x / 2.0
    term = total = 1.0 / a
    n = 0
    while term > 1e-17 * total:
        n += 1
        term *= x / (a + n)
        total += term
    return total * math.exp(-x + a * math.log(x) - math.lgamma(a))

design = json.load(open(f"{out}/design.json"))["predicted"]["parameters"]
runs_json = [json.load(open(f"{out}/run{k}.json")) for k in range(1, runs + 1)]
ratios = []
print(f"{'parameter':<10} {'predicted std':>14} {'spread':>12} {'ratio':>7}")
for name, p in design.items():
    values = [r["parameters"][name]["value"] for r in runs_json if r["parameters"][name]["value"] is not None]
    spread = statistics.stdev(values)
    ratios.append(spread / p[key])
    print(f"{name:<10} {p[key]:>14.4g} {spread:>12.4g} {spread / p[key]:>7.3f}")
inside = sum(0.8 <= r <= 1.25 for r in ratios)
dof = runs - 1
p_inside = chi2_cdf(dof * 1.25**2, dof) - chi2_cdf(dof * 0.8**2, dof)
print(f"spread / predicted ({key}): median {statistics.median(ratios):.3f}, range {min(ratios):.3f} .. {max(ratios):.3f}; "
      f"{inside} of {len(ratios)} within 0.8 .. 1.25 (the sampling error of a std from {runs} runs is about {100 / math.sqrt(2 * dof):.0f} %; "
      f"a perfect prediction leaves {len(ratios) * (1 - p_inside):.1f} of {len(ratios)} outside on average, chi^2 with {dof} dof)")
PY
