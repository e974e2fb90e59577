#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A real robot, straight from its raw logs: a UR10e's real-time data (no header, a 10/12 ms clock with rare
# 2 ms steps, motor currents instead of torques) identified on the 14-harmonic Fourier run, then validated
# on the six joint-at-a-time logs and on the five static poses (gravity check). Numbers in docs/real-data.md.
# The logs are third-party recordings (../shared/realdata/README.md); they are read in place, never copied.
#
#   bash examples/03_identify_ur10e.sh [BUILD_DIR or jacobid executable] [OUTPUT_DIR] [REALDATA_DIR]
set -euo pipefail
name=03_identify_ur10e.sh default_out=out/03_identify_ur10e
source "$(cd "$(dirname "$0")" && pwd)/ur10e_setup.sh"
format="$here/formats/ur10e.yaml"   # columns, currents x drive gains (docs/log-format.md)
train="$data/ur10e/identification/ur-20_02_19_14harm50sec.csv"

"$jacobid" identify --robot "$out/ur10e.yaml" --log-format "$format" --in "$train" --report "$out/report" \
    | tee "$out/identification.txt"
"$jacobid" identify --robot "$out/ur10e.yaml" --log-format "$format" --in "$train" --format json --quiet > "$out/identification.json"
echo
rm -f "$out/validation.stderr.txt"
echo "validation (filtered relative error, per-joint RMS in N.m; messages in $out/validation.stderr.txt):"
for v in "$data"/ur10e/validation/*.csv; do
  name=$(basename "$v" .csv)
  "$jacobid" identify --robot "$out/ur10e.yaml" --log-format "$format" --in "$train" --validate "$v" --format json --quiet \
      > "$out/validate_$name.json" 2>> "$out/validation.stderr.txt"
  /usr/bin/env python3 - "$out/validate_$name.json" "$name" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))["methods"]["jacobi"]
if "static_validation" in j:
    s = j["static_validation"]
    errs = " ".join(f"{e['error']:+.2f}{'' if e['within_friction'] else '!'}" for e in s["joints"])
    print(f"  {sys.argv[2]:<22} static: measured - model {errs} N.m (! outside the Coulomb band), relative {100*s['relative_error']:.1f} %")
else:
    v = j["validation"]
    rms = " ".join(f"{x:.2f}" for x in v["rms_error"])
    print(f"  {sys.argv[2]:<22} moving: relative error {100*v['relative_error']:.1f} %, RMS {rms}")
PY
done
echo "report: $out/report/report.md"
