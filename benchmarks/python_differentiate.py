# SPDX-License-Identifier: MIT
# 1e7-sample velocity differentiation (211 taps, Ts = 1 ms) through the Python module vs the C++ call
# signal::differentiate_batch (bench_batch --compare, output preallocated). Usage, from the repository root:
#   PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_differentiate.py build/benchmarks/bench_batch
import subprocess, sys, time, json
import numpy as np
import jacobid
n, taps, ts = 10_000_000, 211, 0.001
x = np.random.default_rng(1).standard_normal(n)
x.tofile("/tmp/py2_x.bin")
times = []
for _ in range(5):
    s = time.perf_counter(); e = jacobid.differentiate(x, window=(taps - 1) * ts, ts=ts); times.append(time.perf_counter() - s)
cpp = json.loads(subprocess.run([sys.argv[1], "--compare=/tmp/py2_x.bin", f"--taps={taps}", "--out=/tmp/py2_b", "--repeat=5"], capture_output=True, text=True, check=True).stdout)
print(json.dumps({"module_median_s": float(np.median(times)), "cpp_batch_s": cpp["batch_s"], "ratio": float(np.median(times)) / cpp["batch_s"]}))
