#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""jacobid.fleet.identify on 1 and on 2 local Dask workers (issue 41: 2 workers >= 1.7x faster on 16 logs;
docs/fleet.md, "Measured").

16 simulated PUMA 560 logs (the example's: examples/python/03_fleet_dask.py, 4 robots, one with FV2 x 1.3), written
once into --logs. A LocalCluster of 1 and one of 2 single-threaded worker processes take turns run by run (the load
of other work on the machine falls on both alike); each is started before its run, its workers import the module
and identify once untimed (a new worker's first logs are slower, which would favour 2 workers), and it is closed
after it, so that neither its start nor the other cluster's idle processes (their monitors and profilers take
~0.05 of a core, which the 2-worker run, needing both cores, would lose) are in the figures.
The clusters are jacobid.fleet.local_cluster's (its worker settings); --dask-defaults makes them with Dask's
defaults instead, the comparison of docs/fleet.md. --keep-clusters keeps both up all along instead (the setting of the earlier figures in docs/fleet.md). Timed per run:

  - map + reduce: fleet.identify with the plan resolved beforehand (plan=): reading, factoring, merging, solving;
  - end to end: fleet.identify resolving the plan too (one task on one worker, which no second worker shortens).

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/bench_fleet_dask.py [--logs DIR] [--duration 60] [--repeat 5]

Prints every run with the load average and the CPU seconds of the driver and its Dask processes (the scheduler and
nannies in the driver, the workers), the medians and the speed-ups; exit 1 when the map + reduce speed-up is below
--limit (default 1.7). Run it on an otherwise idle machine: with 2 cores, any other work takes a worker's core.
"""
import argparse
import contextlib
import importlib.util
import os
import statistics
import sys
import time
from pathlib import Path

import psutil

from distributed import Client

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


def cpu_seconds():
    """CPU seconds (user + system) of this process and every process it started (the Dask workers)."""
    total = 0.0
    me = psutil.Process()
    for p in [me, *me.children(recursive=True)]:
        with contextlib.suppress(psutil.Error):
            t = p.cpu_times()
            total += t.user + t.system
    return total


def timed(function):
    """(wall seconds, CPU seconds of the driver and its Dask processes) of function()."""
    cpu, start = cpu_seconds(), time.perf_counter()
    function()
    return time.perf_counter() - start, cpu_seconds() - cpu


@contextlib.contextmanager
def local_client(workers, dask_defaults=False):
    import distributed

    make = (lambda n: distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0")) \
        if dask_defaults else jacobid.fleet.local_cluster
    with make(workers) as cluster, Client(cluster) as client:
        client.run(lambda: __import__("jacobid.fleet"))  # the module imported by every worker before timing
        yield client


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--logs", type=Path, default=Path("/tmp/jacobid-fleet-bench"), help="folder of the simulated logs (kept)")
    parser.add_argument("--duration", type=int, default=60, help="s per log, at 1 kHz")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--limit", type=float, default=1.7)
    parser.add_argument("--dask-defaults", action="store_true",
                        help="clusters with Dask's default worker settings instead of jacobid.fleet.worker_settings()")
    parser.add_argument("--keep-clusters", action="store_true", help="both clusters up all along (the earlier setting)")
    args = parser.parse_args()
    with contextlib.ExitStack() as kept:
        kept_clients = {n: kept.enter_context(local_client(n, args.dask_defaults)) for n in (1, 2)} if args.keep_clusters else {}
        with contextlib.nullcontext(kept_clients[2]) if kept_clients else local_client(2, args.dask_defaults) as client:
            robot, logs = simulated_logs(args.logs, args.duration, client)
        plan = jacobid.plan(robot, logs[0], quiet=True, threads=1)
        results = {(n, kind): [] for n in (1, 2) for kind in ("map_reduce", "end_to_end")}
        for run in range(args.repeat):
            for n in (1, 2):
                with contextlib.nullcontext(kept_clients[n]) if kept_clients else local_client(n, args.dask_defaults) as client:
                    if not kept_clients:  # an untimed run first: a new worker's first logs are slower (a cold process)
                        jacobid.fleet.identify(robot, logs, client=client, plan=plan, quiet=True)
                    load = os.getloadavg()[0]
                    a = timed(lambda: jacobid.fleet.identify(robot, logs, client=client, plan=plan, quiet=True))
                    b = timed(lambda: jacobid.fleet.identify(robot, logs, client=client, quiet=True))
                results[(n, "map_reduce")].append(a[0])
                results[(n, "end_to_end")].append(b[0])
                print(f"run {run + 1}, {n} worker{'s' if n > 1 else ''}: map + reduce {a[0]:.2f} s ({a[1]:.2f} s of CPU), "
                      f"end to end {b[0]:.2f} s ({b[1]:.2f} s of CPU) (load average {load:.2f} before, {os.getloadavg()[0]:.2f} after)", flush=True)
    median = {key: statistics.median(v) for key, v in results.items()}
    print(f"{len(logs)} logs of {args.duration} s (PUMA 560, 1 kHz), medians of {args.repeat}:")
    for kind in ("map_reduce", "end_to_end"):
        print(f"  {kind}: 1 worker {median[(1, kind)]:.2f} s, 2 workers {median[(2, kind)]:.2f} s, "
              f"speed-up {median[(1, kind)] / median[(2, kind)]:.2f}x")
    speedup = median[(1, "map_reduce")] / median[(2, "map_reduce")]
    return 0 if speedup >= args.limit else 1


if __name__ == "__main__":
    sys.exit(main())
