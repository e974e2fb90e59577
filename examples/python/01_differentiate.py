#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Differentiate a noisy sine with the Jacobi differentiator and compare with the exact derivative.

Run from the repository root after building the module (docs/python.md):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/01_differentiate.py
"""
import numpy as np

import jacobid

ts = 0.001  # 1 kHz
t = np.arange(20000) * ts
rng = np.random.default_rng(1)
x = np.sin(2 * np.pi * 1.5 * t) + rng.normal(0.0, 1e-4, t.size)  # a position with encoder-like noise

k = jacobid.kernel(order=1, window=0.1, ts=ts)
print(f"kernel: {k['taps']} taps, delay {k['delay_seconds'] * 1e3:.1f} ms, cutoff {k['cutoff_hz']:.1f} Hz")

velocity = jacobid.differentiate(x, order=1, window=0.1, ts=ts)
# values[i] estimates the derivative at input sample first_index + i.
at = (velocity.first_index + np.arange(velocity.values.size)) * ts
exact = 2 * np.pi * 1.5 * np.cos(2 * np.pi * 1.5 * at)
rms = np.sqrt(np.mean((velocity.values - exact) ** 2))
print(f"velocity: {velocity.values.size} samples, RMS error {rms:.2e} rad/s (amplitude {2 * np.pi * 1.5:.2f})")

baseline = jacobid.butterworth_euler(x, ts, "4:5", order=1)
at_b = (baseline.first_index + np.arange(baseline.values.size)) * ts
rms_b = np.sqrt(np.mean((baseline.values - 2 * np.pi * 1.5 * np.cos(2 * np.pi * 1.5 * at_b)) ** 2))
print(f"Butterworth 4:5 + Euler: RMS error {rms_b:.2e} rad/s")
assert rms < 0.01 * 2 * np.pi * 1.5, "the Jacobi estimate should be within 1 % of the amplitude"
