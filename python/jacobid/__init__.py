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
:func:`identify` (with ``validate=``), :func:`diagnose`, :func:`payload`, :func:`monitor_calibrate` and :func:`monitor`
(contact detection with the identified model, docs/monitor.md).
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
    "kernel", "load_robot", "simulate", "identify", "diagnose", "payload", "monitor", "monitor_calibrate", "__version__",
]


def identify(robot=None, log=None, validate=None, truth=None, *extra, **options):
    """Identify the base dynamic parameters of ``robot`` from ``log``, as ``jacobid identify --format json``.

    The command line's own identify job runs, so every feature and number is the command's. robot: a
    :class:`Robot` or the path of its description. log: a path (CSV, a raw log with ``log_format=``, a candump
    capture with ``can_config=``), a tuple ``(t, q, tau)`` of numpy arrays (t in s; q, tau samples x joints),
    the dict :func:`simulate` returns, or a list of these identified together (``--in a --in b``). validate: one
    log of those kinds. truth: the true values (a dict name -> value, simulate's result or its --truth JSON
    file) added to each parameter. options: identify's options as keywords (docs/python.md lists them all:
    method="both", bandwidth=5, cutoff=50, estimator="didim", weighting="ols", torque_delay=0, log_format=...,
    on_gap="split", period="auto", physical=True, essential=10, report="dir", export_robot="r.yaml",
    drive_gains=True with loaded=..., threads=2, quiet=True ...).

    Returns the CLI's JSON as a dict: parameters (name -> value, std, rel_std_percent, identified, truth),
    parameter_order, cond, equations, sigma_rho, residual_rms, pipeline, torque_delay, validation (with validate),
    segments, period, physical, essential, warnings, methods (every method's result), log, logs, model ...
    (docs/identify.md).
    """
    return _jacobid._identify(robot, log, validate, truth, *extra, **options)


def diagnose(robot=None, log=None, validate=None, *extra, **options):
    """Where the identified model misses the data, as ``jacobid diagnose --format json`` (docs/diagnose.md).

    robot, log, validate: as for :func:`identify`. options: diagnose's options as keywords (alpha, min_gain,
    max_effects, folds, max_delay, no_delay=True, max_cogging_order, horizon, horizon_spacing, bandwidth, cutoff,
    log_format ..., quiet=True). Returns the CLI's JSON as a dict (effects named, before/after errors, verdict).
    """
    return _jacobid._diagnose(robot, log, validate, *extra, **options)


def payload(robot=None, arm=None, log=None, unloaded=None, *extra, **options):
    """A payload's mass, centre of mass and inertia on the last link, as ``jacobid payload --json``.

    robot: the path of the robot description. arm: identify's JSON output (values and std) or a robot
    description (values only). log: the run with the payload; unloaded: the same trajectory without it (the
    payload then comes from the difference of the runs, after aligning them in time). Paths only (str, bytes or
    os.PathLike). options: the command's options as keywords (mass=2.8, frame="tool0", tool_frame=(0, 0, 0.1, 0,
    0, 0), gain_std=(0.02,) * 6, log_format=..., bandwidth=..., weighting="ols" ...).

    Returns the command's JSON as a dict: payload (mass, com_x .. I_zz: value, std, rel_std_percent, std_noise,
    std_arm, std_gain, status), standard_parameters, unidentifiable, std_includes, std_leaves_out,
    physically_consistent, violations, warnings, alignment (with unloaded) ... (docs/identify.md, "Payload").
    """
    return _jacobid._payload(robot, arm, log, unloaded, *extra, **options)
