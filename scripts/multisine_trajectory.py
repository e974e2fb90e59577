#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# A random multi-sine reference table for `jacobid simulate --trajectory` (validation motion for
# docs/excite.md's comparison, not a design): per joint a sum of sines at random frequencies in
# [FMIN, FMAX] Hz with random phases, under a raised-cosine envelope of RAMP s at both ends (at rest at the
# pose at the first and last row, so the table ends where it starts), scaled so that every row stays within
# the position room around the pose, the velocity and the acceleration limits (checked on the table itself).
#   multisine_trajectory.py OUT.csv --joints 6 --duration 40 --rate 1000 --pose 0,.. --room 2.4,.. \
#       --velocity-limit 3.15 --acceleration-limit 10 [--fmin 0.05 --fmax 0.8 --sines 8 --ramp 2 --seed 1]
import argparse
import numpy as np


def per_joint(text, n):
    v = [float(x) for x in text.split(",")]
    return np.array(v * n if len(v) == 1 else v)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("out")
    p.add_argument("--joints", type=int, required=True)
    p.add_argument("--duration", type=float, default=40.0)
    p.add_argument("--rate", type=float, default=1000.0)
    p.add_argument("--pose", default="0")
    p.add_argument("--room", default="2.4", help="rad: largest excursion from the pose")
    p.add_argument("--velocity-limit", default="1e9")
    p.add_argument("--acceleration-limit", default="1e9")
    p.add_argument("--fmin", type=float, default=0.05)
    p.add_argument("--fmax", type=float, default=0.8)
    p.add_argument("--sines", type=int, default=8)
    p.add_argument("--ramp", type=float, default=2.0)
    p.add_argument("--seed", type=int, default=1)
    a = p.parse_args()
    n = a.joints
    pose, room = per_joint(a.pose, n), per_joint(a.room, n)
    vmax, amax = per_joint(a.velocity_limit, n), per_joint(a.acceleration_limit, n)
    rng = np.random.default_rng(a.seed)
    t = np.arange(int(round(a.duration * a.rate)) + 1) / a.rate
    # Envelope e(t): 0 -> 1 over the ramp (raised cosine), 1 -> 0 at the end; smooth to the 2nd derivative at rest.
    def envelope(t):
        T, r = a.duration, a.ramp
        s = np.clip(np.minimum(t, T - t) / r, 0.0, 1.0)
        e = s**3 * (10 - 15 * s + 6 * s**2)                      # quintic smoothstep: e, e', e'' = 0 at s = 0
        ds = np.where((t < r) & (t > 0), 1 / r, np.where((t > T - r) & (t < T), -1 / r, 0.0))
        de = 30 * s**2 * (1 - s) ** 2 * ds
        dde = 60 * s * (1 - 3 * s + 2 * s**2) * ds**2
        return e, de, dde
    e, de, dde = envelope(t)
    q, qd, qdd = [], [], []
    for j in range(n):
        f = rng.uniform(a.fmin, a.fmax, a.sines)
        phase = rng.uniform(0, 2 * np.pi, a.sines)
        amp = rng.uniform(0.3, 1.0, a.sines) / (1 + f / a.fmin) ** 0.5
        w = 2 * np.pi * f
        s = (amp[:, None] * np.sin(w[:, None] * t + phase[:, None])).sum(0)
        ds = (amp[:, None] * w[:, None] * np.cos(w[:, None] * t + phase[:, None])).sum(0)
        dds = (-amp[:, None] * w[:, None] ** 2 * np.sin(w[:, None] * t + phase[:, None])).sum(0)
        x, dx, ddx = e * s, de * s + e * ds, dde * s + 2 * de * ds + e * dds
        scale = min(room[j] / np.abs(x).max(), vmax[j] / np.abs(dx).max(), amax[j] / np.abs(ddx).max())
        q.append(pose[j] + scale * x), qd.append(scale * dx), qdd.append(scale * ddx)
    cols = [t] + q + qd + qdd
    header = ",".join(["t"] + [f"{k}{j + 1}" for k in ("q", "qd", "qdd") for j in range(n)])
    np.savetxt(a.out, np.column_stack(cols), delimiter=",", header=header, comments="", fmt="%.12g")


if __name__ == "__main__":
    main()
