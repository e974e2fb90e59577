# SPDX-License-Identifier: MIT
"""jacobid: robot dynamic identification with the Jacobi (algebraic) differentiator.

numpy arrays in and out, the command line's options as keyword arguments (``bandwidth=5`` is ``--bandwidth 5``,
``log_format="ur10e.yaml"`` is ``--log-format ur10e.yaml``, ``weighted=True`` the flag ``--weighted``), results as
plain dicts with the names of the command line's JSON output, and bad input raised as :class:`InputError` (a
``ValueError``) with the one-line message ``jacobid`` prints. Every argument is checked before anything is computed:
arrays must hold finite real numbers (no NaN, None, complex or text), keywords must be known (a misspelt one is
named, with the closest valid keyword). docs/python.md has the whole story.

Core (the real-time library, lib/): :func:`kernel`, :func:`frequency_response`, :func:`differentiate`,
:class:`Bank`, :func:`butterworth_euler`. Host (jacobid::host): :func:`load_robot`, :func:`simulate`,
:func:`identify` (with ``validate=``), :func:`diagnose`, :func:`monitor_calibrate` and :func:`monitor` (contact
detection with the identified model, docs/monitor.md).
"""
from ._jacobid import (  # noqa: F401  (the public API)
    Bank,
    Estimate,
    InputError,
    Robot,
    __version__,
    butterworth_euler,
    differentiate,
    frequency_response,
    kernel,
    load_robot,
    monitor,
    monitor_calibrate,
    simulate,
)
from . import _jacobid

__all__ = [
    "Bank", "Estimate", "InputError", "Robot", "butterworth_euler", "differentiate", "frequency_response",
    "kernel", "load_robot", "simulate", "identify", "diagnose", "monitor", "monitor_calibrate", "__version__",
]


def identify(robot=None, log=None, validate=None, truth=None, *extra, **options):
    """Identify the base dynamic parameters of ``robot`` from ``log``, as ``jacobid identify --format json``.

    robot: a :class:`Robot` or the path of its description. log and validate: a path (CSV, or a raw log with
    ``log_format=``), a tuple ``(t, q, tau)`` of numpy arrays (t in s; q, tau samples x joints), or the dict
    :func:`simulate` returns. truth: the true values (a dict name -> value, simulate's result or its --truth
    JSON file) added to each parameter. options: identify's options as keywords (method="both", bandwidth=5,
    cutoff=50, estimator="didim", weighting="ols", torque_delay=0, log_format=..., on_gap="interpolate",
    time_column="t", quiet=True ...).

    Returns the CLI's JSON as a dict: parameters (name -> value, std, rel_std_percent, identified, truth),
    parameter_order, cond, equations, sigma_rho, residual_rms, pipeline, torque_delay, validation (with validate),
    methods (every method's result), log, model ... (docs/identify.md).
    One continuous log: --on-gap split, --period, --physical, --essential and the reports are the command line's.
    """
    return _jacobid._identify(robot, log, validate, truth, *extra, **options)


def diagnose(robot=None, log=None, validate=None, *extra, **options):
    """Where the identified model misses the data, as ``jacobid diagnose --format json`` (docs/diagnose.md).

    robot, log, validate: as for :func:`identify`. options: diagnose's options as keywords (alpha, min_gain,
    max_effects, folds, max_delay, no_delay=True, max_cogging_order, horizon, horizon_spacing, bandwidth, cutoff,
    log_format ..., quiet=True). Returns the CLI's JSON as a dict (effects named, before/after errors, verdict).
    """
    return _jacobid._diagnose(robot, log, validate, *extra, **options)
