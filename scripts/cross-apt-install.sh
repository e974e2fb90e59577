#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the given Debian packages that are not installed yet (root or sudo); used by cross-deps.sh and
# vm-deps.sh. Prints what it installs.
set -euo pipefail
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -gt 0 ] || exit 0
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "apt: installing ${missing[*]}"
$sudo apt-get update -qq || true   # a third-party source that cannot be reached only warns
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
