# SPDX-License-Identifier: MIT
# jacobid.identify() runs the command line's identify job (host-tools/src/job/identify_job.hpp), so every
# feature of `jacobid identify` is a keyword: several logs, --on-gap split, --period, --physical, --essential.
# Each is checked against the command line itself on logs it simulated, to 1e-12 over the whole JSON.
import math

import numpy as np
import pytest

import jacobid
from conftest import ROBOT, SOURCE_DIR, assert_same_json

RTOL = 1e-12
MDH_ROBOT = SOURCE_DIR / "examples" / "robots" / "planar2r_mdh.yaml"


def assert_same_cli_json(mine, reference):
    """Every key and value of the command line's JSON, floats to 1e-12 (timings left out)."""
    assert_same_json(mine, reference, rel=RTOL, ignored=lambda key: key.endswith("seconds"))


def simulate(cli, robot, out, *extra):
    status, _, err = cli("simulate", "--quiet", "--robot", robot, "--out", out, "--encoder-counts", "65536",
                         "--torque-noise", "0.05,0.01", *extra)
    assert status == 0, err
    return out


def test_several_logs_are_the_cli_in_a_in_b(cli_json, main_job_logs):
    logs = [main_job_logs / "log.csv", main_job_logs / "validation.csv"]
    reference = cli_json("identify", "--robot", ROBOT, "--in", logs[0], "--in", logs[1], "--essential", "--format", "json", "--quiet")
    mine = jacobid.identify(ROBOT, logs, essential=10, quiet=True)
    assert mine["logs"] == [str(p) for p in logs]
    assert_same_cli_json(mine, reference)
    assert mine["methods"]["jacobi"]["segments"], "one report line per log"


def test_several_logs_as_arrays_give_the_files_numbers(main_job_logs):
    def arrays(path):
        data = np.genfromtxt(path, delimiter=",", names=True)
        return (data["t"], np.column_stack([data["q1"], data["q2"]]), np.column_stack([data["tau1"], data["tau2"]]))

    files = [main_job_logs / "log.csv", main_job_logs / "validation.csv"]
    from_files = jacobid.identify(ROBOT, files, quiet=True)
    from_arrays = jacobid.identify(ROBOT, [arrays(p) for p in files], quiet=True)
    for name in from_files["parameter_order"]:
        # The CSV holds the values to 17 digits: the same doubles.
        assert from_arrays["parameters"][name]["value"] == pytest.approx(from_files["parameters"][name]["value"], rel=RTOL)


def test_physical_is_the_cli_physical(cli, cli_json, tmp_path):
    log = simulate(cli, MDH_ROBOT, tmp_path / "mdh.csv", "--duration", "20", "--seed", "5")
    reference = cli_json("identify", "--robot", MDH_ROBOT, "--in", log, "--physical", "--format", "json", "--quiet")
    mine = jacobid.identify(MDH_ROBOT, log, physical=True, quiet=True)
    assert "physical" in mine, "the physically consistent fit's report"
    assert_same_cli_json(mine, reference)


def periodic_trajectory(path, period=4.0):
    """Four harmonics per joint, at rest at t = 0 with zero acceleration (as tests/integration's periodic test)."""
    w = 2 * math.pi / period
    t = np.arange(0, int(period * 1000) + 1) * 1e-3
    pose, a, b = (0.2, 0.9), (0.8, -0.6), (0.3, 0.4)
    cols = {"t": t}
    for j in range(2):
        cols[f"q{j + 1}"] = pose[j] + a[j] * ((1 - np.cos(w * t)) - (1 - np.cos(2 * w * t)) / 4) + \
            b[j] * ((1 - np.cos(3 * w * t)) - 9 * (1 - np.cos(4 * w * t)) / 16)
        cols[f"qd{j + 1}"] = a[j] * (w * np.sin(w * t) - 2 * w * np.sin(2 * w * t) / 4) + \
            b[j] * (3 * w * np.sin(3 * w * t) - 9 * 4 * w * np.sin(4 * w * t) / 16)
        cols[f"qdd{j + 1}"] = a[j] * (w * w * np.cos(w * t) - 4 * w * w * np.cos(2 * w * t) / 4) + \
            b[j] * (9 * w * w * np.cos(3 * w * t) - 9 * 16 * w * w * np.cos(4 * w * t) / 16)
    names = ["t", "q1", "q2", "qd1", "qd2", "qdd1", "qdd2"]
    np.savetxt(path, np.column_stack([cols[n] for n in names]), delimiter=",", header=",".join(names), comments="", fmt="%.17g")
    return path


def test_period_auto_is_the_cli_period(cli, cli_json, tmp_path):
    trajectory = periodic_trajectory(tmp_path / "trajectory.csv")
    log = simulate(cli, ROBOT, tmp_path / "periodic.csv", "--trajectory", trajectory, "--duration", "20", "--seed", "1", "--noise-seed", "7")
    reference = cli_json("identify", "--robot", ROBOT, "--in", log, "--period", "auto", "--format", "json", "--quiet")
    mine = jacobid.identify(ROBOT, log, period="auto", quiet=True)
    assert mine["period"]["periods"] == 5
    assert_same_cli_json(mine, reference)


def test_on_gap_split_is_the_cli_split(cli_json, main_job_logs, tmp_path):
    # The main job's log with 2 s of rows cut out, read through a log format that splits at the gap.
    lines = (main_job_logs / "log.csv").read_text().splitlines()
    kept = [lines[0]] + [line for line in lines[1:] if not 25.0 - 1e-9 <= float(line.split(",", 1)[0]) < 27.0 - 1e-9]
    gap = tmp_path / "gap.csv"
    gap.write_text("\n".join(kept) + "\n")
    fmt = tmp_path / "format.yaml"
    fmt.write_text("header: true\ntime: {column: t}\npositions: [q1, q2]\ntorques: [tau1, tau2]\n")
    reference = cli_json("identify", "--robot", ROBOT, "--in", gap, "--log-format", fmt, "--on-gap", "split", "--format", "json", "--quiet")
    mine = jacobid.identify(ROBOT, gap, log_format=fmt, on_gap="split", quiet=True)
    assert len(mine["methods"]["jacobi"]["segments"]) == 2
    assert_same_cli_json(mine, reference)
