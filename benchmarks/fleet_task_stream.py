#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""What jacobid.fleet.identify waits for after the map (docs/fleet.md, "Measured"): Dask's task stream of a run.

On the logs bench_fleet_dask.py writes (run it first), with the plan resolved beforehand, a LocalCluster of
--workers single-threaded worker processes; per run: the wall time, the factors' compute time (summed over the
workers), the time from the last factor's end to the result (the merges above the last logs and the solve), and
the transfers between workers (count and summed time). Task-stream times are wall times: other work on the
machine lengthens them.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/fleet_task_stream.py [--logs DIR] [--duration 60] [--workers 2] [--repeat 4]
"""
import argparse
import os
import statistics
import sys
import time
from pathlib import Path

from distributed import Client, get_task_stream

import jacobid
import jacobid.fleet

SOURCE = Path(__file__).resolve().parents[1]


def phases(stream, start, end):
    """(factors' compute s, s from the last factor's end to `end`, transfers, their summed s) of a task stream."""
    factor, transfers, last = 0.0, [], start
    for task in stream:
        for step in task["startstops"]:
            if step["action"] == "transfer":
                transfers.append(step["stop"] - step["start"])
            elif step["action"] == "compute" and "_factor_task" in str(task["key"]):
                factor += step["stop"] - step["start"]
                last = max(last, step["stop"])
    return factor, end - last, len(transfers), sum(transfers)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--logs", type=Path, default=Path("/tmp/jacobid-fleet-bench"), help="bench_fleet_dask.py's folder of logs")
    parser.add_argument("--duration", type=int, default=60, help="s per log, as bench_fleet_dask.py wrote them")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=4)
    args = parser.parse_args()
    logs = sorted(str(p) for p in args.logs.glob(f"robot-*-{args.duration}s.csv"))
    if len(logs) != 16:
        sys.exit(f"{args.logs}: {len(logs)} logs of {args.duration} s, expected 16 (run benchmarks/bench_fleet_dask.py first)")
    robot = str(SOURCE / "examples" / "robots" / "puma560.yaml")
    plan = jacobid.plan(robot, logs[0], quiet=True, threads=1)
    with jacobid.fleet.local_cluster(args.workers) as cluster, Client(cluster) as client:
        jacobid.fleet.identify(robot, logs, client=client, plan=plan, quiet=True)  # every worker has imported and run it once
        tails = []
        for run in range(args.repeat):
            load = os.getloadavg()[0]
            with get_task_stream(client) as stream:
                start = time.time()
                jacobid.fleet.identify(robot, logs, client=client, plan=plan, quiet=True)
                end = time.time()
            factor, tail, count, moved = phases(stream.data, start, end)
            tails.append(tail)
            print(f"run {run + 1}, {args.workers} workers: {end - start:.2f} s, factors {factor:.2f} s of compute, after the last factor "
                  f"{tail:.3f} s, {count} transfers {moved:.3f} s (load average {load:.2f} before)", flush=True)
    print(f"after the last factor: median {statistics.median(tails):.3f} s over {args.repeat} runs")


if __name__ == "__main__":
    main()
