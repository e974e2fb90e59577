#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# The UR5-like arm of docs/identify.md, "Payload", with its 1.5 kg payload added to link 6's standard parameters
# (what `jacobid payload --export-robot` writes): centre of mass (0.03, -0.02, 0.05) m in the flange frame, central
# inertia [[4e-3, 5e-4, -3e-4], [5e-4, 6e-3, 2e-4], [-3e-4, 2e-4, 3e-3]] kg.m^2.
#   python3 scripts/payload_loaded_robot.py ROBOT.yaml OUT.yaml
# payload_standard() gives the payload's ten standard parameters (XX..M about the flange frame) to other scripts.
import re
import sys


def payload_standard():
    m, c = 1.5, [0.03, -0.02, 0.05]
    ic = [[4e-3, 5e-4, -3e-4], [5e-4, 6e-3, 2e-4], [-3e-4, 2e-4, 3e-3]]
    cc = sum(x * x for x in c)
    i = [[ic[a][b] + m * ((cc if a == b else 0) - c[a] * c[b]) for b in range(3)] for a in range(3)]
    return {"XX": i[0][0], "XY": i[0][1], "XZ": i[0][2], "YY": i[1][1], "YZ": i[1][2], "ZZ": i[2][2],
            "MX": m * c[0], "MY": m * c[1], "MZ": m * c[2], "M": m}


if __name__ == "__main__":
    text = open(sys.argv[1]).read()
    for k, v in payload_standard().items():
        text = re.sub(r"(\n  %s6: )([-0-9.e]+)" % k, lambda mo, v=v: mo.group(1) + repr(float(mo.group(2)) + v), text)
    open(sys.argv[2], "w").write(text)
