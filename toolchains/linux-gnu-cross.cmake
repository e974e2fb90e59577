# SPDX-License-Identifier: MIT
# Shared part of the Debian cross toolchains (included by aarch64-linux-gnu.cmake and
# arm-linux-gnueabihf.cmake, which set JACOBID_TARGET_TRIPLE and CMAKE_SYSTEM_PROCESSOR first).
#
# Compilers: Debian's g++-<triple> (packages g++-aarch64-linux-gnu, g++-arm-linux-gnueabihf).
# Target libraries (libgpiod for hal/), either way:
#  - Debian multiarch ("dpkg --add-architecture arm64; apt-get install libgpiod-dev:arm64"): the target's
#    "sysroot" is / itself, libraries in /usr/lib/<triple>; HAL programs link libgpiod.so.2 (on the board:
#    package libgpiod2);
#  - -DJACOBID_TARGET_SYSROOT=<dir>: a directory with the target's /usr (unpacked Debian packages, as
#    scripts/cross-deps.sh makes without touching dpkg, or a board SDK sysroot), searched first.
# Arch-independent headers and CMake packages (Eigen) come from the build machine's /usr/include and
# /usr/share either way; the cross C/C++ libraries live in /usr/<triple>.
# Tests run under qemu-user (package qemu-user-static) through CMAKE_CROSSCOMPILING_EMULATOR, so
# ctest and gtest_discover_tests work unchanged; set JACOBID_CROSS_EMULATOR="" to disable.
set(CMAKE_SYSTEM_NAME Linux)
# The Python module is for the build machine's interpreter, never cross-built (docs/python.md).
set(JACOBID_PYTHON OFF CACHE BOOL "")
set(CMAKE_LIBRARY_ARCHITECTURE ${JACOBID_TARGET_TRIPLE})

set(CMAKE_C_COMPILER ${JACOBID_TARGET_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${JACOBID_TARGET_TRIPLE}-g++)

# Forward our variables to try_compile projects (the toolchain file is read again there).
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES JACOBID_TARGET_SYSROOT JACOBID_CROSS_EMULATOR)

set(CMAKE_FIND_ROOT_PATH /usr/${JACOBID_TARGET_TRIPLE} /)
if(JACOBID_TARGET_SYSROOT)
  list(PREPEND CMAKE_FIND_ROOT_PATH ${JACOBID_TARGET_SYSROOT})
endif()
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# pkg-config (libgpiod): only the target's .pc files, never the build machine's. With a sysroot (unpacked
# packages, a board SDK), its .pc files and paths; otherwise the multiarch ones.
if(JACOBID_TARGET_SYSROOT)
  set(ENV{PKG_CONFIG_LIBDIR} "${JACOBID_TARGET_SYSROOT}/usr/lib/${JACOBID_TARGET_TRIPLE}/pkgconfig:${JACOBID_TARGET_SYSROOT}/usr/lib/pkgconfig:${JACOBID_TARGET_SYSROOT}/usr/share/pkgconfig")
  set(ENV{PKG_CONFIG_SYSROOT_DIR} "${JACOBID_TARGET_SYSROOT}")
else()
  set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/${JACOBID_TARGET_TRIPLE}/pkgconfig:/usr/share/pkgconfig")
  unset(ENV{PKG_CONFIG_SYSROOT_DIR})
endif()
unset(ENV{PKG_CONFIG_PATH})

# Run target executables (tests, gtest discovery) with qemu-user and the cross C library as root.
if(NOT DEFINED JACOBID_CROSS_EMULATOR)
  find_program(_jacobid_qemu NAMES qemu-${JACOBID_QEMU_ARCH}-static qemu-${JACOBID_QEMU_ARCH})
  if(_jacobid_qemu)
    set(JACOBID_CROSS_EMULATOR "${_jacobid_qemu};-L;/usr/${JACOBID_TARGET_TRIPLE}")
  else()
    set(JACOBID_CROSS_EMULATOR "")
  endif()
endif()
if(JACOBID_CROSS_EMULATOR)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${JACOBID_CROSS_EMULATOR}")
endif()
