#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The Python module's cost against the C++ call it wraps (issue 19: at most 1.1x; docs/performance.md).

Times jacobid.differentiate on a record of N samples (median of R runs, kernel design included) and runs
bench_estimate, which times signal::jacobi_estimate, the function the module calls, on a record of the same
length with the same kernel options, in the same invocation, one after the other:

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/bench_python_module.py build [--samples 10000000] [--repeat 7]

Prints both medians and their ratio; exit 1 when the ratio exceeds --limit (default 1.1).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import jacobid

KERNEL = dict(window=0.21, ts=0.001, order=1)  # 211 taps: the FFT path, as for any long kernel


def python_seconds(samples: int, repeat: int) -> list:
    rng = np.random.default_rng(1)
    x = np.sin(2 * np.pi * 1e-3 * np.arange(samples)) + rng.uniform(-1e-3, 1e-3, samples)
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        estimate = jacobid.differentiate(x, **KERNEL)
        times.append(time.perf_counter() - start)
        assert estimate.values.size > 0
        del estimate  # freed before the next call, as the C++ loop's result goes out of scope each run
    return times


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", help="the build directory (holds benchmarks/bench_estimate)")
    parser.add_argument("--samples", type=int, default=10_000_000)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--limit", type=float, default=1.1)
    args = parser.parse_args()
    binary = os.path.join(args.build, "benchmarks", "bench_estimate")
    options = [f"--{k}={v}" for k, v in KERNEL.items()]
    cpp = json.loads(subprocess.run([binary, f"--samples={args.samples}", f"--repeat={args.repeat}", *options],
                                    check=True, capture_output=True, text=True).stdout)
    py = statistics.median(python_seconds(args.samples, args.repeat))
    ratio = py / cpp["median_s"]
    print(f"samples {args.samples}, kernel {KERNEL}, median of {args.repeat}: "
          f"C++ jacobi_estimate {cpp['median_s'] * 1e3:.1f} ms, jacobid.differentiate {py * 1e3:.1f} ms, ratio {ratio:.3f}")
    return 0 if ratio <= args.limit else 1


if __name__ == "__main__":
    sys.exit(main())
