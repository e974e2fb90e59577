#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The UR10e's 2.805 kg payload from the shared 14harm50sec / 14harm50secLoad pair (jacobid payload,
# docs/identify.md "Payload"), with drive gains never fitted on the samples the payload is measured on: each
# log is cut at the middle of its own time span; the gains come from identify --drive-gains on one half of
# the pair, the arm from identify on the other half's unloaded run, the payload from that half's loaded run
# (minus its unloaded run, and against the arm model alone), then the other way round. Last, the same with
# the source repository's gains on the whole runs (the 2.44 kg of docs/real-data.md). Two gain sets per half:
# the weighted least squares' (WLS) and the total least squares' (TLS, which corrects the LS gains' pull towards
# 0 from the noise and model error in the current column). --gain-std is the WLS gains' relative std (TLS gives
# none of its own). Numbers in docs/real-data.md, "Payload". The logs are read in place; only the halves
# (derived) go to OUTPUT_DIR.
#
#   bash examples/05_payload_ur10e.sh [BUILD_DIR or jacobid executable] [OUTPUT_DIR] [REALDATA_DIR]
set -euo pipefail
name=05_payload_ur10e.sh default_out=out/05_payload_ur10e
source "$(cd "$(dirname "$0")" && pwd)/ur10e_setup.sh"
format="$here/formats/ur10e.yaml"   # currents x the source repository's gains
ident="$data/ur10e/identification"
unloaded="$ident/ur-20_02_19_14harm50sec.csv" loaded="$ident/ur-20_02_19_14harm50secLoad.csv"
robot="$out/ur10e.yaml"

# Halves: rows before / after the middle of each log's own time span (raw rows, unchanged).
python3 - "$unloaded" "$loaded" "$out" <<'PY'
import sys
for path, tag in ((sys.argv[1], "u"), (sys.argv[2], "l")):
    rows = open(path).read().splitlines()
    t = [float(r.split(",", 1)[0]) for r in rows]
    mid = 0.5 * (t[0] + t[-1])
    open(f"{sys.argv[3]}/{tag}1.csv", "w").write("\n".join(r for r, x in zip(rows, t) if x < mid) + "\n")
    open(f"{sys.argv[3]}/{tag}2.csv", "w").write("\n".join(r for r, x in zip(rows, t) if x >= mid) + "\n")
PY

# A log format whose gains: are one estimator's gains of a drive-gain fit (prior x factor), and the relative std
# of the WLS gains as --gain-std.
gain_format() {  # gains.json out.yaml wls|tls -> prints the --gain-std list
  python3 - "$1" "$2" "$format" "$3" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["drive_gains"]
g = d["estimators"][sys.argv[4]]["gains"]
s = [j["std"] / j["gain"] for j in d["joints"]]
text = [l for l in open(sys.argv[3]) if not l.startswith("gains:")]
open(sys.argv[2], "w").writelines(text + ["gains: [" + ", ".join(f"{x:.6g}" for x in g) + "]\n"])
print(",".join(f"{x:.4g}" for x in s))
PY
}

summary() {  # payload.json label
  python3 - "$1" "$2" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
m = p["payload"]["mass"]; c = [p["payload"][k] for k in ("com_x", "com_y", "com_z")]
shift = f", shift {p['alignment']['shift_seconds']:+.3f} s" if p.get("alignment") else ""
print(f"{sys.argv[2]:<44} mass {m['value']:.3f} +- {m['std']:.3f} kg ({100 * (m['value'] / 2.805 - 1):+.1f} % of 2.805; noise {m['std_noise']:.3f}, "
      f"arm {m['std_arm']:.3f}, gains {m['std_gain']:.3f}), CoM ({', '.join('%.3f' % x['value'] for x in c)}) m{shift}")
PY
}

for pair in "1 2" "2 1"; do
  set -- $pair; g=$1 p=$2
  "$jacobid" identify --robot "$robot" --log-format "$format" --drive-gains --in "$out/u$g.csv" --loaded "$out/l$g.csv" \
      --payload-mass 2.805 --quiet --format json > "$out/gains_half$g.json"
  for est in wls tls; do
    tag="half${p}_${est}_gains$g"
    gain_std=$(gain_format "$out/gains_half$g.json" "$out/format_$tag.yaml" $est)
    "$jacobid" identify --robot "$robot" --log-format "$out/format_$tag.yaml" --in "$out/u$p.csv" --quiet --format json > "$out/arm_$tag.json"
    "$jacobid" payload --robot "$robot" --log-format "$out/format_$tag.yaml" --arm "$out/arm_$tag.json" --in "$out/l$p.csv" \
        --unloaded "$out/u$p.csv" --gain-std "$gain_std" --frame tool0 --quiet --json > "$out/payload_$tag.json"
    summary "$out/payload_$tag.json" "half $p, $est gains of half $g, minus unloaded"
    "$jacobid" payload --robot "$robot" --log-format "$out/format_$tag.yaml" --arm "$out/arm_$tag.json" --in "$out/l$p.csv" \
        --gain-std "$gain_std" --frame tool0 --quiet --json > "$out/payload_${tag}_arm.json"
    summary "$out/payload_${tag}_arm.json" "half $p, $est gains of half $g, arm model only"
  done
done

# The source repository's gains (the shipped format), whole runs: the arm identified on the unloaded run.
"$jacobid" identify --robot "$robot" --log-format "$format" --in "$unloaded" --quiet --format json > "$out/arm_source.json"
"$jacobid" payload --robot "$robot" --log-format "$format" --arm "$out/arm_source.json" --in "$loaded" --unloaded "$unloaded" \
    --frame tool0 --quiet | tee "$out/payload_source.txt" | head -n 20
"$jacobid" payload --robot "$robot" --log-format "$format" --arm "$out/arm_source.json" --in "$loaded" --unloaded "$unloaded" \
    --frame tool0 --quiet --json --export-urdf "$out/payload.urdf" --export-robot "$out/ur10e_with_payload.yaml" > "$out/payload_source.json"
summary "$out/payload_source.json" "whole runs, source gains, minus unloaded"
"$jacobid" payload --robot "$robot" --log-format "$format" --arm "$out/arm_source.json" --in "$loaded" --frame tool0 --quiet --json \
    > "$out/payload_source_arm.json"
summary "$out/payload_source_arm.json" "whole runs, source gains, arm model only"
