#!/usr/bin/env bash
# README command 2: installs the dependencies, builds, and runs every test (unit, integration, install/consume).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
ctest --test-dir "${JACOBID_BUILD_DIR:-$root/build}" -j "$(nproc)" --output-on-failure --timeout 600
