#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configures and builds jacobid (Release) into ${JACOBID_BUILD_DIR:-build}: every target, or the ones named.
#   scripts/build.sh [target...]      e.g. scripts/build.sh jacobid (the command line and its libraries only)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
source "$root/scripts/ccache-env.sh"
build="${JACOBID_BUILD_DIR:-$root/build}"
# -march=native by default: the streaming tick meets its 0.5 us target only with the machine's SIMD width
# (docs/performance.md); set JACOBID_MARCH= (empty) for a portable build.
# Unity batches for the host tools: half the compile time of a clean build (CMakeLists.txt, JACOBID_UNITY_HOST_TOOLS).
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DJACOBID_MARCH="${JACOBID_MARCH-native}" -DJACOBID_UNITY_HOST_TOOLS=ON -DJACOBID_UNITY_BATCH_SIZE=4 ${JACOBID_CMAKE_ARGS:-} >/dev/null
targets=()
[ $# -eq 0 ] || targets=(--target "$@")
cmake --build "$build" -j "$(nproc)" "${targets[@]}"
