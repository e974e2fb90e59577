#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs jacobid's build and test dependencies from Debian 12 packages (needs root or sudo).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config ccache  # ccache: scripts/ccache-env.sh
  libeigen3-dev                                   # lib/: the real-time core
  libgpiod-dev                                    # hal/: GPIO lines (libgpiod v1 C API)
  libcli11-dev libfmt-dev libyaml-cpp-dev libfast-float-dev nlohmann-json3-dev libfftw3-dev gnuplot-nox  # host-tools/
  liburdfdom-dev liborocos-kdl-dev                # host-tools/ URDF loading; tests: independent RNEA (KDL)
  clang libclang-rt-14-dev                        # sanitizer build and libFuzzer targets (scripts/sanitize-test.sh, fuzz/)
  libnlopt-cxx-dev                                # host-tools/: jacobid excite (SLSQP)
  libgtest-dev libgmock-dev libbenchmark-dev valgrind python3-scipy python3-numpy python3-can  # tests, benchmarks, references
  python3-dev python3-pybind11 python3-pytest    # python/: the Python module and its tests (tests/python)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
