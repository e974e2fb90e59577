#!/usr/bin/env bash
# README command 1: installs the dependencies, builds, and runs the main job.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
out="${JACOBID_OUT_DIR:-$root/out}"
mkdir -p "$out"
"${JACOBID_BUILD_DIR:-$root/build}/host-tools/jacobid" paper-sines --out-dir "$out/paper-sines"
