#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 1: installs the dependencies, builds, and runs the main job: simulate the paper-like 2R
# robot, identify it with the Jacobi pipeline and the Butterworth baseline, print the Table II comparison
# next to the truth, and write the report with plots (examples/01_identify_planar2r.sh).
# Only what the main job needs: the main job's packages (install-deps.sh --main) and the `jacobid` target
# with its libraries; the tests, benchmarks, examples and the Python module wait for scripts/run-tests.sh,
# which builds the rest in the same build directory.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh" --main
"$root/scripts/build.sh" jacobid
bash "$root/examples/01_identify_planar2r.sh" "${JACOBID_BUILD_DIR:-$root/build}" "${JACOBID_OUT_DIR:-$root/out}/01_identify_planar2r"
