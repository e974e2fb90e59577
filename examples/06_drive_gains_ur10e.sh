#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Drive gains of the UR10e from its two Fourier runs, without and with the 2.805 kg payload (identify
# --drive-gains, docs/identify.md), then each gain set tried the way a user would: written into the log
# format's `gains:`, identification on 14harm50sec, validation on the six joint-at-a-time logs. Numbers in
# docs/real-data.md, "Drive gains from the loaded run". The logs are read in place, never copied.
#
#   bash examples/06_drive_gains_ur10e.sh [BUILD_DIR or jacobid executable] [OUTPUT_DIR] [REALDATA_DIR]
set -euo pipefail
name=06_drive_gains_ur10e.sh default_out=out/06_drive_gains_ur10e
source "$(cd "$(dirname "$0")" && pwd)/ur10e_setup.sh"
format="$here/formats/ur10e.yaml"   # currents x the source repository's gains: the prior
ident="$data/ur10e/identification"
train="$ident/ur-20_02_19_14harm50sec.csv"

"$jacobid" identify --robot "$out/ur10e.yaml" --log-format "$format" --drive-gains --in "$train" \
    --loaded "$ident/ur-20_02_19_14harm50secLoad.csv" --payload-mass 2.805 --quiet | tee "$out/drive_gains.txt" | tail -n 12
"$jacobid" identify --robot "$out/ur10e.yaml" --log-format "$format" --drive-gains --in "$train" \
    --loaded "$ident/ur-20_02_19_14harm50secLoad.csv" --payload-mass 2.805 --quiet --format json > "$out/drive_gains.json"

# One log format per gain set: the shipped one with its gains: line replaced.
python3 - "$out" "$format" <<'PY'
import json, sys
out, fmt = sys.argv[1], sys.argv[2]
d = json.load(open(f"{out}/drive_gains.json"))["drive_gains"]
sets = {"source": [10.0, 10.6956, 8.4566, 9.0029, 9.48, 10.1232], "literature": [14.87, 13.26, 11.13, 10.62, 11.03, 11.47]}
for name, e in d["estimators"].items():
    sets[name] = e["gains"]
text = [l for l in open(fmt) if not l.startswith("gains:")]
for name, g in sets.items():
    with open(f"{out}/format_{name}.yaml", "w") as f:
        f.writelines(text)
        f.write("gains: [" + ", ".join(f"{x:.6g}" for x in g) + "]\n")
print(" ".join(sets))
PY
for f in "$out"/format_*.yaml; do
  name=$(basename "$f" .yaml); name=${name#format_}
  for n in 1 2 3 4 5 6; do
    "$jacobid" identify --robot "$out/ur10e.yaml" --log-format "$f" --in "$train" --quiet --format json \
        --validate "$data/ur10e/validation/ur-20_01_22-joint_$n.csv" > "$out/validate_${name}_joint_$n.json" 2>/dev/null
  done
done

# Per gain set and jointwise log: the moving joint's filtered RMS error over its RMS torque (NRMSE, free of
# the gain's scale) and the error over all joints in current units (each joint's RMS error / its gain).
python3 - "$out" <<'PY'
import glob, json, math, os, sys
out = sys.argv[1]
names = sorted({os.path.basename(p)[len("format_"):-len(".yaml")] for p in glob.glob(f"{out}/format_*.yaml")})
print(f"{'gain set':<12} " + " ".join(f"{'joint_' + str(n):>14}" for n in range(1, 7)) + f" {'mean':>14}")
print(f"{'':<12} " + " ".join(f"{'NRMSE% / A':>14}" for n in range(1, 7)))
for name in names:
    gains = [float(x) for x in open(f"{out}/format_{name}.yaml").read().split("gains: [")[1].split("]")[0].split(",")]
    cells, nr, amps = [], [], []
    for n in range(1, 7):
        v = json.load(open(f"{out}/validate_{name}_joint_{n}.json"))["methods"]["jacobi"]["validation"]
        e = 100 * v["rms_error"][n - 1] / v["rms_torque"][n - 1]
        a = math.sqrt(sum((x / g) ** 2 for x, g in zip(v["rms_error"], gains)))
        nr.append(e); amps.append(a)
        cells.append(f"{e:6.2f} / {a:5.3f}")
    print(f"{name:<12} " + " ".join(f"{c:>14}" for c in cells) + f" {sum(nr)/6:6.2f} / {sum(amps)/6:5.3f}")
PY
