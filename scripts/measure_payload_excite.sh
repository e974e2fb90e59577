#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# `excite --payload` against the arm's own design of the same duration (docs/excite.md, "Payload designs"; issue
# 39): both designed for the UR5-like arm within the same limits and noise, the payload design's predicted std
# beside the arm design's (--compare), then each played RUNS times on the simulated arm carrying the 1.5 kg payload
# of docs/identify.md (scripts/payload_loaded_robot.py) with fresh torque noise, and `jacobid payload` run on every
# log with the arm held at its true values (--arm the description). Prints, per design and per payload parameter,
# the predicted std, the spread of the RUNS estimates and their ratio, the median std jacobid payload reported,
# and the coverage of the truth by +-2 spread-free predicted std.
#
#   [SIMULATE_ARGS="--encoder-counts 0"] bash scripts/measure_payload_excite.sh [BUILD_DIR] [OUTPUT_DIR] [RUNS] [TIME_LIMIT]
# SIMULATE_ARGS: more options of every `jacobid simulate`. Designs already in OUTPUT_DIR (payload_design.json and
# arm_design.csv) are kept, so that one pair of designs can be measured under several simulations.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jacobid=${1:-$root/build}/host-tools/jacobid
out=${2:-out/payload_excite}
runs=${3:-20}
time_limit=${4:-30}
[ -x "$jacobid" ] || { echo "measure_payload_excite.sh: no jacobid at '$jacobid'" >&2; exit 2; }
mkdir -p "$out"
robot="$root/examples/robots/ur5_like.yaml"
noise=0.15,0.15,0.1,0.03,0.03,0.02
limits="--velocity-limit 3.15 --acceleration-limit 10 --torque-noise $noise --time-limit $time_limit --starts 2"
python3 "$root/scripts/payload_loaded_robot.py" "$robot" "$out/loaded.yaml"
if [ ! -f "$out/payload_design.json" ] || [ ! -f "$out/arm_design.csv" ]; then
  "$jacobid" excite --quiet --robot "$robot" --duration 10 $limits -o "$out/arm_design.csv" --json "$out/arm_design.json"
  "$jacobid" excite --quiet --robot "$robot" --payload --payload-mass 1.5 --payload-com 0.03,-0.02,0.05 $limits \
    --compare "$out/arm_design.csv" -o "$out/payload_design.csv" --json "$out/payload_design.json"
fi
for design in payload_design arm_design; do
  for i in $(seq 1 "$runs"); do
    "$jacobid" simulate --quiet --robot "$out/loaded.yaml" --trajectory "$out/$design.csv" --torque-noise "$noise" --noise-seed $((500 + i)) \
      ${SIMULATE_ARGS:-} -o "$out/${design}_log.csv"
    "$jacobid" payload --quiet --robot "$robot" --arm "$robot" --in "$out/${design}_log.csv" --json > "$out/${design}_$i.json"
  done
done
python3 - "$out" "$runs" "$root/scripts" <<'PY'
import json, statistics, sys
sys.path.insert(0, sys.argv[3])
from payload_loaded_robot import payload_standard
out, n = sys.argv[1], int(sys.argv[2])
truth = payload_standard()
design = json.load(open(f"{out}/payload_design.json"))
prediction = {"payload_design": design["predicted"]["parameters"], "arm_design": design["compare"]["predicted"]["parameters"]}
for name in ("payload_design", "arm_design"):
    runs = [json.load(open(f"{out}/{name}_{k}.json"))["standard_parameters"] for k in range(1, n + 1)]
    print(f"{name}: {n} runs, jacobid payload --arm (the true arm)")
    print(f"{'param':<5} {'predicted':>10} {'spread':>10} {'ratio':>6} {'reported':>10} {'bias/pred':>9} {'covered':>7}")
    ratios = []
    for k, t in truth.items():
        values = [r[k]["value"] for r in runs]
        spread = statistics.stdev(values)
        predicted = prediction[name][k]["std"]
        reported = statistics.median(r[k]["std"] for r in runs)
        covered = sum(abs(v - t) <= 2 * predicted for v in values)
        ratios.append(spread / predicted)
        print(f"{k:<5} {predicted:>10.3g} {spread:>10.3g} {spread / predicted:>6.2f} {reported:>10.3g} {(statistics.mean(values) - t) / predicted:>+9.2f} {covered:>4}/{n}")
    print(f"spread / predicted: median {statistics.median(ratios):.2f} (range {min(ratios):.2f}-{max(ratios):.2f}); "
          f"within 0.8-1.25: {sum(0.8 <= r <= 1.25 for r in ratios)} of 10")
p, a = design["predicted"], design["compare"]["predicted"]
print(f"predicted: payload design worst relative std {100 * p['worst_relative_std']:.3g} % ({p['worst_parameter']}), log det {p['log_det_information']:.2f}; "
      f"arm design {100 * a['worst_relative_std']:.3g} % ({a['worst_parameter']}), log det {a['log_det_information']:.2f}")
PY
