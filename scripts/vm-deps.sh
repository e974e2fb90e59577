#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What the VM tests need (docs/targets.md), from Debian 12 packages only:
#  - qemu-system-x86 / qemu-system-arm (has qemu-system-aarch64), run without KVM (-accel tcg);
#  - per VM architecture, in ${JACOBID_VM_ASSETS:-build-vm/assets}/<arch>: Debian's stock kernel
#    (linux-image-<ver>-amd64 / -arm64: vmlinuz and the CAN modules only) and a static
#    busybox (busybox-static), downloaded with scripts/cross-sysroot.sh --debs-only (no multiarch, no
#    dpkg change). Architectures: JACOBID_VM_ARCHES (default "x86_64 aarch64").
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
assets="${JACOBID_VM_ASSETS:-$root/build-vm/assets}"
arches=(${JACOBID_VM_ARCHES:-x86_64 aarch64})
packages=(busybox-static python3 g++ cmake ninja-build pkg-config libeigen3-dev libgpiod-dev libgtest-dev)
for arch in "${arches[@]}"; do
  case "$arch" in
    x86_64) packages+=(qemu-system-x86) ;;
    aarch64) packages+=(qemu-system-arm) ;;
    *) echo "vm-deps: unknown VM architecture $arch (x86_64, aarch64)" >&2; exit 2 ;;
  esac
done
bash "$root/scripts/cross-apt-install.sh" "${packages[@]}"
for arch in "${arches[@]}"; do
  dir="$assets/$arch"
  [ -e "$dir/.complete" ] && continue
  case "$arch" in x86_64) debarch=amd64 ;; aarch64) debarch=arm64 ;; esac
  rm -rf "$dir" && mkdir -p "$dir/extract"
  start=$(date +%s)
  mapfile -t debs < <(bash "$root/scripts/cross-sysroot.sh" --debs-only "$debarch" kernel busybox-static)
  [ ${#debs[@]} -eq 2 ] || { echo "vm-deps: downloads failed for $arch" >&2; exit 1; }
  # The kernel image and the CAN modules (net/can, drivers/net/can) only. modules.dep is made by depmod
  # at install time, so it is not in the package: the VM harness reads each module's depends= instead.
  dpkg-deb --fsys-tarfile "${debs[0]}" | tar -x -C "$dir/extract" --wildcards \
    '*/boot/vmlinuz-*' '*/modules/*/kernel/net/can/*' '*/modules/*/kernel/drivers/net/can/*'
  dpkg-deb --fsys-tarfile "${debs[1]}" | tar -x -C "$dir/extract" --wildcards '*/bin/busybox'
  mv "$(find "$dir/extract" -path '*/boot/vmlinuz-*' | head -1)" "$dir/vmlinuz"
  mv "$(find "$dir/extract" -path '*/bin/busybox' | head -1)" "$dir/busybox"
  mv "$(dirname "$(find "$dir/extract" -type d -path '*/modules/*/kernel' | head -1)")" "$dir/modules"
  rm -rf "$dir/extract"
  echo "$(basename "${debs[0]}")" > "$dir/kernel-package"
  touch "$dir/.complete"
  echo "vm-deps: $arch: $(cat "$dir/kernel-package"), $(find "$dir/modules" -name '*.ko*' | wc -l) CAN modules, busybox ($(( $(date +%s) - start )) s)"
done
