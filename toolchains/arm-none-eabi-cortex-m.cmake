# SPDX-License-Identifier: MIT
# Bare-metal Cortex-M with a hardware FPU (Debian gcc-arm-none-eabi + libstdc++-arm-none-eabi-newlib).
# Builds lib/ (jacobid::core) only: there is no OS, so the top-level project's HAL, host tools, tests and
# benchmarks are switched off below. Choose the core with -DJACOBID_CORTEX_M_CPU=:
#   cortex-m4  (default) Cortex-M4F, single-precision FPU fpv4-sp-d16 (STM32F4, nRF52, ...)
#   cortex-m7  Cortex-M7 with the double-precision FPU fpv5-d16 (STM32F7/H7, i.MX RT)
# No startup code, C library syscalls or heap are linked in by default (-nostartfiles, no nosys.specs):
# an executable that needs malloc, printf or exit fails to link. tests/cross/cortex-m is such a program.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
# Compiler checks must not link (there is no startup code or syscalls to link with).
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(JACOBID_CORTEX_M_CPU "cortex-m4" CACHE STRING "Cortex-M core: cortex-m4 (M4F) or cortex-m7 (M7, double FPU)")
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES JACOBID_CORTEX_M_CPU)
if(JACOBID_CORTEX_M_CPU STREQUAL "cortex-m7")
  set(_jacobid_mcu "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard")
elseif(JACOBID_CORTEX_M_CPU STREQUAL "cortex-m4")
  set(_jacobid_mcu "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
else()
  message(FATAL_ERROR "JACOBID_CORTEX_M_CPU must be cortex-m4 or cortex-m7, not '${JACOBID_CORTEX_M_CPU}'")
endif()
# -fno-exceptions -fno-rtti: the core uses neither; sections per function so the linker drops the unused.
set(CMAKE_C_FLAGS_INIT "${_jacobid_mcu} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT "${_jacobid_mcu} -ffunction-sections -fdata-sections -fno-exceptions -fno-rtti -fno-threadsafe-statics")
set(CMAKE_ASM_FLAGS_INIT "${_jacobid_mcu}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${_jacobid_mcu} -nostartfiles -Wl,--gc-sections")

# Eigen is header-only: the build machine's /usr/share/eigen3 + /usr/include/eigen3 serve the target.
set(CMAKE_FIND_ROOT_PATH /usr/lib/arm-none-eabi /)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Used with the top-level project: only the core makes sense on an MCU.
set(JACOBID_BUILD_HOST_TOOLS OFF CACHE BOOL "")
set(JACOBID_BUILD_TESTS OFF CACHE BOOL "")
set(JACOBID_BUILD_BENCHMARKS OFF CACHE BOOL "")
set(JACOBID_BUILD_HAL OFF CACHE BOOL "")
set(JACOBID_PYTHON OFF CACHE BOOL "")
