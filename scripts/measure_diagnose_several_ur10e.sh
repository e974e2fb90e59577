#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# `jacobid diagnose` with several logs on the shared UR10e (docs/diagnose.md, "Four identification logs
# together"): the 14harm50sec run alone, then the four unloaded Fourier runs together, each validated on every
# joint-at-a-time log; prints, per validation log, the rows per joint, the held-out torque RMS per joint
# before -> after and the named effects. The robot is examples/03's (alpha auto, offset, rotor inertia).
#
#   bash scripts/measure_diagnose_several_ur10e.sh [BUILD_DIR] [OUTPUT_DIR] [REALDATA_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
jacobid=${1:-build}/host-tools/jacobid
out=${2:-out/diagnose_several_ur10e}
data=$(cd "${3:-$here/../../shared/realdata}" && pwd)
[ -x "$jacobid" ] || { echo "measure_diagnose_several_ur10e.sh: no jacobid at '$jacobid'" >&2; exit 2; }
mkdir -p "$out"
printf 'model: urdf\nurdf: %s\ngravity: [0, 0, -9.81]\nfriction: {coulomb: smooth, alpha: auto, offset: true}\nrotor_inertia: true\n' \
    "$data/ur10e/ur10e.urdf" > "$out/ur10e.yaml"
id="$data/ur10e/identification"
one=(--in "$id/ur-20_02_19_14harm50sec.csv")
four=("${one[@]}" --in "$id/ur-20_02_12-50sec_12harm.csv" --in "$id/ur-20_02_10-20sec_7harm.csv" --in "$id/ur-20_02_05-20sec_8harm.csv")
for n in 1 2 3 4 5 6; do
  v="$data/ur10e/validation/ur-20_01_22-joint_$n.csv"
  for tag in one four; do
    if [ "$tag" = one ]; then logs=("${one[@]}"); else logs=("${four[@]}"); fi
    "$jacobid" diagnose --robot "$out/ur10e.yaml" --log-format "$here/../examples/formats/ur10e.yaml" "${logs[@]}" --validate "$v" \
        --format json --quiet > "$out/${tag}_joint_$n.json"
  done
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
for n in range(1, 7):
    for tag in ("one", "four"):
        d = json.load(open(f"{out}/{tag}_joint_{n}.json"))
        named = ", ".join(f"{e['label']} {e['value']:.3g} {e['unit']}" for e in d["effects"]) or "none"
        pairs = "  ".join(f"{b:.3f}->{a:.3f}" for b, a in zip(d["before"]["heldout_rms"], d["after"]["heldout_rms"]))
        print(f"joint_{n} {tag:4s} rows {d['rows']:4d}  held-out RMS (N.m) {pairs}  | {named}")
PY
