# SPDX-License-Identifier: MIT
"""jacobid.monitor_calibrate and jacobid.monitor against the command line (docs/monitor.md): the same
thresholds and events as `jacobid monitor calibrate --json` and `jacobid monitor --json`, the simulated
pulses found, and the command line's refusals."""
import json

import pytest

import jacobid
from conftest import SOURCE_DIR

ARM = SOURCE_DIR / "examples" / "robots" / "ur5_like.yaml"
OPTIONS = ["--velocity-window", "0.04", "--xi", "0.5", "--false-alarm-rate", "0", "--margin", "0.5"]


@pytest.fixture(scope="module")
def logs(cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("monitor")
    for seed in (1, 2):
        status, _, err = cli("simulate", "--robot", ARM, "--out", out / f"free{seed}.csv", "--duration", "10", "--seed", seed, "--quiet")
        assert status == 0, err
    status, _, err = cli("simulate", "--robot", ARM, "--out", out / "pulse.csv", "--duration", "10", "--seed", 7, "--quiet",
                         "--effect", "external:joint=2,start=4,duration=0.5,value=20")
    assert status == 0, err
    return out


def test_calibrate_and_monitor_are_the_command_line(cli_json, logs):
    frees = [logs / "free1.csv", logs / "free2.csv"]
    mine = jacobid.monitor_calibrate(ARM, frees, logs / "py.yaml", velocity_window=0.04, xi=0.5, false_alarm_rate=0, margin=0.5)
    reference = cli_json("monitor", "calibrate", "--robot", ARM, "--in", frees[0], "--in", frees[1], "--out", logs / "cli.yaml", "--json", *OPTIONS)
    assert [j["moving"] for j in mine["joints"]] == [j["moving"] for j in reference["joints"]]
    assert [j["standing"] for j in mine["joints"]] == [j["standing"] for j in reference["joints"]]
    events = jacobid.monitor(ARM, logs / "pulse.csv", logs / "py.yaml")
    assert events["events"] == cli_json("monitor", "--robot", ARM, "--monitor", logs / "cli.yaml", "--in", logs / "pulse.csv", "--json")["events"]
    # The pulse as simulate was told: joint 2, 20 N.m from 4 s.
    assert len(events["events"]) == 1
    event = events["events"][0]
    assert event["joints"] == [2]
    assert 4.0 <= event["start"] <= 4.02
    assert event["median"][1] == pytest.approx(20.0, rel=0.1)


def test_refusals_are_the_command_line_messages(logs):
    with pytest.raises(jacobid.InputError, match="gian: unknown keyword of monitor_calibrate"):
        jacobid.monitor_calibrate(ARM, [logs / "free1.csv"], logs / "x.yaml", gian=3)
    with pytest.raises(jacobid.InputError, match="--false-alarm-rate"):
        jacobid.monitor_calibrate(ARM, [logs / "free1.csv"], logs / "x.yaml", false_alarm_rate=2)
    with pytest.raises(jacobid.InputError, match="logs: expected one or more paths"):
        jacobid.monitor_calibrate(ARM, [], logs / "x.yaml")
    with pytest.raises(jacobid.InputError, match="cannot open"):
        jacobid.monitor(ARM, logs / "pulse.csv", logs / "missing.yaml")
