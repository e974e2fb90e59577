#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# GoogleTest for a cross target, compiled from Debian's googletest sources (package googletest) with the
# target's toolchain into build-cross-<arch>/googletest-install, unless it is there already. Used by
# scripts/cross-test.sh (unit tests under qemu-user) and scripts/vm-test.sh (the board build).
#   scripts/cross-gtest.sh aarch64|armhf      prints the GTest_DIR to pass to cmake
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
source "$root/scripts/ccache-env.sh"
case "${1:-}" in
  aarch64) toolchain=aarch64-linux-gnu ;;
  armhf) toolchain=arm-linux-gnueabihf ;;
  *) echo "usage: $0 aarch64|armhf" >&2; exit 2 ;;
esac
b="$root/build-cross-$1"
if [ ! -e "$b/googletest-install/lib/cmake/GTest/GTestConfig.cmake" ]; then
  echo "cross-gtest: building GoogleTest for $1 (/usr/src/googletest)" >&2
  cmake -S /usr/src/googletest -B "$b/googletest" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$root/toolchains/$toolchain.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$b/googletest-install" >/dev/null
  cmake --build "$b/googletest" -j "$(nproc)" >/dev/null
  cmake --install "$b/googletest" >/dev/null
fi
echo "$b/googletest-install/lib/cmake/GTest"
