#!/usr/bin/env bash
# Configures and builds jacobid (Release) into ${JACOBID_BUILD_DIR:-build}.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${JACOBID_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release ${JACOBID_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j "$(nproc)"
