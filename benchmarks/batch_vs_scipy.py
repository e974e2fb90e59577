#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Batch differentiation of 1e7 samples: jacobid (direct, FFT, dispatcher) vs scipy.signal.oaconvolve.

Usage: /usr/bin/python3 benchmarks/batch_vs_scipy.py BUILD_DIR [--samples N] [--repeat R] [--taps L ...]

Writes one float64 record (deterministic: numpy default_rng(2015)) to a temporary directory, runs
BUILD_DIR/benchmarks/bench_batch --compare on it for each kernel length (the C++ side designs the velocity
kernel, kappa = mu = 6, q = 2, Ts = 1 ms, central, and writes its weights), then times
scipy.signal.oaconvolve(x, w[::-1], mode="valid") on the same record and weights in this process, checks
that both give the same result, and prints a table. Times are medians of R runs; the C++ FFT times include
planning and buffer allocation (one-shot use). Needs Debian's python3 (numpy, scipy), not a pyenv python.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy
import scipy.signal


def median_seconds(repeat, f):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return sorted(times)[len(times) // 2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build_dir", type=pathlib.Path)
    parser.add_argument("--samples", type=int, default=10_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--taps", type=int, nargs="+", default=[211, 1101])
    args = parser.parse_args()

    exe = args.build_dir / "benchmarks" / "bench_batch"
    if not exe.exists():
        sys.exit(f"{exe} not found: build the benchmarks first")

    rng = np.random.default_rng(2015)
    t = np.arange(args.samples) * 1e-3
    x = np.sin(2 * np.pi * 4 * t) + np.sin(2 * np.pi * 9 * t) + np.sin(2 * np.pi * 15 * t) + 0.2 * rng.standard_normal(args.samples)
    x = np.ascontiguousarray(x, dtype="<f8")

    rows = []
    with tempfile.TemporaryDirectory(prefix="jacobid-batch-") as tmp:
        x_path = os.path.join(tmp, "x.bin")
        x.tofile(x_path)
        for taps in args.taps:
            prefix = os.path.join(tmp, f"L{taps}")
            out = subprocess.run([str(exe), f"--compare={x_path}", f"--taps={taps}", f"--out={prefix}", f"--repeat={args.repeat}"],
                                 check=True, capture_output=True, text=True).stdout
            cpp = json.loads(out.strip().splitlines()[-1])
            w = np.fromfile(prefix + ".w.bin", dtype="<f8")
            y_cpp = np.fromfile(prefix + ".y.bin", dtype="<f8")
            y_scipy = None

            def run_scipy():
                nonlocal y_scipy
                y_scipy = scipy.signal.oaconvolve(x, w[::-1], mode="valid")

            t_scipy = median_seconds(args.repeat, run_scipy)
            scale = np.abs(w).sum() * np.abs(x).max()
            diff = np.abs(y_scipy - y_cpp).max() / scale if y_scipy.shape == y_cpp.shape else float("inf")
            rows.append((taps, t_scipy, cpp, diff))

    print(f"samples {args.samples}, median of {args.repeat} runs, scipy {scipy.__version__}, numpy {np.__version__}")
    print("FFT times include planning; 'measure' = FFTW_MEASURE plans (planning time in brackets); ratio = scipy time / jacobid time;")
    print("last columns: max |difference| / (sum|w| max|x|) of jacobid batch vs scipy and of jacobid FFT vs direct")
    header = f"{'taps':>5} {'scipy oaconv':>13} {'direct':>9} {'ratio':>6} {'fft est.':>9} {'ratio':>6} {'fft measure (plan)':>21} {'ratio':>6} {'batch':>9} {'ratio':>6} {'scipy-batch':>12} {'fft-direct':>11}"
    print(header)
    print("-" * len(header))
    for taps, t_scipy, c, diff in rows:
        print(f"{taps:5d} {t_scipy:12.3f}s {c['direct_s']:8.3f}s {t_scipy / c['direct_s']:5.1f}x {c['fft_estimate_s']:8.3f}s "
              f"{t_scipy / c['fft_estimate_s']:5.1f}x {c['fft_measure_s']:9.3f}s ({c['fft_measure_plan_s']:.3f}s) "
              f"{t_scipy / c['fft_measure_s']:5.1f}x {c['batch_s']:8.3f}s {t_scipy / c['batch_s']:5.1f}x {diff:12.1e} {c['fft_vs_direct_rel']:11.1e}")
    ok = all(d < 1e-12 for *_, d in rows)
    print("results agree (jacobid batch vs scipy) to 1e-12 of sum|w| max|x|" if ok else "RESULTS DIFFER")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
