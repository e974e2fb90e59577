#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The tests that need a kernel with CAN or a GPIO chip (ctest labels vcan, vm, gpio; docs/targets.md):
#  1. this machine's build (build-vm): vcan.host runs the SocketCAN tests directly if vcan interfaces can
#     be made here (else skipped, the reason printed), vm.x86_64.hal-vcan runs them in qemu-system-x86_64
#     with Debian's kernel, and, with JACOBID_VM_CHAIN=1, vm.x86_64.chain: the full chain sim-can -> vcan0
#     -> jacobid-fw -> UDP -> record -> identify there (build-vm's own jacobid + jacobid-fw, without
#     -march=native: qemu's TCG has no AVX-512). Opt-in: the aarch64 board below runs the same chain with
#     the identification gated; the x86_64 one adds ~5 min of build and VM time (docs/targets.md).
#  2. the emulated controller board (build-vm-aarch64: jacobid-board, the board's sim-can and record, jacobid-fw
#     and the static VM test binaries cross-built for arm64; nothing of identification) in qemu-system-aarch64
#     -M virt: vm.aarch64.hal-vcan, vm.aarch64.hal-gpio (PL061), vm.aarch64.board (sim-can -> vcan0 ->
#     jacobid-fw with GPIO -> UDP -> record on the board; the log identified on this machine by the native
#     build's jacobid, gated on the bars) and vm.aarch64.board-load (6 joints, 1 kHz, 60 s;
#     JACOBID_VM_LOAD=0 leaves it out).
# Usage: scripts/vm-test.sh [x86_64|aarch64]...   (default: both; JACOBID_VM_ARCHES likewise)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
source "$root/scripts/ccache-env.sh"
cd "$root"
arches=("$@")
[ ${#arches[@]} -gt 0 ] || arches=(${JACOBID_VM_ARCHES:-x86_64 aarch64})
jobs="$(nproc)"
timing=()
now() { date +%s; }

start=$(now)
JACOBID_VM_ARCHES="${arches[*]}" bash "$root/scripts/vm-deps.sh"
timing+=("VM packages + kernels: $(( $(now) - start )) s")

for arch in "${arches[@]}"; do
  start=$(now)
  case "$arch" in
    x86_64)
      b="$root/build-vm"
      if [ "${JACOBID_VM_CHAIN:-0}" = "1" ]; then
        cmake -S "$root" -B "$b" -G Ninja -DCMAKE_BUILD_TYPE=Release -DJACOBID_BUILD_HOST_TOOLS=ON \
          -DJACOBID_BUILD_BENCHMARKS=OFF -DJACOBID_BUILD_FIRMWARE=ON -DJACOBID_VM_TESTS=ON -DJACOBID_MARCH= \
          -DJACOBID_BUILD_TESTS=OFF -DJACOBID_PYTHON=OFF >/dev/null
        cmake --build "$b" -j "$jobs" --target jacobid-vcan-link test_hal_vcan jacobid jacobid-fw
        ctest --test-dir "$b" -L 'vcan|chain' --output-on-failure
      else
        cmake -S "$root" -B "$b" -G Ninja -DCMAKE_BUILD_TYPE=Release -DJACOBID_BUILD_HOST_TOOLS=OFF \
          -DJACOBID_BUILD_BENCHMARKS=OFF -DJACOBID_BUILD_FIRMWARE=OFF -DJACOBID_VM_TESTS=ON -DJACOBID_BUILD_TESTS=OFF -DJACOBID_PYTHON=OFF >/dev/null
        cmake --build "$b" -j "$jobs" --target jacobid-vcan-link test_hal_vcan
        ctest --test-dir "$b" -L vcan -LE chain --output-on-failure
      fi
      # ctest does not show a skipped test's output: the reason vcan.host did not run here.
      sed -n 's/^\(vcan.host: SKIPPED: .*\)$/vm-test: \1/p' "$b/Testing/Temporary/LastTest.log" || true
      ;;
    aarch64)
      # The emulated controller board: jacobid-fw and jacobid-board cross-built for arm64 against Debian's arm64
      # libraries (scripts/cross-deps.sh: build-cross-sysroot/arm64-board), only the targets the VM runs.
      b="$root/build-vm-aarch64"
      # The board's log is identified here, by the native build's jacobid (built if missing).
      host_jacobid="${JACOBID_BUILD_DIR:-$root/build}/host-tools/jacobid"
      [ -x "$host_jacobid" ] || bash "$root/scripts/build.sh" jacobid
      bash "$root/scripts/cross-deps.sh"
      gtest_dir="$(bash "$root/scripts/cross-gtest.sh" aarch64)"
      cmake -S "$root" -B "$b" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$root/toolchains/aarch64-linux-gnu.cmake" \
        -DCMAKE_BUILD_TYPE=Release -DJACOBID_TARGET_SYSROOT="${JACOBID_CROSS_SYSROOTS:-$root/build-cross-sysroot}/arm64-board" \
        -DGTest_DIR="$gtest_dir" -DJACOBID_BUILD_HOST_TOOLS=ON -DJACOBID_BUILD_FIRMWARE=ON -DJACOBID_BUILD_BENCHMARKS=OFF \
        -DJACOBID_BUILD_TESTS=OFF -DJACOBID_UNITY_HOST_TOOLS=ON -DJACOBID_PYTHON=OFF \
        -DJACOBID_VM_TESTS=ON -DJACOBID_VM_HOST_JACOBID="$host_jacobid" >/dev/null
      step=$(now)
      cmake --build "$b" -j "$jobs" --target jacobid-vcan-link test_hal_vcan test_hal_gpio_chardev jacobid-board jacobid-fw
      timing+=("aarch64 cross build (jacobid-board, jacobid-fw, VM test binaries): $(( $(now) - step )) s")
      exclude=()
      [ "${JACOBID_VM_LOAD:-1}" = "1" ] || exclude=(-LE load)
      # -j: the guests' clocks follow their own instructions (sleep=off), so running them side by side only
      # stretches wall time; the 60 s load test overlaps the others.
      ctest --test-dir "$b" -L vm "${exclude[@]}" -j "$jobs" --output-on-failure
      ;;
    *) echo "vm-test: unknown architecture $arch (x86_64, aarch64)" >&2; exit 2 ;;
  esac
  timing+=("$arch build + VM tests: $(( $(now) - start )) s")
done
printf 'vm-test: %s\n' "${timing[@]}"
