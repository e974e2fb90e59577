#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Cross builds and their tests (docs/targets.md):
#  1. aarch64 and armhf (toolchains/*-linux-gnu*.cmake): GoogleTest compiled from Debian's sources with
#     the cross compiler, jacobid's core + HAL + unit tests cross-compiled, `ctest -L unit` run under
#     qemu-user; then tests/cross/golden compares the core's numbers with the native build's.
#  2. Cortex-M4F and M7 (toolchains/arm-none-eabi-cortex-m.cmake): lib/ alone in a bare-metal program
#     linked with no heap and no syscalls; a program with `new` must fail to link; sizes printed.
# Usage: scripts/cross-test.sh [--build-only] [aarch64|armhf|cortex-m]...   (default: all three).
# Build dirs build-cross-<target>; --build-only skips the tests (scripts/vm-test.sh uses it).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
source "$root/scripts/ccache-env.sh"
cd "$root"
build_only=""
if [ "${1:-}" = --build-only ]; then build_only=1; shift; fi
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(aarch64 armhf cortex-m)
jobs="$(nproc)"
sysroots="${JACOBID_CROSS_SYSROOTS:-$root/build-cross-sysroot}"
timing=()
now() { date +%s; }

bash "$root/scripts/cross-deps.sh"

linux_target() {  # $1 = aarch64 | armhf
  local name="$1" toolchain debarch start
  case "$name" in
    aarch64) toolchain=aarch64-linux-gnu debarch=arm64 ;;
    armhf) toolchain=arm-linux-gnueabihf debarch=armhf ;;
  esac
  local b="$root/build-cross-$name" tc="$root/toolchains/$toolchain.cmake"
  start=$(now)
  local gtest_dir
  gtest_dir="$(bash "$root/scripts/cross-gtest.sh" "$name")"
  cmake -S "$root" -B "$b" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$tc" -DCMAKE_BUILD_TYPE=Release \
    -DJACOBID_TARGET_SYSROOT="$sysroots/$debarch" -DGTest_DIR="$gtest_dir" \
    -DJACOBID_BUILD_HOST_TOOLS=OFF -DJACOBID_BUILD_BENCHMARKS=OFF -DJACOBID_BUILD_FIRMWARE=OFF \
    -DJACOBID_VM_TESTS=ON -DJACOBID_PYTHON=OFF ${JACOBID_CROSS_CMAKE_ARGS:-} >/dev/null
  cmake --build "$b" -j "$jobs"
  if [ -n "$build_only" ]; then
    timing+=("$name build: $(( $(now) - start )) s")
    return
  fi
  echo "cross-test: $name: unit tests under $(grep -o 'qemu-[a-z0-9_]*-static' "$b/CMakeCache.txt" | head -1)"
  ctest --test-dir "$b" -L unit -j "$jobs" --output-on-failure --timeout 600
  # Same numbers as the native build (tests/cross/golden): run under the toolchain's qemu-user.
  local native="$root/build-cross-golden-native"
  if [ ! -x "$native/jacobid_golden" ]; then
    cmake -S "$root/tests/cross/golden" -B "$native" -G Ninja >/dev/null && cmake --build "$native" >/dev/null
  fi
  cmake -S "$root/tests/cross/golden" -B "$b/golden" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$tc" >/dev/null
  cmake --build "$b/golden" >/dev/null
  "$native/jacobid_golden" > "$b/golden/native.txt"
  local qemu verdict
  qemu="$(sed -n 's/^_jacobid_qemu:FILEPATH=//p' "$b/golden/CMakeCache.txt")"
  "$qemu" -L "/usr/$toolchain" "$b/golden/jacobid_golden" > "$b/golden/$name.txt"
  verdict="$(python3 "$root/tests/cross/golden/compare.py" "$b/golden/native.txt" "$b/golden/$name.txt")" || {
    echo "$verdict" >&2; echo "cross-test: $name: results differ from the native build" >&2; exit 1; }
  echo "cross-test: $name vs native: $verdict"
  timing+=("$name build+unit tests under qemu-user: $(( $(now) - start )) s")
}

cortex_m() {
  local cpu start b
  start=$(now)
  for cpu in cortex-m4 cortex-m7; do
    b="$root/build-cross-$cpu"
    cmake -S "$root/tests/cross/cortex-m" -B "$b" -G Ninja -DCMAKE_BUILD_TYPE=MinSizeRel \
      -DCMAKE_TOOLCHAIN_FILE="$root/toolchains/arm-none-eabi-cortex-m.cmake" -DJACOBID_CORTEX_M_CPU=$cpu >/dev/null
    cmake --build "$b" -j "$jobs" >/dev/null
    local elf="$b/jacobid_cortex_m_bank.elf"
    # No heap, no OS: none of these may be in the image (the link would have failed already; belt and braces).
    if arm-none-eabi-nm "$elf" | grep -E ' (malloc|_malloc_r|free|_free_r|_sbrk|_sbrk_r|_write|_exit|abort|_Znwj|_Znaj)$'; then
      echo "cross-test: $cpu: heap or OS symbols linked into $elf" >&2; exit 1
    fi
    # Negative control: a program with `new` must not link.
    if cmake --build "$b" --target jacobid_cortex_m_heap_canary >"$b/heap_canary.log" 2>&1; then
      echo "cross-test: $cpu: a program using new linked: the no-heap link check is not working" >&2; exit 1
    fi
    grep -q "undefined reference to \`__wrap_malloc'" "$b/heap_canary.log" || {
      cat "$b/heap_canary.log" >&2; echo "cross-test: $cpu: heap canary failed for another reason" >&2; exit 1; }
    echo "cross-test: $cpu: 6-joint bank linked without heap or syscalls (a program with new fails: __wrap_malloc undefined)"
    arm-none-eabi-size -A "$elf" | awk '$1 ~ /^\.(isr_vector|text|ARM.exidx|init_array|data|bss|stack)$/'
    arm-none-eabi-size -B "$elf"
  done
  timing+=("cortex-m4 + cortex-m7 builds: $(( $(now) - start )) s")
}

for t in "${targets[@]}"; do
  case "$t" in
    aarch64|armhf) linux_target "$t" ;;
    cortex-m) cortex_m ;;
    *) echo "cross-test: unknown target $t (aarch64, armhf, cortex-m)" >&2; exit 2 ;;
  esac
done
printf 'cross-test: %s\n' "${timing[@]}"
