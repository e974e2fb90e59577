#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Target packages without multiarch: downloads Debian packages of another architecture with apt-get
# download (its own package lists, the machine's apt sources, the machine's dpkg left alone) and unpacks
# them with dpkg -x.
#   scripts/cross-sysroot.sh DEBARCH DEST PACKAGE...     e.g. arm64 build-cross-sysroot/arm64 libgpiod-dev
#   scripts/cross-sysroot.sh --debs-only DEBARCH PACKAGE...   downloads only; prints the .deb paths
# A PACKAGE may be "kernel": the package linux-image-<arch> currently depends on (Debian's stock kernel).
# Progress goes to stderr; exits non-zero if a package cannot be found or downloaded.
set -euo pipefail
debs_only=""
if [ "${1:-}" = --debs-only ]; then debs_only=1; shift; set -- "$1" "" "${@:2}"; fi
[ $# -ge 3 ] || { echo "usage: $0 [--debs-only] DEBARCH DEST PACKAGE..." >&2; exit 2; }
arch="$1"; dest="$2"; shift 2
root="$(cd "$(dirname "$0")/.." && pwd)"
state="${JACOBID_APT_STATE_DIR:-$root/build-cross-sysroot/apt}/$arch"
mkdir -p "$state/lists/partial" "$state/cache/archives/partial" "$state/debs"
[ -n "$debs_only" ] || mkdir -p "$dest"
apt_opts=(-o "APT::Architecture=$arch" -o "APT::Architectures=$arch" -o "Dir::State::Lists=$state/lists"
          -o "Dir::Cache=$state/cache" -o "Dir::State::status=$state/status" -o "Debug::NoLocking=1" -o "APT::Sandbox::User=root")
touch "$state/status"
# Lists for this architecture (a few seconds). Unreachable third-party sources only warn.
if [ ! -e "$state/lists/.complete" ] || [ -n "${JACOBID_APT_REFRESH:-}" ]; then
  apt-get "${apt_opts[@]}" -qq update 2>&1 | grep -v "^W:" >&2 || true
  touch "$state/lists/.complete"
fi
pkgs=()
for p in "$@"; do
  if [ "$p" = kernel ]; then
    meta="linux-image-$arch"
    p="$(apt-cache "${apt_opts[@]}" depends "$meta" 2>/dev/null | sed -n 's/^ *Depends: \(linux-image-[0-9][^ ]*\)$/\1/p' | head -1)"
    [ -n "$p" ] || { echo "cross-sysroot: cannot resolve the kernel package of $meta for $arch" >&2; exit 1; }
  fi
  pkgs+=("$p")
done
( cd "$state/debs" && apt-get "${apt_opts[@]}" -qq download "${pkgs[@]}" >&2 )
for p in "${pkgs[@]}"; do
  deb="$(ls -t "$state/debs/${p}_"*"_$arch.deb" "$state/debs/${p}_"*"_all.deb" 2>/dev/null | head -1 || true)"
  [ -n "$deb" ] || { echo "cross-sysroot: $p was not downloaded" >&2; exit 1; }
  if [ -n "$debs_only" ]; then
    echo "$deb"
  else
    dpkg -x "$deb" "$dest"
    echo "cross-sysroot: $arch $(basename "$deb") -> $dest" >&2
  fi
done
