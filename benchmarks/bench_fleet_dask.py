#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""jacobid.fleet.identify on 1 and on 2 local Dask workers (issue 41: 2 workers >= 1.7x faster on 16 logs;
docs/fleet.md, "Measured").

16 simulated PUMA 560 logs (the example's: examples/python/03_fleet_dask.py, 4 robots, one with FV2 x 1.3), written
once into --logs. Two LocalClusters (1 and 2 single-threaded worker processes) stay up, so that their start is
not timed, and take turns run by run (the load of other work on the machine falls on both alike). Timed per run:

  - map + reduce: fleet.identify with the plan resolved beforehand (plan=): reading, factoring, merging, solving;
  - end to end: fleet.identify resolving the plan too (one task on one worker, which no second worker shortens).

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/bench_fleet_dask.py [--logs DIR] [--duration 60] [--repeat 3]

Prints every run with the load average, the medians and the speed-ups; exit 1 when the map + reduce speed-up is
below --limit (default 1.7). Run it on an otherwise idle machine: with 2 cores, any other work takes a worker's core.
"""
import argparse
import importlib.util
import os
import statistics
import sys
import time
from pathlib import Path

from distributed import Client, LocalCluster

import jacobid
import jacobid.fleet

SOURCE = Path(__file__).resolve().parents[1]


def example():
    """examples/python/03_fleet_dask.py as a module: its robots, drift and simulation."""
    spec = importlib.util.spec_from_file_location("fleet_example", SOURCE / "examples" / "python" / "03_fleet_dask.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def simulated_logs(folder, duration, client):
    """The 16 logs (4 robots x 4), simulated on the workers when not already in `folder`."""
    ex = example()
    ex.DURATION = duration
    folder.mkdir(parents=True, exist_ok=True)
    drifted = ex.drifted_description(folder)
    logs, runs = [], []
    for r, name in enumerate(ex.ROBOTS):
        for k in range(ex.LOGS_PER_ROBOT):
            path = folder / f"{name}-{k + 1}-{duration}s.csv"
            logs.append(str(path))
            if not path.exists():
                description = drifted if name == ex.DRIFTED else str(ex.ROBOT)
                runs.append(client.submit(ex.simulate_log, description, 1 + ex.LOGS_PER_ROBOT * r + k, str(path), pure=False))
    client.gather(runs)
    return str(ex.ROBOT), logs


def timed(function):
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--logs", type=Path, default=Path("/tmp/jacobid-fleet-bench"), help="folder of the simulated logs (kept)")
    parser.add_argument("--duration", type=int, default=60, help="s per log, at 1 kHz")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--limit", type=float, default=1.7)
    args = parser.parse_args()
    clusters = {n: LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0") for n in (1, 2)}
    clients = {n: Client(c) for n, c in clusters.items()}
    try:
        robot, logs = simulated_logs(args.logs, args.duration, clients[2])
        plan = jacobid.plan(robot, logs[0], quiet=True, threads=1)
        for client in clients.values():  # the module imported and a log read once by every worker before timing
            client.run(lambda: __import__("jacobid.fleet"))
        results = {(n, kind): [] for n in clients for kind in ("map_reduce", "end_to_end")}
        for run in range(args.repeat):
            for n, client in clients.items():
                load = os.getloadavg()[0]
                a = timed(lambda: jacobid.fleet.identify(robot, logs, client=client, plan=plan, quiet=True))
                b = timed(lambda: jacobid.fleet.identify(robot, logs, client=client, quiet=True))
                results[(n, "map_reduce")].append(a)
                results[(n, "end_to_end")].append(b)
                print(f"run {run + 1}, {n} worker{'s' if n > 1 else ''}: map + reduce {a:.2f} s, end to end {b:.2f} s "
                      f"(load average {load:.2f} before, {os.getloadavg()[0]:.2f} after)", flush=True)
        median = {key: statistics.median(v) for key, v in results.items()}
        print(f"{len(logs)} logs of {args.duration} s (PUMA 560, 1 kHz), medians of {args.repeat}:")
        for kind in ("map_reduce", "end_to_end"):
            print(f"  {kind}: 1 worker {median[(1, kind)]:.2f} s, 2 workers {median[(2, kind)]:.2f} s, "
                  f"speed-up {median[(1, kind)] / median[(2, kind)]:.2f}x")
        speedup = median[(1, "map_reduce")] / median[(2, "map_reduce")]
        return 0 if speedup >= args.limit else 1
    finally:
        for client in clients.values():
            client.close()
        for cluster in clusters.values():
            cluster.close()


if __name__ == "__main__":
    sys.exit(main())
