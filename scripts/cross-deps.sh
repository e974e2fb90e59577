#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Cross-compilation dependencies (Debian 12 packages; root or sudo):
#  - toolchains: g++-aarch64-linux-gnu, g++-arm-linux-gnueabihf, gcc-arm-none-eabi + its newlib libstdc++;
#  - qemu-user-static: runs the aarch64/armhf test executables on this machine (ctest, no binfmt needed);
#  - target libgpiod (hal/): Debian's libgpiod-dev for arm64/armhf, unpacked into
#    build-cross-sysroot/<arch> (scripts/cross-sysroot.sh; dpkg's architectures are left alone). Only
#    the static library is kept, so target programs carry libgpiod and run under qemu-user as they are.
#  - the emulated controller board (scripts/vm-test.sh aarch64): jacobid-fw and jacobid for arm64 need
#    fmt, yaml-cpp and FFTW as well (CLI11, nlohmann-json, fast_float and Eigen are header-only and come
#    from the build machine). build-cross-sysroot/arm64-board holds Debian's arm64 -dev packages and their
#    runtime libraries, as a Debian board has them installed; the VM harness copies the shared libraries
#    the executables need into the initramfs (readelf's NEEDED, resolved in the sysroot).
# GoogleTest for the target is compiled from Debian's googletest sources by scripts/cross-test.sh.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
packages=(g++-aarch64-linux-gnu g++-arm-linux-gnueabihf gcc-arm-none-eabi libstdc++-arm-none-eabi-newlib
          qemu-user-static googletest libeigen3-dev cmake ninja-build pkg-config python3)
bash "$root/scripts/cross-apt-install.sh" "${packages[@]}"
sysroots="${JACOBID_CROSS_SYSROOTS:-$root/build-cross-sysroot}"
for arch in arm64 armhf; do
  if [ ! -e "$sysroots/$arch/.complete" ]; then
    rm -rf "${sysroots:?}/$arch"
    bash "$root/scripts/cross-sysroot.sh" "$arch" "$sysroots/$arch" libgpiod-dev
    find "$sysroots/$arch/usr/lib" -name 'libgpiod*.so*' -delete
    touch "$sysroots/$arch/.complete"
  fi
done
# The board's packages: every library jacobid-fw and jacobid link (host-tools/**/CMakeLists.txt and
# sources.cmake; a new host-tools dependency needs its arm64 packages here). Re-made when the list changes.
board_packages=(libgpiod-dev libgpiod2 libfmt-dev libfmt9 libyaml-cpp-dev libyaml-cpp0.7 libfftw3-dev libfftw3-double3
  liburdfdom-dev liburdfdom-headers-dev liburdfdom-model3.0 liburdfdom-model-state3.0 liburdfdom-sensor3.0
  liburdfdom-world3.0 libconsole-bridge-dev libconsole-bridge1.0 libtinyxml-dev libtinyxml2.6.2v5)
board="$sysroots/arm64-board"
if [ "$(cat "$board/.complete" 2>/dev/null)" != "${board_packages[*]}" ]; then
  rm -rf "$board"
  bash "$root/scripts/cross-sysroot.sh" arm64 "$board" "${board_packages[@]}"
  echo "${board_packages[*]}" > "$board/.complete"
fi
echo "cross-deps: toolchains and target sysroots ready ($sysroots)"
