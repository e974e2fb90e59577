#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/real-data.md, "A design against the peer's": the UR10e's shared 14harm50sec log (the source repository's
# condition-number-optimised Fourier trajectory, 50 s) against a design of `jacobid excite` within the same
# motion limits (per joint the log's position range, its largest |qd| and |qdd|), both predicted the same way:
# the base parameters' std of the WLS estimate with the parameters and per-joint noise identified from that
# log (--prior), the log's motion differentiated like identify (--compare), the design sampled at the log's rate.
#   bash scripts/measure_excite_ur10e.sh BUILD_DIR OUT_DIR [REALDATA_DIR] [EXCITE_ARGS...]
set -euo pipefail
build=${1:-build} out=${2:-out/excite_ur10e}
name=measure_excite_ur10e.sh default_out=$out
root=$(cd "$(dirname "$0")/.." && pwd)
set -- "$build" "$out" "${3:-$root/../shared/realdata}" "${@:4}"
source "$root/examples/ur10e_setup.sh"
shift 3
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
format="$root/examples/formats/ur10e.yaml"
log="$data/ur10e/identification/ur-20_02_19_14harm50sec.csv"
"$jacobid" identify --robot "$out/ur10e.yaml" --log-format "$format" --in "$log" --format json --quiet > "$out/prior.json"
# The log's limits: position range, |qd| (measured) and |qdd| (its measured velocity on the identify grid, differentiated
# by a Savitzky-Golay filter of 0.21 s: noise-free enough not to inflate the peak), and its grid rate.
read -r ranges velocities accelerations rate < <($PY - "$log" "$out/prior.json" <<'PY'
import json, sys
import numpy as np
from scipy.signal import savgol_filter
raw = np.loadtxt(sys.argv[1], delimiter=",")
period = json.load(open(sys.argv[2]))["settings"]["sample_period"]
t = raw[:, 0]
grid = np.arange(t[0], t[-1], period)
q = raw[:, 1:7]
qd = np.column_stack([np.interp(grid, t, raw[:, 7 + j]) for j in range(6)])
qdd = savgol_filter(qd, int(round(0.21 / period)) | 1, 3, deriv=1, delta=period, axis=0)
ranges = ",".join(f"{q[:, j].min():.4f}:{q[:, j].max():.4f}" for j in range(6))
print(ranges, ",".join(f"{np.abs(qd[:, j]).max():.4f}" for j in range(6)), ",".join(f"{np.abs(qdd[:, j]).max():.4f}" for j in range(6)),
      f"{round(5 / period) / 5:g}")  # a multiple of 0.2 Hz: whole samples per period of 10, 25 or 50 s
PY
)
echo "limits from the log: position $ranges; velocity $velocities rad/s; acceleration $accelerations rad/s^2; rate $rate Hz"
"$jacobid" excite --robot "$out/ur10e.yaml" --duration 50 --rate "$rate" --position-limit "$ranges" --velocity-limit "$velocities" \
    --acceleration-limit "$accelerations" --prior "$out/prior.json" --compare "$log" --log-format "$format" \
    -o "$out/design.csv" --json "$out/design.json" --plot "$out/design.png" "$@" 2> "$out/excite.txt" || { cat "$out/excite.txt"; exit 1; }
$PY - "$out/design.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
p, c = d["predicted"], d["compare"]["predicted"]
print(f"design: worst relative std {100 * p['worst_relative_std']:.3g} % ({p['worst_parameter']}); 14harm50sec: {100 * c['worst_relative_std']:.3g} % "
      f"({c['worst_parameter']}); ratio {d['compare']['worst_relative_std_ratio']:.3f}; log det information {p['log_det_information']:.1f} vs {c['log_det_information']:.1f}")
PY
