# SPDX-License-Identifier: MIT
# 32-bit Arm Linux controller boards with hardware float (ARMv7-A: BeagleBone, Raspberry Pi 2/3 with a
# 32-bit OS, i.MX6, STM32MP1, ...). Debian's armhf baseline: -march=armv7-a -mfpu=vfpv3-d16 -mthumb.
#   apt-get install g++-arm-linux-gnueabihf qemu-user-static
#   dpkg --add-architecture armhf && apt-get update && apt-get install libgpiod-dev:armhf   # for hal/
#   cmake -S . -B build-cross-armhf -G Ninja -DCMAKE_TOOLCHAIN_FILE=toolchains/arm-linux-gnueabihf.cmake \
#         -DJACOBID_BUILD_HOST_TOOLS=OFF -DJACOBID_BUILD_BENCHMARKS=OFF
# Add board-specific flags with -DCMAKE_CXX_FLAGS="-mcpu=cortex-a7 -mfpu=neon-vfpv4" and the like.
set(CMAKE_SYSTEM_PROCESSOR armv7l)
set(JACOBID_TARGET_TRIPLE arm-linux-gnueabihf)
set(JACOBID_QEMU_ARCH arm)
# -Wno-psabi: silences GCC's "parameter passing ... changed in GCC 7.1" notes (ABI notices about code built
# with GCC < 7.1, which nothing here is).
set(CMAKE_CXX_FLAGS_INIT "-Wno-psabi")
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-cross.cmake)
