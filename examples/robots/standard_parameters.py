#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Standard parameters (Khalil's XXj ... Mj about the link frame origin) from mass, centre of mass and
central inertia, as used to write the `parameters:` blocks of puma560.yaml and ur5_like.yaml.

    XX = Ixx + m (cy^2 + cz^2)   XY = Ixy - m cx cy   XZ = Ixz - m cx cz
    YY = Iyy + m (cx^2 + cz^2)   YZ = Iyz - m cy cz   ZZ = Izz + m (cx^2 + cy^2)
    MX, MY, MZ = m c

Run: /usr/bin/python3 examples/robots/standard_parameters.py puma560|ur5_like
"""
import math
import sys


def standard(j, m, c, inertia):
    ixx, iyy, izz, ixy, iyz, ixz = inertia
    cx, cy, cz = c
    values = {
        "XX": ixx + m * (cy * cy + cz * cz), "XY": ixy - m * cx * cy, "XZ": ixz - m * cx * cz,
        "YY": iyy + m * (cx * cx + cz * cz), "YZ": iyz - m * cy * cz, "ZZ": izz + m * (cx * cx + cy * cy),
        "MX": m * cx, "MY": m * cy, "MZ": m * cz, "M": m,
    }
    return {f"{k}{j}": v for k, v in values.items()}


def puma560():
    # Corke, Robotics Toolbox, mdl_puma560akb (Armstrong, Khatib, Burdick 1986), link frames = MDH frames.
    m = [0, 17.4, 4.8, 0.82, 0.34, 0.09]
    c = [[0, 0, 0], [0.068, 0.006, -0.016], [0, -0.070, 0.014], [0, 0, -0.019], [0, 0, 0], [0, 0, 0.032]]
    inertia = [[0, 0, 0.35, 0, 0, 0], [.13, .524, .539, 0, 0, 0], [.066, .0125, .066, 0, 0, 0],
               [1.8e-3, 1.8e-3, 1.3e-3, 0, 0, 0], [.3e-3, .3e-3, .4e-3, 0, 0, 0], [.15e-3, .15e-3, .04e-3, 0, 0, 0]]
    jm = [291e-6, 409e-6, 299e-6, 35e-6, 35e-6, 35e-6]
    gear = [-62.6111, 107.815, -53.7063, 76.0364, 71.923, 76.686]
    # Motor friction from Corke's mdl_puma560 (Corke & Armstrong-Helouvry 1994), AKB gives none.
    b = [1.48e-3, .817e-3, 1.38e-3, 71.2e-6, 82.6e-6, 36.7e-6]
    tc = [.395, .126, .132, 11.2e-3, 9.26e-3, 3.96e-3]
    out = {}
    for j in range(6):
        out.update(standard(j + 1, m[j], c[j], inertia[j]))
        out[f"IA{j + 1}"] = jm[j] * gear[j] ** 2
        out[f"FV{j + 1}"] = b[j] * gear[j] ** 2
        out[f"FC{j + 1}"] = tc[j] * abs(gear[j])
    return out


def rot_x(alpha, v):
    ca, sa = math.cos(alpha), math.sin(alpha)
    return [v[0], ca * v[1] - sa * v[2], sa * v[1] + ca * v[2]]


def ur5_like():
    # UR5 standard DH (Universal Robots, "DH parameters for calculations of kinematics and dynamics"):
    # a = [0, -0.425, -0.39225, 0, 0, 0], d = [0.089159, 0, 0, 0.10915, 0.09465, 0.0823],
    # alpha = [pi/2, 0, 0, pi/2, -pi/2, 0]; masses and centres of mass from the same page (in the standard
    # DH link frames). The MDH frame j sits on joint axis j: c_mdh = Trans(x, a_j) Rot(x, alpha_j) c_dh.
    a = [0, -0.425, -0.39225, 0, 0, 0]
    alpha = [math.pi / 2, 0, 0, math.pi / 2, -math.pi / 2, 0]
    m = [3.7, 8.393, 2.275, 1.219, 1.219, 0.1879]
    c_dh = [[0, -0.02561, 0.00193], [0.2125, 0, 0.11336], [0.15, 0, 0.0265], [0, -0.0018, 0.01634],
            [0, 0.0018, 0.01634], [0, 0, -0.001159]]
    # Central inertias: NOT published by UR; solid cylinders (radius 0.06/0.06/0.05/0.045/0.045/0.04 m) along
    # each link, the "UR5-like" part of this model. Axes in the MDH frame: links 2, 3 along x, others along z.
    lengths = [0.15, 0.425, 0.39225, 0.12, 0.12, 0.05]
    radii = [0.06, 0.06, 0.05, 0.045, 0.045, 0.04]
    out = {}
    for j in range(6):
        c = rot_x(alpha[j], c_dh[j])
        c = [c[0] + a[j], c[1], c[2]]
        r, h, mass = radii[j], lengths[j], m[j]
        axial, transverse = mass * r * r / 2, mass * (3 * r * r + h * h) / 12
        inertia = [axial, transverse, transverse, 0, 0, 0] if j in (1, 2) else [transverse, transverse, axial, 0, 0, 0]
        out.update(standard(j + 1, mass, c, inertia))
    return out


if __name__ == "__main__":
    table = {"puma560": puma560, "ur5_like": ur5_like}[sys.argv[1]]()
    print("parameters:")
    for name, value in table.items():
        print(f"  {name}: {value:.10g}")
