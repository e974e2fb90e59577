#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A fleet on Dask: 16 simulated PUMA 560 logs of 4 robots, one of which has 30 % more viscous friction on joint 2,
identified on a LocalCluster of 2 worker processes (docs/fleet.md).

Checks that the pooled identification equals `jacobid identify --in ...` of the same 16 logs (the parameter values
to 1e-10, every other number to 1e-9), and that the drifted robot and joint are named and no other robot is.

Run from the repository root after building the module and the command line (docs/python.md):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/03_fleet_dask.py
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from distributed import Client

import jacobid
import jacobid.fleet

ROBOT = Path("examples/robots/puma560.yaml").resolve()
CLI = os.environ.get("JACOBID_CLI", "build/host-tools/jacobid")
ROBOTS = ["robot-A", "robot-B", "robot-C", "robot-D"]
DRIFTED = "robot-C"  # its joint 2 (shoulder) has FV2 x 1.3
LOGS_PER_ROBOT = 4
DURATION = 20  # s at 1 kHz
TORQUE_NOISE = (0.5, 0.5, 0.3, 0.05, 0.05, 0.05)  # N.m, as docs/performance.md's PUMA runs


def drifted_description(folder):
    """puma560.yaml with the shoulder's viscous friction FV2 30 % higher (what the drifted robot is simulated with)."""
    text = ROBOT.read_text()
    old = "  FV2: 9.496868642\n"
    assert old in text, "examples/robots/puma560.yaml changed: FV2 not found"
    path = Path(folder) / "puma560_fv2_drift.yaml"
    path.write_text(text.replace(old, f"  FV2: {9.496868642 * 1.3!r}\n"))
    return str(path)


def simulate_log(description, seed, path):
    """One simulated log written as CSV (a Dask task: the 16 simulations run on the workers too)."""
    robot = jacobid.load_robot(description)
    run = jacobid.simulate(robot, duration=DURATION, seed=seed, noise_seed=seed + 100, torque_noise=TORQUE_NOISE)
    header = ",".join(["t", *robot.position_columns, *robot.torque_columns])
    np.savetxt(path, np.column_stack([run["t"], run["q"], run["tau"]]), delimiter=",", header=header, comments="", fmt="%.17g")
    return path


def largest_difference(mine, reference, where="$"):
    """The largest relative difference of two identify dicts (every key but timings), and where it is."""
    if isinstance(reference, dict):
        keys = {k for k in reference if "seconds" not in k}
        assert {k for k in mine if "seconds" not in k} == keys, where
        return max((largest_difference(mine[k], reference[k], f"{where}.{k}") for k in keys), default=(0.0, where))
    if isinstance(reference, list):
        assert len(mine) == len(reference), where
        return max((largest_difference(a, b, f"{where}[{i}]") for i, (a, b) in enumerate(zip(mine, reference))), default=(0.0, where))
    if isinstance(reference, float) and not isinstance(mine, bool):
        return (abs(mine - reference) / max(abs(reference), 1e-300), where)
    assert mine == reference, (where, mine, reference)
    return (0.0, where)


def main():
    with tempfile.TemporaryDirectory() as folder, \
            jacobid.fleet.local_cluster(2) as cluster, Client(cluster) as client:
        drifted = drifted_description(folder)
        logs, by_robot, runs = [], {}, []
        for r, name in enumerate(ROBOTS):
            for k in range(LOGS_PER_ROBOT):
                path = str(Path(folder) / f"{name}-{k + 1}.csv")
                logs.append(path)
                by_robot[path] = name
                runs.append(client.submit(simulate_log, drifted if name == DRIFTED else str(ROBOT), 1 + LOGS_PER_ROBOT * r + k, path))
        client.gather(runs)
        print(f"simulated {len(logs)} logs of {len(ROBOTS)} robots ({DURATION} s each) on {len(client.scheduler_info()['workers'])} workers")

        out = jacobid.fleet.identify(str(ROBOT), logs, client=client, by_robot=by_robot, quiet=True)
        kib = np.mean(list(out["factor_bytes"].values())) / 1024
        print(f"pooled: {len(out['pooled']['logs'])} logs, {out['pooled']['equations']} equations; {kib:.0f} KiB per factor; failed: {out['failed']}")

        args = [CLI, "identify", "--quiet", "--robot", str(ROBOT), "--format", "json"]
        for log in logs:
            args += ["--in", log]
        reference = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
        values = max(abs(out["pooled"]["parameters"][n]["value"] / reference["parameters"][n]["value"] - 1) for n in reference["parameter_order"])
        difference, where = largest_difference(out["pooled"], reference)
        print(f"pooled vs `jacobid identify --in ...` of the same logs: parameter values to {values:.1e} (relative), "
              f"every number of the JSON to {difference:.1e} ({where})")
        # The values to 1e-10; the std and the residual statistics, whose HAC terms cancel about 4 digits, to 1e-9
        # (jacobid.identify of the same logs in this process already differs from the command line by up to 3e-10
        # there: docs/fleet.md, "Measured").
        assert values <= 1e-10 and difference <= 1e-9, (values, difference, where)

        for name in ROBOTS:
            drift = out["robots"][name]["drifted"]
            line = ", ".join(f"{d['parameter']} (joint {d['joint']}) {100 * d['relative']:+.1f} %, z = {d['z']:+.1f}" for d in drift)
            print(f"{name}: {line or 'no parameter beyond |z| > 5 from the other robots'}")
        named = out["robots"][DRIFTED]["drifted"]
        assert named and named[0]["parameter"] == "FV2" and named[0]["joint"] == "shoulder", named
        assert all(not out["robots"][name]["drifted"] for name in ROBOTS if name != DRIFTED), {n: out["robots"][n]["drifted"] for n in ROBOTS}
        print(f"drifted: {DRIFTED}, joint shoulder (FV2); the other robots within the fleet's spread")


if __name__ == "__main__":
    sys.exit(main())
