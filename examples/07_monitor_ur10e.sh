#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Contact detection on the real UR10e (docs/monitor.md, docs/real-data.md "Contact monitoring"): the model
# identified from 14harm50sec (identify --export-robot), thresholds calibrated on the shared contact-free logs
# (identification and validation, moving and static; not the 2.805 kg payload run, whose load the model does
# not know), then
#   - leave one out: each contact-free log replayed with thresholds calibrated on all the others: its alarms;
#   - the push log (a person pushes the standing arm) replayed with thresholds from every contact-free log.
# The logs are read in place, never copied.
#
#   bash examples/07_monitor_ur10e.sh [BUILD_DIR or jacobid executable] [OUTPUT_DIR] [REALDATA_DIR]
set -euo pipefail
name=07_monitor_ur10e.sh default_out=out/07_monitor_ur10e
source "$(cd "$(dirname "$0")" && pwd)/ur10e_setup.sh"
format="$here/formats/ur10e.yaml"
train="$data/ur10e/identification/ur-20_02_19_14harm50sec.csv"
push="$data/ur10e/collision/ur-20_01_22-push_pose_1.csv"
free=()
for f in "$data"/ur10e/identification/*.csv "$data"/ur10e/validation/*.csv; do
  case "$f" in *Load.csv) ;; *) free+=("$f") ;; esac
done

# MONITOR_DESCRIPTION=FILE identifies with another description, e.g. the one `diagnose --export-robot` writes
# (scripts/measure_diagnose_export_ur10e.sh); the default one monitors better (docs/real-data.md, "The diagnosed description").
"$jacobid" identify --robot "${MONITOR_DESCRIPTION:-$out/ur10e.yaml}" --log-format "$format" --in "$train" --export-robot "$out/identified.yaml" --quiet > /dev/null
rm -f "$out/messages.txt"
calibrate() {  # calibrate OUT.yaml LOG... (the options of every calibration here)
  local file=$1; shift
  local ins=()
  for f in "$@"; do ins+=(--in "$f"); done
  "$jacobid" monitor calibrate --robot "$out/identified.yaml" --log-format "$format" "${ins[@]}" --out "$file" "${MONITOR_OPTIONS[@]}" 2>> "$out/messages.txt"
}
# MONITOR_CALIBRATION="--false-alarm-rate 0" (say) changes the calibration of every step. The default: a joint stands
# after 0.3 s below 0.02 rad/s (the gear's ringing after a hard stop is motion) and holds up to 1.2 x its Coulomb level
# at rest, the elbow (joint 3) 1.4 x (break-away above sliding friction); docs/real-data.md, "Break-away and ringing".
read -r -a MONITOR_OPTIONS <<< "${MONITOR_CALIBRATION:---false-alarm-rate 1e-4 --margin 0.5 --confirm 2 --standing-time 0.3 --band-margin 0.2,0.2,0.4,0.2,0.2,0.2}"

echo "leave one out: alarms on each contact-free log, thresholds calibrated on the $(( ${#free[@]} - 1 )) others"
total=0
for tested in "${free[@]}"; do
  others=()
  for f in "${free[@]}"; do [ "$f" = "$tested" ] || others+=("$f"); done
  calibrate "$out/loo.yaml" "${others[@]}" > /dev/null
  events=$("$jacobid" monitor --robot "$out/identified.yaml" --log-format "$format" --monitor "$out/loo.yaml" --in "$tested" --json 2>> "$out/messages.txt" \
    | python3 -c 'import json,sys; e=json.load(sys.stdin)["events"]; print(len(e), " ".join("%.2f-%.2f s j%s" % (x["start"], x["end"], ",".join(map(str, x["joints"]))) for x in e))')
  echo "  $(basename "$tested" .csv): $events"
  total=$(( total + ${events%% *} ))
done
echo "  false alarms in all: $total"

echo
calibrate "$out/monitor.yaml" "${free[@]}" | tee "$out/calibration.txt"
echo
echo "push log (a person pushes the standing arm):"
"$jacobid" monitor --robot "$out/identified.yaml" --log-format "$format" --monitor "$out/monitor.yaml" --in "$push" --plot "$out/push.png" \
  --estimates "$out/push_estimates.csv" 2>> "$out/messages.txt" | tee "$out/push.txt"
"$jacobid" monitor --robot "$out/identified.yaml" --log-format "$format" --monitor "$out/monitor.yaml" --in "$push" --json 2>> "$out/messages.txt" > "$out/push.json"
echo "figure: $out/push.png"
