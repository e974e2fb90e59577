#!/usr/bin/env bash
# Cross-compilation dependencies (Debian 12 packages; root or sudo):
#  - toolchains: g++-aarch64-linux-gnu, g++-arm-linux-gnueabihf, gcc-arm-none-eabi + its newlib libstdc++;
#  - qemu-user-static: runs the aarch64/armhf test executables on this machine (ctest, no binfmt needed);
#  - target libgpiod (hal/): Debian's libgpiod-dev for arm64/armhf, unpacked into
#    build-cross-sysroot/<arch> (scripts/cross-sysroot.sh; dpkg's architectures are left alone). Only
#    the static library is kept, so target programs carry libgpiod and run under qemu-user as they are.
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
echo "cross-deps: toolchains and target sysroots ready ($sysroots)"
