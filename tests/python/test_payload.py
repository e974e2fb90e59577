# SPDX-License-Identifier: MIT
# jacobid.payload against the jacobid command line (issue 39): the simulated UR5-like arm with a 1.5 kg payload
# on link 6, the same numbers as `jacobid payload --json` and the command line's messages for bad input.
import re

import pytest

import jacobid
from conftest import SOURCE_DIR, assert_same_json, cli_error

UR5 = SOURCE_DIR / "examples" / "robots" / "ur5_like.yaml"


def loaded_description(path):
    """ur5_like.yaml with a 1.5 kg point mass at (0.03, -0.02, 0.05) m added to link 6 (parallel axes)."""
    m, c = 1.5, (0.03, -0.02, 0.05)
    cc = sum(x * x for x in c)
    add = {"XX6": m * (cc - c[0] ** 2), "XY6": -m * c[0] * c[1], "XZ6": -m * c[0] * c[2], "YY6": m * (cc - c[1] ** 2),
           "YZ6": -m * c[1] * c[2], "ZZ6": m * (cc - c[2] ** 2), "MX6": m * c[0], "MY6": m * c[1], "MZ6": m * c[2], "M6": m}
    text = UR5.read_text()
    for k, v in add.items():
        text = re.sub(r"(\n  %s: )([-0-9.e]+)" % k, lambda mo: mo.group(1) + repr(float(mo.group(2)) + v), text)
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def runs(cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("payload")
    common = ("simulate", "--quiet", "--duration", "10", "--seed", "3", "--torque-noise", "0.3")
    assert cli(*common, "--noise-seed", "4", "--robot", UR5, "-o", out / "unloaded.csv")[0] == 0
    assert cli(*common, "--noise-seed", "5", "--robot", loaded_description(out / "loaded.yaml"), "-o", out / "loaded.csv")[0] == 0
    assert cli("identify", "--quiet", "--robot", UR5, "--in", out / "unloaded.csv", "--format", "json", "-o", out / "arm.json")[0] == 0
    return out


def assert_same(mine, reference):
    """Equal, numbers to 1e-9 relative: the module's library is compiled position independent, the command
    line's is not, and the last bits differ through the solves (sensitivities of rank-near columns amplify them)."""
    assert_same_json(mine, reference, rel=1e-9, abs=1e-15, where="payload")


def test_payload_is_the_cli_payload(cli_json, runs):
    reference = cli_json("payload", "--quiet", "--json", "--robot", UR5, "--arm", runs / "arm.json", "--in", runs / "loaded.csv",
                         "--unloaded", runs / "unloaded.csv", "--gain-std", "0.01,0.01,0.01,0.01,0.01,0.01")
    mine = jacobid.payload(UR5, runs / "arm.json", runs / "loaded.csv", unloaded=runs / "unloaded.csv", gain_std=(0.01,) * 6)
    assert_same(mine, reference)
    assert mine["payload"]["mass"]["value"] == pytest.approx(1.5, rel=0.01)


def test_payload_errors_carry_the_cli_messages(cli, runs):
    with pytest.raises(jacobid.InputError) as e:
        jacobid.payload(UR5, runs / "arm.json", runs / "loaded.csv", frame="tool0")
    assert str(e.value) == cli_error(cli, "payload", "--robot", UR5, "--arm", runs / "arm.json", "--in", runs / "loaded.csv", "--frame", "tool0")
    with pytest.raises(jacobid.InputError, match="mas: unknown keyword of payload \\(did you mean mass\\?\\)"):
        jacobid.payload(UR5, runs / "arm.json", runs / "loaded.csv", mas=2)
