#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs README.md's quick start block exactly as written from the repository root, with two substitutions
# only: the jacobid binary of this build (the README says build/host-tools/jacobid) and a scratch output
# folder instead of out/quick. Fails when a command of the README fails, so the README cannot rot.
#   readme_quick_start.sh SOURCE_DIR JACOBID_EXECUTABLE
set -euo pipefail
source_dir=$1
jacobid=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
block=$(awk '/^J=build\/host-tools\/jacobid; R=/{on=1} on&&/^```/{exit} on{print}' "$source_dir/README.md")
[ -n "$block" ] || { echo "readme_quick_start: no quick start block (a line starting 'J=build/host-tools/jacobid; R=') in README.md" >&2; exit 1; }
block=${block/J=build\/host-tools\/jacobid/J=$jacobid}
block=${block/O=out\/quick/O=$scratch}
cd "$source_dir"
bash -euo pipefail -c "$block" > "$scratch.log" 2>&1 || { cat "$scratch.log" >&2; rm -f "$scratch.log"; exit 1; }
rm -f "$scratch.log"
for f in identification.json report/report.md diagnosis bode.png derivatives.csv baseline.csv puma.csv; do
  [ -e "$scratch/$f" ] || { echo "readme_quick_start: the quick start did not produce $f" >&2; exit 1; }
done
echo "readme_quick_start: every command of README's quick start ran"
