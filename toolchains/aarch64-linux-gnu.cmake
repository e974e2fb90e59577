# SPDX-License-Identifier: MIT
# 64-bit Arm Linux controller boards (Raspberry Pi 4/5 with a 64-bit OS, i.MX8, Jetson, RK3588, ...).
#   apt-get install g++-aarch64-linux-gnu qemu-user-static
#   dpkg --add-architecture arm64 && apt-get update && apt-get install libgpiod-dev:arm64   # for hal/
#   cmake -S . -B build-cross-aarch64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake \
#         -DJACOBID_BUILD_HOST_TOOLS=OFF -DJACOBID_BUILD_BENCHMARKS=OFF
# scripts/cross-test.sh does all of it, GoogleTest for the target included (docs/targets.md).
# jacobid-fw and jacobid for the board also need libfmt-dev:arm64 libyaml-cpp-dev:arm64 libfftw3-dev:arm64
# liburdfdom-dev:arm64 (or -DJACOBID_TARGET_SYSROOT=build-cross-sysroot/arm64-board from scripts/cross-deps.sh);
# scripts/vm-test.sh aarch64 builds them and runs them on the emulated board.
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(JACOBID_TARGET_TRIPLE aarch64-linux-gnu)
set(JACOBID_QEMU_ARCH aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-cross.cmake)
