#!/usr/bin/env bash
# The tests that need a kernel with CAN or a GPIO chip (ctest labels vcan, vm, gpio; docs/targets.md):
#  1. this machine's build (build-vm): vcan.host runs the SocketCAN tests directly if vcan interfaces can
#     be made here (else skipped), vm.x86_64.hal-vcan runs them in qemu-system-x86_64 with Debian's kernel,
#     and, with JACOBID_VM_CHAIN=1, vm.x86_64.chain: the full chain sim-can -> vcan0 -> jacobid-fw -> UDP ->
#     record -> identify there (build-vm's own jacobid + jacobid-fw, without -march=native: qemu's TCG has no
#     AVX-512). Not in the default run: its outcome depends on emulated timing (docs/targets.md).
#  2. the aarch64 cross build (build-cross-aarch64, made by scripts/cross-test.sh if missing):
#     vm.aarch64.hal-vcan and vm.aarch64.hal-gpio (PL061 GPIO) in qemu-system-aarch64 -M virt.
# Usage: scripts/vm-test.sh [x86_64|aarch64]...   (default: both; JACOBID_VM_ARCHES likewise)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
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
          -DJACOBID_BUILD_BENCHMARKS=OFF -DJACOBID_BUILD_FIRMWARE=ON -DJACOBID_VM_TESTS=ON -DJACOBID_MARCH= >/dev/null
        cmake --build "$b" -j "$jobs" --target jacobid-vcan-link test_hal_vcan jacobid jacobid-fw
        ctest --test-dir "$b" -L 'vcan|chain' --output-on-failure
      else
        cmake -S "$root" -B "$b" -G Ninja -DCMAKE_BUILD_TYPE=Release -DJACOBID_BUILD_HOST_TOOLS=OFF \
          -DJACOBID_BUILD_BENCHMARKS=OFF -DJACOBID_BUILD_FIRMWARE=OFF -DJACOBID_VM_TESTS=ON >/dev/null
        cmake --build "$b" -j "$jobs" --target jacobid-vcan-link test_hal_vcan
        ctest --test-dir "$b" -L vcan -LE chain --output-on-failure
      fi
      ;;
    aarch64)
      b="$root/build-cross-aarch64"
      bash "$root/scripts/cross-test.sh" --build-only aarch64
      ctest --test-dir "$b" -L vm --output-on-failure
      ;;
    *) echo "vm-test: unknown architecture $arch (x86_64, aarch64)" >&2; exit 2 ;;
  esac
  timing+=("$arch build + VM tests: $(( $(now) - start )) s")
done
printf 'vm-test: %s\n' "${timing[@]}"
