#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Presliding friction on the shared UR10e logs (docs/real-data.md, "Presliding friction"): identify on
# 14harm50sec with and without `presliding: dahl`, validate on each joint-at-a-time log, and print each
# joint's filtered RMS error over the five logs in which it stands still (position range below 1e-3 rad,
# the pipeline's motion threshold), the whole-log relative error, and the moving joint's own error.
#
#   bash scripts/measure_presliding_ur10e.sh [BUILD_DIR] [OUTPUT_DIR] [REALDATA_DIR] [extra friction keys] [one|four] [dahl|none]
# one (default): identified on 14harm50sec; four: on the four unloaded Fourier runs together. The compared
# model ("dahl" in the tables) is the plain one with `presliding: dahl` and the extra keys (default), or with
# the extra keys alone (none: e.g. ", coulomb_load: abs" against the plain model).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
jacobid=${1:-build}/host-tools/jacobid
out=${2:-out/presliding_ur10e}
data=$(cd "${3:-$here/../../shared/realdata}" && pwd)
extra=${4:-}
id="$data/ur10e/identification"
inputs=(--in "$id/ur-20_02_19_14harm50sec.csv")
if [ "${5:-one}" = four ]; then
  inputs+=(--in "$id/ur-20_02_12-50sec_12harm.csv" --in "$id/ur-20_02_10-20sec_7harm.csv" --in "$id/ur-20_02_05-20sec_8harm.csv")
fi
[ -x "$jacobid" ] || { echo "measure_presliding_ur10e.sh: no jacobid at '$jacobid'" >&2; exit 2; }
mkdir -p "$out"
for tag in plain dahl; do
  friction="coulomb: smooth, alpha: auto, offset: true"
  if [ "$tag" = dahl ]; then
    if [ "${6:-dahl}" = none ]; then friction="$friction$extra"; else friction="$friction, presliding: dahl$extra"; fi
  fi
  printf 'model: urdf\nurdf: %s\ngravity: [0, 0, -9.81]\nfriction: {%s}\nrotor_inertia: true\n' "$data/ur10e/ur10e.urdf" "$friction" > "$out/$tag.yaml"
  for n in 1 2 3 4 5 6; do
    "$jacobid" identify --robot "$out/$tag.yaml" --log-format "$here/../examples/formats/ur10e.yaml" \
        "${inputs[@]}" \
        --validate "$data/ur10e/validation/ur-20_01_22-joint_$n.csv" --format json --quiet > "$out/${tag}_joint_$n.json"
  done
done
python3 - "$out" <<'PY'
import json, math, sys
out = sys.argv[1]
res = {}
for tag in ("plain", "dahl"):
    still = [[] for _ in range(6)]; rel = []; moving = [0.0] * 6
    for n in range(1, 7):
        v = json.load(open(f"{out}/{tag}_joint_{n}.json"))["methods"]["jacobi"]["validation"]
        rel.append(v["relative_error"])
        for k in range(6):
            if k == n - 1: moving[k] = v["rms_error"][k]
            else: still[k].append(v["rms_error"][k] ** 2)
    res[tag] = ([math.sqrt(sum(s) / len(s)) for s in still], rel, moving)
def show(title, i, fmt):
    print(title)
    for tag in res: print(f"  {tag:6}", " ".join(fmt(x) for x in res[tag][i]))
    print("  change", " ".join(f"{100 * (b / a - 1):+6.0f}%" for a, b in zip(res["plain"][i], res["dahl"][i])))
show("standing-joint RMS error, joints 1..6 (N.m, over the 5 logs where the joint stands):", 0, lambda x: f"{x:7.3f}")
show("whole-log relative error, logs joint_1..6 (%):", 1, lambda x: f"{100 * x:7.1f}")
show("moving joint's own RMS error in its log, joints 1..6 (N.m):", 2, lambda x: f"{x:7.3f}")
PY
