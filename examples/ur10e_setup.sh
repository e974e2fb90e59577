# SPDX-License-Identifier: MIT
# Sourced by the UR10e examples (03_identify_ur10e.sh, 06_drive_gains_ur10e.sh) with their arguments
# [BUILD_DIR or jacobid executable] [OUTPUT_DIR] [REALDATA_DIR] and $name, $default_out set: resolves
# $jacobid, $out (created), $data (absolute) and writes the robot description $out/ur10e.yaml.
here=$(cd "$(dirname "$0")" && pwd)
arg=${1:-build}
if [ -d "$arg" ]; then jacobid="$arg/host-tools/jacobid"; else jacobid="$arg"; fi
[ -x "$jacobid" ] || { echo "$name: no jacobid executable at '$jacobid'" >&2; exit 2; }
out=${2:-$default_out}
data=${3:-$here/../../shared/realdata}
[ -d "$data/ur10e" ] || { echo "$name: no UR10e logs in '$data/ur10e' (give REALDATA_DIR)" >&2; exit 2; }
data=$(cd "$data" && pwd)
mkdir -p "$out"

# The manufacturer-like URDF of the source repository for the geometry and the prior; viscous + smoothed
# Coulomb friction (its smoothing chosen per joint from the data: alpha auto) with an offset and a rotor
# inertia per joint, as that repository's model has.
cat > "$out/ur10e.yaml" <<YAML
model: urdf
urdf: $data/ur10e/ur10e.urdf
gravity: [0, 0, -9.81]
friction: {coulomb: smooth, alpha: auto, offset: true}
rotor_inertia: true
YAML
