#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The discrepancy workflow on a real robot (issue 15): `jacobid diagnose` on the UR10e's 14-harmonic Fourier
# run, first with blocked cross-validation on that log alone, then validated on each joint-at-a-time log
# (one joint moves, the others stand still and hold friction). Prints each diagnosis's named effects and the
# held-out torque RMS per joint before -> after; the reports and JSON stay in OUTPUT_DIR. Numbers and what
# they mean: docs/diagnose.md ("The shared UR10e logs"). The logs are read in place, never copied.
#
#   bash examples/04_diagnose_ur10e.sh [BUILD_DIR or jacobid executable] [OUTPUT_DIR] [REALDATA_DIR]
set -euo pipefail
name=04_diagnose_ur10e.sh default_out=out/04_diagnose_ur10e
source "$(cd "$(dirname "$0")" && pwd)/ur10e_setup.sh"
format="$here/formats/ur10e.yaml"
train="$data/ur10e/identification/ur-20_02_19_14harm50sec.csv"

summary() {
  /usr/bin/env python3 - "$1" "$2" <<'PY'
import json, math, sys
d = json.load(open(sys.argv[1]))
fmt = lambda v: "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.3g}"
named = ", ".join(f"{e['label']} {e['value']:.3g} {e['unit']}" for e in d["effects"]) or "none"
print(f"{sys.argv[2]}: {named}")
before, after = d["before"]["heldout_rms"], d["after"]["heldout_rms"]
print("  held-out torque RMS per joint (N.m): " + "  ".join(f"{fmt(b)} -> {fmt(a)}" for b, a in zip(before, after)))
print(f"  verdict: {d['verdict']}")
PY
}

"$jacobid" diagnose --robot "$out/ur10e.yaml" --log-format "$format" --in "$train" --report "$out/report" --format json \
    > "$out/diagnose.json" 2> "$out/diagnose.stderr.txt"
summary "$out/diagnose.json" "14harm50sec, blocked cross-validation"
for j in 1 2 3 4 5 6; do
  v="$data/ur10e/validation/ur-20_01_22-joint_$j.csv"
  "$jacobid" diagnose --robot "$out/ur10e.yaml" --log-format "$format" --in "$train" --validate "$v" --format json \
      > "$out/diagnose_joint_$j.json" 2>> "$out/diagnose.stderr.txt"
  summary "$out/diagnose_joint_$j.json" "validated on joint_$j (joint $j moves)"
done
echo "report: $out/report/report.md"
