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
(contact detection with the identified model, docs/monitor.md). Several logs as a map-reduce (docs/fleet.md):
:func:`plan`, :func:`factor`, :func:`merge`, and :mod:`jacobid.fleet` running them on Dask.
"""
from ._jacobid import (  # noqa: F401  (the public API)
    Bank,
    Estimate,
    Factor,
    Plan,
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
    "Plan", "Factor", "plan", "factor", "merge",
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


def plan(robot=None, log=None, *extra, **options):
    """identify's set-up for several logs, resolved once: the first step of ``identify --in a --in b ...``.

    What the command resolves on the longest of its logs before it reduces each one (bandwidth, Jacobi windows,
    F_p, decimation, torque delay, Coulomb smoothing, the Coulomb columns' velocity) resolved on ``log`` (one log,
    or a list: then on the longest, as identify does). robot: a :class:`Robot` or a path; log: as for
    :func:`identify`; options: identify's keywords (method, bandwidth, weighting, std, physical, essential,
    on_gap, log_format, threads ...), except period, piece_rows, drive_gains, report, export_urdf, export_robot and
    the iterated estimators (iv, didim), which need one log or the whole run in one process.

    Returns a :class:`Plan`, picklable (the robot and log_format travel as paths: on a cluster, give paths every
    worker can read). Every log of a plan must share its sample period.
    """
    return _jacobid._plan(robot, log, *extra, **options)


def factor(robot=None, log=None, plan=None, *extra, **options):
    """One log reduced with ``plan`` to what identify merges: per method and joint the triangular factor of its
    equations, their count, the lagged products the joint-HAC std needs, and the log's report lines.

    robot: the plan's robot (a :class:`Robot` or a path); log: one log, as for :func:`identify`; plan: a
    :class:`Plan`. A log too short for the plan gives a factor that says why (identify's ``segments[].why``);
    a log that cannot be read raises :class:`InputError` naming it. Returns a :class:`Factor`, picklable;
    ``Factor.nbytes`` is its size as it travels (independent of the log's length).
    """
    return _jacobid._factor(robot, log, plan, *extra, **options)


def merge(factors=None, *extra, **options):
    """The factors of several logs merged in their order and solved: the dict ``jacobid identify --in a --in b
    ... --format json`` gives for the same logs (every key, the same numbers to rounding).

    factors: a list of :class:`Factor` of one plan, each log once. The merge is associative: with
    ``solve=False`` it returns the merged :class:`Factor` instead, which merges again like any factor, so
    ``merge([merge([a, b], solve=False), merge([c, d], solve=False)])`` equals ``merge([a, b, c, d])`` to rounding
    (a tree reduction; keep the logs' order for the same ``segments`` list).
    """
    return _jacobid._merge(factors, *extra, **options)
