# SPDX-License-Identifier: MIT
# Sourced by every script that configures a build (build.sh, hardening-config.sh, cross-test.sh,
# cross-gtest.sh, vm-test.sh): every compiler they run goes through ccache, so that a fresh clone (CI) with
# one file changed since the last run compiles that file only (docs/performance.md "Build time (CI)").
#  - CMake (3.17+) reads CMAKE_C_COMPILER_LAUNCHER / CMAKE_CXX_COMPILER_LAUNCHER from the environment when
#    it configures a build directory for the first time: native, sanitizer, cross, board and Cortex-M
#    builds, the cross-built GoogleTest and the install/consume test all get it without a flag each.
#    A build directory configured before keeps what its CMakeCache.txt says (delete it to change).
#  - The cache lives outside the clone, so a fresh clone (CI) finds the previous run's objects:
#    JACOBID_CCACHE_DIR, else CCACHE_DIR, else /var/cache/jacobid-ccache, else (not writable, e.g. no
#    root) ~/.cache/jacobid-ccache. JACOBID_CCACHE=0 turns it off; without ccache installed, nothing changes.
if [ "${JACOBID_CCACHE:-1}" != "0" ] && command -v ccache >/dev/null 2>&1; then
  CCACHE_DIR="${JACOBID_CCACHE_DIR:-${CCACHE_DIR:-/var/cache/jacobid-ccache}}"
  if ! mkdir -p "$CCACHE_DIR" 2>/dev/null || [ ! -w "$CCACHE_DIR" ]; then
    CCACHE_DIR="${XDG_CACHE_HOME:-$HOME/.cache}/jacobid-ccache"
    mkdir -p "$CCACHE_DIR"
  fi
  # All the builds of a test run share the cache: 8 GB unless CCACHE_MAXSIZE says otherwise (ccache's default is 5 GB).
  export CCACHE_DIR CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-8G}"
  # Another clone (another path: CI's checkout, a worktree) hits the same objects: paths below the clone's
  # root are hashed relative to the build directory, and the build directory's own path is not hashed
  # (the sanitizer build's -gline-tables-only would add it; its debug info then names the first clone).
  CCACHE_BASEDIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  export CCACHE_BASEDIR CCACHE_NOHASHDIR=1
  export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache
fi
