# SPDX-License-Identifier: MIT
# Issue 36 (bad input, round three), the Python module: every careless value a user can hand to a public
# function is refused as jacobid.InputError with one line naming the argument (and the element, key or
# keyword) and what was expected, before any computation; nothing goes through as NaN, as a dropped
# imaginary part, or as one of pybind11's internal messages. docs/reliability.md lists the audit.
import json
import os
from pathlib import Path

import numpy as np
import pytest

import jacobid
from conftest import ROBOT

KERNEL = dict(window=0.01, ts=0.001)
SAMPLES = np.sin(np.arange(300) * 0.01)
# What pybind11 and CLI11 say when a value reaches them unchecked; never part of a message to the user.
INTERNAL = ("Unable to cast", "caught in your main function", "incompatible function arguments", "incompatible constructor",
            "dimensions", "b'", "index out of range", "not iterable")


def refused(call, *args, **kwargs):
    """The message of the InputError `call` raises; fails on any other outcome or on an internal message."""
    with pytest.raises(jacobid.InputError) as error:
        call(*args, **kwargs)
    message = str(error.value)
    assert "\n" not in message, message
    for internal in INTERNAL:
        assert internal not in message, message
    return message


def bank_step(q, tau=None, joints=1):
    bank = jacobid.Bank(joints, **KERNEL)
    return bank.step(q, np.zeros((3, joints)) if tau is None else tau)


def identify_arrays(t=None, q=None, tau=None):
    n = 200
    t = np.arange(n) * 0.001 if t is None else t
    q = np.zeros((n, 2)) if q is None else q
    tau = np.zeros((n, 2)) if tau is None else tau
    return jacobid.identify(None, (t, q, tau), quiet=True)


# --- arrays: dtype, shape, finiteness ------------------------------------------------------------------------

# (the call, the value that is wrong, the message expected).
BAD_ARRAYS = [
    (lambda v: jacobid.differentiate(v, **KERNEL), [1.0, None, 3.0], "x[1] is None; expected a finite number"),
    (lambda v: jacobid.differentiate(v, **KERNEL), [1.0, 2.0, "3"], "x[2] is str '3'; expected a finite number"),
    (lambda v: jacobid.differentiate(v, **KERNEL), np.r_[SAMPLES[:7], np.nan, SAMPLES[8:]], "x[7] is nan; expected a finite number"),
    (lambda v: jacobid.differentiate(v, **KERNEL), np.r_[SAMPLES[:7], -np.inf, SAMPLES[8:]], "x[7] is -inf; expected a finite number"),
    (lambda v: jacobid.differentiate(v, **KERNEL), SAMPLES + 0j,
     "x: complex numbers (dtype complex128); expected real numbers (pass x.real if the imaginary part is to be dropped)"),
    (lambda v: jacobid.differentiate(v, **KERNEL), SAMPLES > 0, "x: booleans (dtype bool); expected numbers"),
    (lambda v: jacobid.differentiate(v, **KERNEL), np.array(["1", "2"]), "x: text (dtype <U1); expected numbers"),
    (lambda v: jacobid.differentiate(v, **KERNEL), None, "x: expected an array of numbers, got None"),
    (lambda v: jacobid.differentiate(v, **KERNEL), {"x": 1}, "x: expected an array of numbers, got dict"),
    (lambda v: jacobid.differentiate(v, **KERNEL), 5.0, "x: a single number; expected a one-dimensional array of samples"),
    (lambda v: jacobid.differentiate(v, **KERNEL), [], "x: empty (shape (0,)); expected at least one sample"),
    (lambda v: jacobid.differentiate(v, **KERNEL), np.zeros((3, 4, 5)),
     "x: an array of shape (3, 4, 5); expected a one-dimensional array of samples"),
    (lambda v: jacobid.differentiate(v, **KERNEL), [[1.0, 2.0], [3.0]],
     "x: a nested sequence whose rows differ in length; expected an array of numbers"),
    (lambda v: jacobid.butterworth_euler(v, 0.001, "4:5"), np.r_[SAMPLES[:4], np.nan], "x[4] is nan; expected a finite number"),
    (lambda v: jacobid.butterworth_euler(v, 0.001, "4:5"), SAMPLES * 1j, "x: complex numbers (dtype complex128); expected real numbers "
                                                                          "(pass x.real if the imaginary part is to be dropped)"),
    (lambda v: jacobid.frequency_response(v, 0.001, [1.0]), [1.0, float("nan")], "weights[1] is nan; expected a finite number"),
    (lambda v: jacobid.frequency_response([1.0, -1.0], 0.001, v), [1.0, None], "frequencies[1] is None; expected a finite number"),
    (lambda v: jacobid.frequency_response([1.0, -1.0], 0.001, v), [], "frequencies: empty (shape (0,)); expected at least one sample"),
    (lambda v: bank_step(v), np.full((3, 1), np.nan), "q[0, 0] is nan; expected a finite number"),
    (lambda v: bank_step(np.zeros((3, 1)), v), np.array([[0.0], [0.0], [np.inf]]), "tau[2, 0] is inf; expected a finite number"),
    (lambda v: bank_step(v), np.zeros((3, 1), dtype=complex), "q: complex numbers (dtype complex128); expected real numbers "
                                                              "(pass x.real if the imaginary part is to be dropped)"),
    (lambda v: bank_step(v), 0.5, "q: a single number; expected an array of samples x joints"),
    (lambda v: bank_step(v, joints=2), np.zeros(2),
     "q: a one-dimensional array of 2 values; expected samples x joints (1 x 2 for one sample: q.reshape(1, -1))"),
    (lambda v: bank_step(v, joints=2), np.zeros((3, 3)), "q: 3 columns, the bank has 2 joints"),
    (lambda v: identify_arrays(q=v), np.where(np.arange(400).reshape(200, 2) == 11, np.nan, 0.0), "--in q[5, 1] is nan; expected a finite number"),
    (lambda v: identify_arrays(t=v), [None] * 200, "--in t[0] is None; expected a finite number"),
    (lambda v: identify_arrays(tau=v), np.zeros((200, 2)) + 1j, "--in tau: complex numbers (dtype complex128); expected real numbers "
                                                                  "(pass x.real if the imaginary part is to be dropped)"),
]


@pytest.mark.parametrize("call,value,expected", BAD_ARRAYS, ids=[e for _, _, e in BAD_ARRAYS])
def test_bad_arrays_are_refused_naming_the_element(call, value, expected):
    assert refused(call, value) == expected


def test_a_bank_never_flags_a_nan_row_valid():
    bank = jacobid.Bank(1, **KERNEL)
    q = np.zeros((30, 1))
    q[20, 0] = np.nan
    assert refused(bank.step, q, np.zeros((30, 1))) == "q[20, 0] is nan; expected a finite number"
    # Refused before any row was fed: the history is as before the call, so the same clean rows give the same output.
    clean = np.zeros((30, 1))
    fresh = jacobid.Bank(1, **KERNEL)
    np.testing.assert_array_equal(bank.step(clean, clean)["valid"], fresh.step(clean, clean)["valid"])


def test_other_layouts_and_integer_arrays_give_the_same_numbers():
    x = np.round(100 * SAMPLES)
    reference = jacobid.differentiate(x, **KERNEL).values
    for layout in (x.astype(np.int64), x.astype(np.float32), x.tolist(), tuple(x), np.repeat(x, 2)[::2]):
        np.testing.assert_array_equal(jacobid.differentiate(layout, **KERNEL).values, reference)


# --- keywords ----------------------------------------------------------------------------------------------------


def test_a_misspelt_keyword_is_named_as_unknown_with_the_closest_suggested():
    message = refused(jacobid.differentiate, SAMPLES, windw=0.01, ts=0.001)
    assert message.startswith("windw: unknown keyword of differentiate (did you mean window?); its keywords: x, "), message
    assert "ts" in message.split("its keywords: ")[1]
    message = refused(jacobid.kernel, window=0.01, tss=0.001)
    assert message.startswith("tss: unknown keyword of kernel (did you mean ts?); its keywords: "), message
    # The function's own arguments are keywords too.
    message = refused(jacobid.identify, None, str(ROBOT), validat="v.csv")
    assert message.startswith("validat: unknown keyword of identify (did you mean validate?)"), message
    message = refused(jacobid.Bank, 2, ts=0.001, windos=(0.01, 0.01, 0.01))
    assert message.startswith("windos: unknown keyword of Bank (did you mean windows?)"), message
    assert refused(jacobid.frequency_response, [1.0, -1.0], 0.001, frequency=[1.0]).startswith(
        "frequency: unknown keyword of frequency_response (did you mean frequencies?)")
    # Nothing close: no guess, the keywords listed.
    message = refused(jacobid.simulate, jacobid.load_robot(), colour="red")
    assert message.startswith("colour: unknown keyword of simulate; its keywords: robot, "), message


def test_cli11_internals_and_wrong_value_types_are_one_line_errors():
    assert refused(jacobid.differentiate, SAMPLES, help=True, **KERNEL).startswith("help: unknown keyword of differentiate")
    assert refused(jacobid.kernel, window=True, ts=0.001) == "--window: expected a value, got True"
    assert refused(jacobid.identify, None, "log.csv", weighted=1) == "--weighted: a flag, expected True or False, got 1"
    assert refused(jacobid.kernel, window={"a": 1}, ts=0.001) == "--window: expected a number, text or path, got dict"
    assert refused(jacobid.kernel, window=0.01, ts=0.001 + 1j) == "--ts: expected a real number, got complex (0.001+1j)"
    # A text value that looks like an option is the value, not another option.
    assert refused(jacobid.kernel, window="--ts", ts=0.001) == "--window: expected a finite number > 0, got '--ts'"
    # numpy scalars, 0-d arrays and one-dimensional arrays are numbers and lists.
    assert jacobid.kernel(window=np.array(0.01), ts=0.001)["taps"] == 11
    sim = jacobid.simulate(None, duration=0.5, torque_noise=np.array([0.05, 0.01]))
    assert np.array_equal(sim["tau"], jacobid.simulate(None, duration=0.5, torque_noise=(0.05, 0.01))["tau"])
    np.testing.assert_array_equal(jacobid.kernel(window=np.float64(0.01), ts=np.float32(0.5) / 500, order=np.int64(1))["weights"],
                                  jacobid.kernel(window=0.01, ts=float(np.float32(0.5) / 500), order=1)["weights"])


BAD_SCALARS = [
    (lambda: jacobid.frequency_response([1.0, -1.0], None, [1.0]), "--ts is required"),
    (lambda: jacobid.frequency_response([1.0, -1.0], float("inf"), [1.0]), "--ts: expected a finite number > 0, got 'inf'"),
    # Text is the command line's text, as for every keyword: "0.001" is 0.001, "fast" is refused.
    (lambda: jacobid.frequency_response([1.0, -1.0], "fast", [1.0]), "--ts: expected a finite number > 0, got 'fast'"),
    (lambda: jacobid.butterworth_euler(SAMPLES, 0.001, "4:5", crop=-1), "--crop: expected a whole number >= 0, got '-1'"),
    (lambda: jacobid.butterworth_euler(SAMPLES, 0.001, "4:5", order=3), "--order: expected a whole number in [0, 2], got '3'"),
    (lambda: jacobid.butterworth_euler(SAMPLES, 0.001, "4:5", order=1.5), "--order: expected a whole number in [0, 2], got '1.5'"),
    (lambda: jacobid.butterworth_euler(SAMPLES, 0.0, "4:5"), "--ts: expected a finite number > 0, got '0.0'"),
    (lambda: jacobid.Bank("two", **KERNEL), "--joints: expected a whole number in [1, 8], got 'two'"),
    (lambda: jacobid.Bank(2.0, **KERNEL), "--joints: expected a whole number in [1, 8], got '2.0'"),
    (lambda: jacobid.Bank(0, **KERNEL), "--joints: expected a whole number in [1, 8], got '0'"),
    (lambda: jacobid.Bank(9, **KERNEL), "--joints: expected a whole number in [1, 8], got '9'"),
    (lambda: jacobid.Bank(2, ts=0.001, windows=(0.01,)), "--windows: expected 3 windows (orders 0, 1, 2), got 1"),
    (lambda: jacobid.Bank(2, ts=0.001, window=0.01, windows=(0.01, 0.01, 0.01)), "--window and --windows: give one of them"),
    (lambda: jacobid.identify(None, 5), "--in: expected a path, a tuple (t, q, tau) or simulate()'s result, got int"),
    (lambda: jacobid.identify(None, (np.zeros(3), np.zeros(3))), "--in: expected a path or a tuple (t, q, tau), got 2 items"),
    (lambda: jacobid.identify(None, {"t": np.zeros(3)}), "--in: a dict without 'q'; expected simulate()'s result (keys t, q, tau)"),
    (lambda: jacobid.simulate(42), "robot: expected a Robot or the path of a robot description, got int"),
    (lambda: jacobid.kernel(0.01, ts=0.001), "kernel: got 1 positional argument, takes 0; give the options as keywords"),
    (lambda: jacobid.differentiate(SAMPLES, 0.01, ts=0.001), "differentiate: got 2 positional arguments, takes 1 (x); give the options as keywords"),
    (lambda: jacobid.identify(None, "log.csv", None, None, "jacobi"),
     "identify: got 5 positional arguments, takes 4 (robot, log, validate, truth); give the options as keywords"),
    (lambda: jacobid.Bank(1, **KERNEL).reset(True), "reset: got 1 positional argument, takes 0; give the options as keywords"),
    (lambda: jacobid.load_robot().base_parameters(format="json"), "format: unknown keyword of base_parameters; it takes none"),
    (lambda: jacobid.kernel(window="", ts=0.001), "--window: expected a value, got ''"),
    (lambda: jacobid.simulate(None, torque_noise=[]), "--torque-noise: expected a value, got []"),
    # A log given as arrays: where the shared log checks name a line, the number is the sample's index.
    (lambda: identify_arrays(t=np.r_[0.0, 0.002, 0.001, np.arange(3, 200) * 0.001]),
     "--in arrays:2: column 't': time 0.001 is not after the previous 0.002 (time must increase)"),
    (lambda: jacobid.load_robot(3.5), "path: expected a path (str, bytes or os.PathLike), got float"),
]


@pytest.mark.parametrize("call,expected", BAD_SCALARS, ids=[e for _, e in BAD_SCALARS])
def test_bad_scalars_and_containers_are_refused_by_name(call, expected):
    assert refused(call) == expected


# --- truth ---------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def small_run():
    robot = jacobid.load_robot(ROBOT)
    return robot, jacobid.simulate(robot, duration=8, rate=500, seed=3)


def test_truth_must_name_exactly_the_robots_parameters(small_run, tmp_path):
    robot, run = small_run
    truth = dict(run["parameters"])
    known = ", ".join(robot.parameter_names)
    message = refused(jacobid.identify, robot, run, truth={**truth, "ZZ1": 1.0}, quiet=True)
    assert message == f"truth: parameter 'ZZ1' is not one of the robot's (did you mean ZZ1R?); its parameters: {known}"
    missing = dict(truth)
    del missing[robot.parameter_names[-1]]
    assert refused(jacobid.identify, robot, run, truth=missing, quiet=True) == (
        f"truth: no parameter '{robot.parameter_names[-1]}', which the robot has ({len(missing)} given, {len(truth)} in the model): "
        "the truth of another robot or parameter set?")
    assert refused(jacobid.identify, robot, run, truth={**truth, "ZZ1R": None}, quiet=True) == "truth['ZZ1R'] is None; expected a finite number"
    assert refused(jacobid.identify, robot, run, truth={**truth, "ZZ1R": 1 + 2j}, quiet=True) == (
        "truth['ZZ1R'] is complex (1+2j); expected a finite number")
    assert refused(jacobid.identify, robot, run, truth=[1.0], quiet=True) == (
        "truth: expected a dict name -> value, simulate()'s result or the path of simulate --truth's JSON file, got list")
    (tmp_path / "bad.json").write_text("{}")
    assert refused(jacobid.identify, robot, run, truth=tmp_path / "bad.json", quiet=True) == f"truth {tmp_path / 'bad.json'}: no object 'parameters'"
    (tmp_path / "broken.json").write_text("{'parameters': ")
    assert refused(jacobid.identify, robot, run, truth=tmp_path / "broken.json", quiet=True).startswith(f"truth {tmp_path / 'broken.json'}: invalid JSON: ")
    # The accepted forms give the same table: a dict, simulate()'s result, its JSON file by str, bytes or Path.
    (tmp_path / "t.json").write_text(json.dumps({"parameters": truth}))
    values = []
    for form in (truth, run, str(tmp_path / "t.json"), os.fsencode(tmp_path / "t.json"), tmp_path / "t.json"):
        fit = jacobid.identify(robot, run, truth=form, quiet=True)
        values.append([fit["parameters"][name]["truth"] for name in robot.parameter_names])
    assert all(v == values[0] for v in values) and values[0] == [truth[name] for name in robot.parameter_names]


# --- paths ----------------------------------------------------------------------------------------------------


class CustomPath:
    """An os.PathLike that is not a pathlib.Path."""

    def __init__(self, path):
        self.path = path

    def __fspath__(self):
        return self.path


def test_bytes_and_pathlike_paths_are_read_and_printed_decoded(small_run, tmp_path):
    missing = tmp_path / "nothere.yaml"
    for form in (os.fsencode(missing), CustomPath(os.fsencode(missing)), CustomPath(str(missing))):
        assert refused(jacobid.load_robot, form) == f"{missing}: cannot open robot description"
    # A path that is not UTF-8 is named as os.fsdecode gives it (was an empty message).
    odd = os.fsencode(tmp_path) + b"/\xff.yaml"
    assert refused(jacobid.load_robot, odd) == f"{os.fsdecode(odd)}: cannot open robot description"
    for form in (os.fsencode(ROBOT), CustomPath(str(ROBOT))):
        robot = jacobid.load_robot(form)
        assert robot.source == str(ROBOT) and robot.joint_names == jacobid.load_robot(ROBOT).joint_names
    assert jacobid.Robot(ROBOT).parameter_names == jacobid.load_robot(ROBOT).parameter_names
    robot, run = small_run
    path = tmp_path / "log.csv"
    with open(path, "w") as f:
        f.write("t,q1,q2,tau1,tau2\n")
        for i in range(len(run["t"])):
            f.write(",".join(repr(float(v)) for v in (run["t"][i], *run["q"][i], *run["tau"][i])) + "\n")
    reference = jacobid.identify(robot, str(path), quiet=True)
    for form in (os.fsencode(path), CustomPath(str(path)), path):
        fit = jacobid.identify(robot, form, quiet=True)
        assert fit["log"] == str(path)
        assert [fit["parameters"][n]["value"] for n in robot.parameter_names] == [reference["parameters"][n]["value"] for n in robot.parameter_names]
    assert refused(jacobid.identify, robot, os.fsencode(tmp_path / "gone.csv"), quiet=True).startswith(f"{tmp_path / 'gone.csv'}: ")
    assert refused(jacobid.identify, robot, path, log_format=os.fsencode(tmp_path / "f.yaml"), quiet=True).startswith(f"{tmp_path / 'f.yaml'}: ")
