#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""compare.py NATIVE CROSS: same names, values equal within |a-b| <= tol * max(1, |a|, |b|),
tol 1e-9 for double ("d.") and 2e-3 for float ("f.") outputs. Prints the largest deviations.
The float tolerance is that of the arithmetic, not of the platform: a 51-tap second-derivative kernel at
1 kHz has sum|w| ~ 1e5, so one float rounding of a weight or a different summation order (SSE vs NEON)
moves qdd by ~1e-4 of its O(1) value (measured: 3.6e-4 between x86-64 and aarch64)."""
import sys


def load(path):
    out = {}
    with open(path) as f:
        for line in f:
            name, value = line.split()
            out[name] = float(value)
    return out


a, b = load(sys.argv[1]), load(sys.argv[2])
if set(a) != set(b) or not a:
    sys.exit(f"golden: different outputs ({len(a)} vs {len(b)} values)")
worst = {"d": 0.0, "f": 0.0}
bad = []
for name, x in a.items():
    y = b[name]
    kind = name.split(".")[0]
    err = abs(x - y) / max(1.0, abs(x), abs(y))
    worst[kind] = max(worst[kind], err)
    if err > {"d": 1e-9, "f": 2e-3}[kind]:
        bad.append(f"{name}: {x!r} vs {y!r}")
print(f"golden: {len(a)} values; largest relative deviation double {worst['d']:.2e}, float {worst['f']:.2e}")
if bad:
    print("\n".join(bad[:20]))
    sys.exit(1)
