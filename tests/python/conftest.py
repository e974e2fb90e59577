# SPDX-License-Identifier: MIT
# Shared fixtures of the Python module's tests: the built jacobid command line (the reference every result
# is compared with), and the main job's simulated logs, written by that command line.
import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("JACOBID_SOURCE_DIR", Path(__file__).resolve().parents[2]))
ROBOT = SOURCE_DIR / "examples" / "robots" / "planar2r.yaml"


def pytest_sessionfinish(session, exitstatus):
    """Nothing passed and something was skipped (e.g. JACOBID_CLI unset): exit 77, which ctest's
    SKIP_RETURN_CODE (python/CMakeLists.txt) reports as skipped, not passed."""
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if exitstatus == 0 and reporter is not None and not reporter.stats.get("passed") and reporter.stats.get("skipped"):
        session.exitstatus = 77


@pytest.fixture(scope="session")
def cli():
    """Runs `jacobid ARGS`; returns (exit status, stdout, stderr)."""
    binary = os.environ.get("JACOBID_CLI")
    if not binary or not os.access(binary, os.X_OK):
        pytest.skip("JACOBID_CLI does not name the built jacobid executable (ctest sets it)")

    def run(*args):
        p = subprocess.run([binary, *map(str, args)], capture_output=True, text=True, check=False)
        return p.returncode, p.stdout, p.stderr

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    def run(*args):
        status, out, err = cli(*args)
        assert status == 0, err
        return json.loads(out)

    return run


def assert_same_json(mine, reference, rel, abs=1e-300, where="$", ignored=lambda key: False):
    """`mine` (a function's dict) against the command line's JSON `reference`: the same keys but the `ignored` ones,
    the same values, floats to `rel` relative (or `abs`)."""
    if isinstance(reference, dict):
        keys = {k for k in reference if not ignored(k)}
        assert {k for k in mine if not ignored(k)} == keys, where
        for k in keys:
            assert_same_json(mine[k], reference[k], rel, abs, f"{where}.{k}", ignored)
    elif isinstance(reference, list):
        assert len(mine) == len(reference), where
        for i, (a, b) in enumerate(zip(mine, reference)):
            assert_same_json(a, b, rel, abs, f"{where}[{i}]", ignored)
    elif isinstance(reference, float) and not isinstance(mine, bool):
        assert mine == pytest.approx(reference, rel=rel, abs=abs), where
    else:
        assert mine == reference, where


def cli_error(cli, *args):
    """The one-line message of a refused `jacobid COMMAND ...`, without its 'jacobid COMMAND: error: ' prefix."""
    status, _, err = cli(*args)
    assert status == 2, err
    line = err.strip().splitlines()[-1]
    prefix = f"jacobid {args[0]}: error: "
    assert line.startswith(prefix), line
    return line[len(prefix):]


@pytest.fixture(scope="session")
def main_job_logs(cli, tmp_path_factory):
    """The logs of examples/01_identify_planar2r.sh: identification (seed 1) and validation (seed 2) runs."""
    out = tmp_path_factory.mktemp("main_job")
    common = ["--robot", ROBOT, "--rate", "1000", "--encoder-counts", "65536", "--torque-noise", "0.05,0.01"]
    for name, extra in (("log", ["--duration", "60", "--seed", "1"]), ("validation", ["--duration", "30", "--seed", "2", "--noise-seed", "3"])):
        status, _, err = cli("simulate", *common, "--out", out / f"{name}.csv", "--truth", out / f"{name}.truth.json", *extra)
        assert status == 0, err
    return out
