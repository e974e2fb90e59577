#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Simulate the paper's planar 2R robot, identify it from the numpy arrays, compare with the truth.

Run from the repository root after building the module (docs/python.md):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/02_identify.py
"""
import jacobid

robot = jacobid.load_robot("examples/robots/planar2r.yaml")
# The main job's settings (examples/01_identify_planar2r.sh), as keyword arguments of simulate's options.
run = jacobid.simulate(robot, duration=60, rate=1000, encoder_counts=65536, torque_noise=(0.05, 0.01), seed=1)
print(f"simulated {run['samples']} samples of {robot.joint_names}")

fit = jacobid.identify(robot, (run["t"], run["q"], run["tau"]), truth=run, quiet=True)
print(f"{'parameter':<10} {'identified':>12} {'std':>10} {'truth':>10}")
for name in fit["parameter_order"]:
    p = fit["parameters"][name]
    std = "" if p["std"] is None else f"{p['std']:.4f}"
    print(f"{name:<10} {p['value']:>12.4f} {std:>10} {p['truth']:>10.4f}")
    if p["std"] is not None:
        assert abs(p["value"] - p["truth"]) < 5 * p["std"] + 1e-3 * abs(p["truth"]), name
