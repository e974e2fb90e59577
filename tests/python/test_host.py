# SPDX-License-Identifier: MIT
# The host bindings (robot, simulate, identify, validate, diagnose) against the jacobid command line on
# the main job's simulated logs.
import json

import numpy as np
import pytest

import jacobid
from conftest import ROBOT, assert_same_json, cli_error

RTOL = 1e-12


def assert_same_parameters(mine, reference):
    assert mine["parameter_order"] == reference["parameter_order"]
    for name in reference["parameter_order"]:
        a, b = mine["parameters"][name], reference["parameters"][name]
        for key in ("value", "std", "rel_std_percent"):
            if b[key] is None:
                assert a[key] is None, (name, key)
            else:
                assert a[key] == pytest.approx(b[key], rel=RTOL, abs=1e-300), (name, key)
        assert a["identified"] == b["identified"]


@pytest.fixture(scope="module")
def cli_identification(cli_json, main_job_logs):
    return cli_json("identify", "--robot", ROBOT, "--in", main_job_logs / "log.csv", "--method", "both", "--format", "json",
                    "--truth", main_job_logs / "log.truth.json", "--validate", main_job_logs / "validation.csv")


def test_identify_a_file_gives_the_cli_parameters(cli_identification, main_job_logs):
    mine = jacobid.identify(str(ROBOT), main_job_logs / "log.csv", method="both", truth=main_job_logs / "log.truth.json",
                            validate=main_job_logs / "validation.csv", quiet=True)
    for method in ("jacobi", "butterworth"):
        assert_same_parameters(mine["methods"][method], cli_identification["methods"][method])
        for key in ("cond", "equations", "rank", "sigma_rho", "relative_error_norm"):
            assert mine["methods"][method][key] == pytest.approx(cli_identification["methods"][method][key], rel=RTOL)
        # validate: the second log's torques predicted, as --validate reports them.
        a, b = mine["methods"][method]["validation"], cli_identification["methods"][method]["validation"]
        assert a.keys() == b.keys()
        assert_same_json(a, b, rel=RTOL, where="validation")
    assert mine["log"] == str(main_job_logs / "log.csv") and mine["model"] == cli_identification["model"]
    # The truth beside each value, as --truth adds it.
    assert mine["parameters"]["ZZ1R"]["truth"] == cli_identification["parameters"]["ZZ1R"]["truth"]


def read_log(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    column = {name: data[:, i] for i, name in enumerate(header)}
    return column["t"], np.column_stack([column["q1"], column["q2"]]), np.column_stack([column["tau1"], column["tau2"]])


def test_identify_numpy_arrays_gives_the_cli_parameters(cli_identification, main_job_logs):
    t, q, tau = read_log(main_job_logs / "log.csv")
    robot = jacobid.load_robot(ROBOT)
    mine = jacobid.identify(robot, (t, q, tau), quiet=True)
    assert_same_parameters(mine, cli_identification["methods"]["jacobi"])
    # Fortran-ordered or float32-free integer views are converted by numpy; the numbers stay.
    again = jacobid.identify(robot, (t, np.asfortranarray(q), np.asfortranarray(tau)), quiet=True)
    assert_same_parameters(again, cli_identification["methods"]["jacobi"])


def test_simulate_is_the_cli_simulation(cli, main_job_logs, tmp_path):
    robot = jacobid.load_robot(ROBOT)
    run = jacobid.simulate(robot, duration=5, rate=1000, encoder_counts=65536, torque_noise=(0.05, 0.01), seed=4)
    status, _, err = cli("simulate", "--robot", ROBOT, "--out", tmp_path / "s.csv", "--truth", tmp_path / "s.json", "--duration", 5,
                         "--rate", 1000, "--encoder-counts", 65536, "--torque-noise", "0.05,0.01", "--seed", 4)
    assert status == 0, err
    t, q, tau = read_log(tmp_path / "s.csv")
    truth = json.loads((tmp_path / "s.json").read_text())
    assert run["samples"] == truth["samples"] == len(t)
    np.testing.assert_allclose(run["t"], t, rtol=0, atol=5e-7)  # the CSV prints t with 6 decimals
    np.testing.assert_allclose(run["q"], q, rtol=1e-11, atol=1e-13)  # q printed with 12 digits
    np.testing.assert_allclose(run["tau"], tau, rtol=1e-9, atol=1e-11)  # tau with 10
    assert run["parameters"] == truth["parameters"] and run["parameter_order"] == truth["parameter_order"]
    # Identifying the simulated arrays recovers the truth (Table II) within a few reported std.
    fit = jacobid.identify(robot, run, quiet=True)
    assert fit["parameters"]["ZZ1R"]["value"] == pytest.approx(truth["parameters"]["ZZ1R"], rel=0.05)


def test_errors_carry_the_cli_messages(cli, main_job_logs, tmp_path):
    robot = jacobid.load_robot(ROBOT)
    # A log without the torque column of joint 2.
    text = (main_job_logs / "log.csv").read_text().splitlines()
    header = text[0].split(",")
    keep = [i for i, name in enumerate(header) if name != "tau2"]
    (tmp_path / "short.csv").write_text("\n".join(",".join(line.split(",")[i] for i in keep) for line in text[:3000]) + "\n")
    cases = [
        (("--in", tmp_path / "short.csv"), dict(log=tmp_path / "short.csv")),
        (("--in", tmp_path / "missing.csv"), dict(log=tmp_path / "missing.csv")),
        (("--in", main_job_logs / "log.csv", "--bandwidth", "-3"), dict(log=main_job_logs / "log.csv", bandwidth=-3)),
        (("--in", main_job_logs / "log.csv", "--weighted", "--unweighted"), dict(log=main_job_logs / "log.csv", weighted=True, unweighted=True)),
        (("--in", main_job_logs / "log.csv", "--torque-delay", "soon"), dict(log=main_job_logs / "log.csv", torque_delay="soon")),
        (("--in", main_job_logs / "log.csv", "--velocity", "butterworth", "--method", "jacobi"),
         dict(log=main_job_logs / "log.csv", velocity="butterworth", method="jacobi")),
    ]
    for args, call in cases:
        expected = cli_error(cli, "identify", "--robot", ROBOT, *args)
        with pytest.raises(jacobid.InputError) as error:
            jacobid.identify(robot, **call)
        assert str(error.value) == expected
    expected = cli_error(cli, "identify", "--robot", tmp_path / "nothere.yaml", "--in", main_job_logs / "log.csv")
    with pytest.raises(jacobid.InputError) as error:
        jacobid.load_robot(tmp_path / "nothere.yaml")
    assert str(error.value) == expected
    with pytest.raises(jacobid.InputError, match="expected 60001 x 2"):
        t, q, tau = read_log(main_job_logs / "log.csv")
        jacobid.identify(robot, (t, q[:, :1], tau))
    with pytest.raises(jacobid.InputError, match="is nan"):
        q[5, 1] = np.nan
        jacobid.identify(robot, (t, q, tau))


def test_diagnose_is_the_cli_diagnosis(cli_json, cli, main_job_logs, tmp_path):
    status, _, err = cli("simulate", "--robot", ROBOT, "--out", tmp_path / "hidden.csv", "--duration", 30, "--torque-noise", "0.05,0.01",
                         "--effect", "coulomb_offset:joint=1,value=0.3")
    assert status == 0, err
    reference = cli_json("diagnose", "--robot", ROBOT, "--in", tmp_path / "hidden.csv", "--validate", main_job_logs / "validation.csv",
                         "--format", "json", "--quiet", "--no-delay")
    mine = jacobid.diagnose(ROBOT, tmp_path / "hidden.csv", validate=main_job_logs / "validation.csv", quiet=True, no_delay=True)
    mine.pop("seconds", None), reference.pop("seconds", None)
    assert_same_json(mine, reference, rel=RTOL)
