#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The 20-run Monte Carlo of docs/identify.md, "Payload" (issue 39): the simulated UR5-like arm with a 1.5 kg
# payload at (0.03, -0.02, 0.05) m in the flange frame, one excitation (seed 3), new torque noise per run; the arm
# identified on each unloaded run, then jacobid payload with and without --unloaded (the loaded log desynchronized:
# 137 samples later, another clock). Prints, per mode, how often +-2 std covers the truth of the mass and of each
# centre-of-mass coordinate, and the RMS and mean of (estimate - truth) / std.
#
#   bash scripts/measure_payload_montecarlo.sh [BUILD_DIR] [OUTPUT_DIR] [RUNS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jacobid=${1:-$root/build}/host-tools/jacobid
out=${2:-out/payload_montecarlo}
runs=${3:-20}
[ -x "$jacobid" ] || { echo "measure_payload_montecarlo.sh: no jacobid at '$jacobid'" >&2; exit 2; }
mkdir -p "$out"
robot="$root/examples/robots/ur5_like.yaml"
python3 "$root/scripts/payload_loaded_robot.py" "$robot" "$out/loaded.yaml"
for i in $(seq 1 "$runs"); do
  common="simulate --quiet --duration 30 --seed 3 --torque-noise 0.3"
  "$jacobid" $common --noise-seed $((100 + 2 * i)) --robot "$robot" -o "$out/unloaded.csv"
  "$jacobid" $common --noise-seed $((101 + 2 * i)) --robot "$out/loaded.yaml" -o "$out/loaded_full.csv"
  awk -F, -v OFS=, 'NR == 1 { print; next } NR > 138 { $1 = sprintf("%.6f", $1 + 1000); print }' "$out/loaded_full.csv" > "$out/loaded.csv"
  "$jacobid" identify --quiet --robot "$robot" --in "$out/unloaded.csv" --format json > "$out/arm.json"
  "$jacobid" payload --quiet --robot "$robot" --arm "$out/arm.json" --in "$out/loaded.csv" --unloaded "$out/unloaded.csv" --json > "$out/unloaded_$i.json"
  "$jacobid" payload --quiet --robot "$robot" --arm "$out/arm.json" --in "$out/loaded.csv" --json > "$out/arm_$i.json"
done
python3 - "$out" "$runs" <<'PY'
import json, math, sys
out, n = sys.argv[1], int(sys.argv[2])
truth = {"mass": 1.5, "com_x": 0.03, "com_y": -0.02, "com_z": 0.05}
for mode, label in (("unloaded", "--unloaded"), ("arm", "arm model alone")):
    cells = []
    for k, t in truth.items():
        z = []
        for i in range(1, n + 1):
            p = json.load(open(f"{out}/{mode}_{i}.json"))["payload"][k]
            z.append((p["value"] - t) / p["std"])
        cover = sum(abs(x) <= 2 for x in z)
        cells.append(f"{k} {cover}/{n} (z rms {math.sqrt(sum(x * x for x in z) / n):.2f}, mean {sum(z) / n:+.2f})")
    print(f"{label:<16} " + "; ".join(cells))
PY
