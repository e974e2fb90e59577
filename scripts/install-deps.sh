#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs jacobid's build and test dependencies from Debian 12 packages (needs root or sudo).
#   scripts/install-deps.sh          everything (README command 2, scripts/run-tests.sh)
#   scripts/install-deps.sh --main   what the main job needs (README command 1, scripts/main-job.sh)
set -euo pipefail
# The main job's packages: what configuring the tree (tests included, so that both README commands share
# one build directory) and running examples/01_identify_planar2r.sh need.
packages=(
  build-essential cmake ninja-build pkg-config ccache  # ccache: scripts/ccache-env.sh
  libeigen3-dev                                   # lib/: the real-time core
  libgpiod-dev                                    # hal/: GPIO lines (libgpiod v1 C API)
  libcli11-dev libfmt-dev libyaml-cpp-dev libfast-float-dev nlohmann-json3-dev libfftw3-dev gnuplot-nox  # host-tools/
  liburdfdom-dev liborocos-kdl-dev                # host-tools/ URDF loading; tests: independent RNEA (KDL)
  libnlopt-cxx-dev                                # host-tools/: jacobid excite (SLSQP)
  libgtest-dev libgmock-dev libbenchmark-dev      # configured with the tree (tests, benchmarks)
  python3-dev python3-pybind11                    # python/: the Python module (on when these are found at the first configure)
)
# The rest, for the test command (scripts/run-tests.sh); `install-deps.sh --main` leaves them out.
if [ "${1:-}" != "--main" ]; then
  packages+=(
    clang libclang-rt-14-dev lld                  # sanitizer build and libFuzzer targets (scripts/sanitize-test.sh, fuzz/), linked by lld
    valgrind python3-scipy python3-numpy python3-can python3-pytest  # tests, references, tests/python
    python3-dask python3-distributed              # jacobid.fleet on Dask (tests/python/test_fleet.py, examples/python/03_fleet_dask.py)
  )
fi
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
