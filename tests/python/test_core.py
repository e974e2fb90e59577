# SPDX-License-Identifier: MIT
# The core bindings (kernel, frequency response, batch differentiation, bank, Butterworth baseline) against
# the jacobid command line on the same data, and against closed forms.
import numpy as np
import pytest

import jacobid
from conftest import cli_error

KERNELS = [
    dict(order=1, kappa=6, mu=6, q=2, window=0.21, ts=0.001),
    dict(order=2, kappa=12, mu=12, q=6, window=0.1, ts=0.001, discretization="exact"),
    dict(order=1, kappa=2, mu=3, q=1, window=0.05, ts=0.002, xi="delayed"),
]


def cli_options(options):
    args = []
    for key, value in options.items():
        args += ["--" + key.replace("_", "-"), str(value)]
    return args


@pytest.mark.parametrize("options", KERNELS)
def test_kernel_is_the_cli_kernel_json(cli_json, options):
    reference = cli_json("kernel", "--format", "json", *cli_options(options))
    mine = jacobid.kernel(**options)
    assert isinstance(mine["weights"], np.ndarray)
    # The same producer and doubles printed to round-trip: identical, not merely close.
    assert mine["weights"].tolist() == reference["weights"]
    for key in ("parameters", "taps", "effective_window", "delay_samples", "delay_seconds", "cutoff_hz", "weights_order"):
        assert mine[key] == reference[key], key


def test_kernel_errors_carry_the_cli_messages(cli):
    for options in (dict(window=0.21, ts=0.001, kappa=-2), dict(window=0.001, ts=0.001, q=4), dict(ts=0.001), dict(window=0.2, ts=0.001, xi="sideways")):
        expected = cli_error(cli, "kernel", *cli_options(options))
        with pytest.raises(jacobid.InputError) as error:
            jacobid.kernel(**options)
        assert str(error.value) == expected
        assert isinstance(error.value, ValueError)


def test_frequency_response_is_the_fir_sum():
    w = jacobid.kernel(order=1, window=0.05, ts=0.001)["weights"]
    f = np.array([0.0, 1.0, 7.5, 40.0, 200.0])
    h = jacobid.frequency_response(w, 0.001, f)
    # H(f) = sum_j w[L-1-j] exp(-i 2 pi f Ts j): weights oldest first, the newest sample has lag 0.
    lags = np.arange(len(w))
    expected = np.array([np.sum(w[::-1] * np.exp(-2j * np.pi * fi * 0.001 * lags)) for fi in f])
    np.testing.assert_allclose(h["response"], expected, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(h["magnitude"], np.abs(expected), rtol=1e-12, atol=1e-12)
    # A velocity estimator is a differentiator at low frequency: |H(1 Hz)| ~ 2 pi.
    assert abs(h["magnitude"][1] - 2 * np.pi) < 1e-3 * 2 * np.pi


def sine_log(path, ts=0.001, n=3000):
    t = np.arange(n) * ts
    x = np.sin(2 * np.pi * 1.3 * t) + 0.3 * np.cos(2 * np.pi * 0.4 * t)
    with open(path, "w") as f:
        f.write("t,x\n")
        for ti, xi in zip(t, x):
            f.write(f"{ti:.6f},{xi!r}\n")
    return t, x


@pytest.mark.parametrize("order,window", [(1, 0.1), (2, 0.2), (0, 0.05)])
def test_differentiate_is_the_cli_differentiate(cli, tmp_path, order, window):
    t, x = sine_log(tmp_path / "sine.csv")
    status, _, err = cli("differentiate", "--in", tmp_path / "sine.csv", "--columns", "x", "--orders", order, "--window", window,
                         "-o", tmp_path / "d.csv")
    assert status == 0, err
    reference = np.loadtxt(tmp_path / "d.csv", delimiter=",", skiprows=1)
    e = jacobid.differentiate(x, order=order, window=window, ts=0.001)
    assert len(e.values) == len(reference)
    np.testing.assert_array_equal(e.values, reference[:, 1])
    np.testing.assert_allclose(e.first_index * 0.001, reference[0, 0], rtol=0, atol=1e-12)


def test_differentiate_matches_the_analytic_derivative():
    ts = 0.001
    t = np.arange(4000) * ts
    x = np.sin(2 * np.pi * 1.3 * t)
    e = jacobid.differentiate(x, order=1, window=0.1, ts=ts, kappa=6, mu=6, q=2)
    at = (e.first_index + np.arange(len(e.values))) * ts
    exact = 2 * np.pi * 1.3 * np.cos(2 * np.pi * 1.3 * at)
    # The kernel's low-pass bias at 1.3 Hz for a 0.1 s window is far below 0.1 % of the amplitude.
    assert np.max(np.abs(e.values - exact)) < 1e-3 * 2 * np.pi * 1.3


def test_differentiate_reads_other_layouts_and_refuses_short_input(cli):
    x = np.sin(np.arange(1000) * 0.01)
    strided = np.repeat(x, 2)[::2]  # a non-contiguous view: converted once by numpy, same numbers
    assert not strided.flags["C_CONTIGUOUS"]
    np.testing.assert_array_equal(jacobid.differentiate(strided, window=0.1, ts=0.001).values, jacobid.differentiate(x, window=0.1, ts=0.001).values)
    with pytest.raises(jacobid.InputError, match="shorter than the differentiator window of 101 taps"):
        jacobid.differentiate(x[:50], window=0.1, ts=0.001)
    with pytest.raises(jacobid.InputError, match="one-dimensional"):
        jacobid.differentiate(np.zeros((10, 2)), window=0.005, ts=0.001)


def test_butterworth_euler_is_the_cli_baseline(cli, tmp_path):
    t, x = sine_log(tmp_path / "sine.csv")
    for order in (0, 1, 2):
        status, _, err = cli("differentiate", "--in", tmp_path / "sine.csv", "--columns", "x", "--orders", order, "--method", "butterworth",
                             "--butterworth", "4:5", "-o", tmp_path / "b.csv")
        assert status == 0, err
        reference = np.loadtxt(tmp_path / "b.csv", delimiter=",", skiprows=1)
        e = jacobid.butterworth_euler(x, 0.001, "4:5", order)
        np.testing.assert_array_equal(e.values, reference[:, 1])
        assert abs(e.first_index * 0.001 - reference[0, 0]) < 1e-12


def test_bank_gives_the_batch_estimates():
    ts, n = 0.001, 2500
    t = np.arange(n) * ts
    q = np.column_stack([np.sin(2 * np.pi * 0.7 * t), 0.5 * np.cos(2 * np.pi * 1.1 * t) + t])
    tau = np.column_stack([np.cos(t), np.sin(3 * t)])
    bank = jacobid.Bank(2, ts=ts, window=0.05, xi="causal")
    # Two calls: the history carries over.
    first, second = bank.step(q[:1000], tau[:1000]), bank.step(q[1000:], tau[1000:])
    out = {k: np.concatenate([first[k], second[k]]) for k in first}
    valid = out["valid"]
    assert not valid[: bank.warmup_samples - 1].any() and valid[bank.warmup_samples - 1 :].all()
    idx = out["sample_index"][valid].astype(int)
    for channel, order in (("position", 0), ("velocity", 1), ("acceleration", 2)):
        for j in range(2):
            e = jacobid.differentiate(q[:, j], order=order, window=0.05, ts=ts, xi="causal")
            batch = e.values[np.round(idx - e.first_index).astype(int)]
            scale = np.max(np.abs(batch))
            np.testing.assert_allclose(out[channel][valid, j], batch, rtol=0, atol=1e-11 * scale)
    # The raw torque, delayed by the common delay: the input sample each row refers to.
    np.testing.assert_array_equal(out["torque"][valid], tau[idx])
    with pytest.raises(jacobid.InputError, match="columns"):
        bank.step(q[:, :1], tau[:, :1])
