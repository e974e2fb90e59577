#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# diagnose --export-robot on the UR10e, closed in files (issue 40; docs/real-data.md, "The diagnosed description"):
# diagnose the robot of examples/03_identify_ur10e.sh on 14harm50sec, export the description with the named
# effects, then identify on 14harm50sec with the default description and with the exported one, each validated
# on every jointwise and static log. Prints one line per validation log and description.
# Usage: scripts/measure_diagnose_export_ur10e.sh BUILD_DIR OUT_DIR REALDATA_DIR
set -euo pipefail
name=measure_diagnose_export_ur10e.sh default_out=out/measure_diagnose_export_ur10e
here_script="$(cd "$(dirname "$0")" && pwd)"
# jacobid, out, data and $out/ur10e.yaml (the default description of examples/03_identify_ur10e.sh)
source "$here_script/../examples/ur10e_setup.sh"
format="$here_script/../examples/formats/ur10e.yaml"
train="$data/ur10e/identification/ur-20_02_19_14harm50sec.csv"
cp "$out/ur10e.yaml" "$out/default.yaml"
"$jacobid" diagnose --robot "$out/default.yaml" --log-format "$format" --in "$train" --export-robot "$out/exported.yaml" --quiet > "$out/diagnose.txt"
grep -E "^exported|not in the description" "$out/diagnose.txt"
for description in default exported; do
  for v in "$data"/ur10e/validation/*.csv; do
    name=$(basename "$v" .csv)
    "$jacobid" identify --robot "$out/$description.yaml" --log-format "$format" --in "$train" --validate "$v" --format json --quiet \
        > "$out/${description}_$name.json" 2>> "$out/messages.txt"
    python3 - "$out/${description}_$name.json" "$description" "$name" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))["methods"]["jacobi"]
head = f"{sys.argv[2]:<9} {sys.argv[3]:<16}"
if "static_validation" in j:
    s = j["static_validation"]
    print(head, "static relative %5.1f %%  measured - model" % (100 * s["relative_error"]), " ".join("%+.2f" % e["error"] for e in s["joints"]))
else:
    v = j["validation"]
    print(head, "moving relative %5.1f %%  RMS" % (100 * v["relative_error"]), " ".join("%.3f" % x for x in v["rms_error"]))
PY
  done
done
