# SPDX-License-Identifier: MIT
"""jacobid.fleet: many logs identified, and Monte Carlo studies run, on Dask (docs/fleet.md).

``identify --in a --in b ...`` is a map-reduce (:func:`jacobid.plan`, :func:`jacobid.factor`, :func:`jacobid.merge`);
here Dask's ``distributed`` scheduler runs it over worker processes on one host or many: the set-up is resolved
once, every log is reduced to its factor where a worker reads it, and the factors are merged by an ordered
tree (adjacent pairs, in the logs' order, so the result does not depend on the scheduling). A log that fails is
reported by its path and left out; a worker lost mid-run loses only results Dask computes again from their
tasks (nothing is scattered), so it changes no result.
"""
import math
import os
import re
from collections import namedtuple

import jacobid
from jacobid._fleet_tree import OrderedTree

__all__ = ["identify", "montecarlo", "local_cluster", "worker_settings"]

# A log that could not be factored: its name and the one-line reason (jacobid.InputError's message).
Failed = namedtuple("Failed", "log message")


def _name(log):
    """The log's name as identify names it: the path as given (os.fsdecode), or "--in" for arrays."""
    try:
        return os.fsdecode(log)
    except TypeError:
        return "--in"


def worker_settings():
    """The Dask settings fleet's own LocalCluster runs with (docs/fleet.md, "Worker settings"), to pass to
    ``dask.config.set``; the same keys serve ``dask worker`` hosts as DASK_* environment variables.

    - The nanny no longer sets MALLOC_TRIM_THRESHOLD_ in the workers (Dask's default sets 65536). Any value turns
      off glibc's adaptive mmap threshold, so a factor's multi-megabyte buffers are mapped and zeroed afresh for
      every log: 14 % of a worker's time on the PUMA 560 logs of benchmarks/bench_fleet_dask.py. The memory
      returns to the heap and the next log reuses it.
    - No statistical profiler (it feeds only the dashboard's profile page), and the memory and system monitors
      every 1 s and 2 s instead of 0.1 s and 0.5 s: with one worker per core, each worker's event loop takes its
      CPU from the other worker's core.
    """
    import dask

    environ = {k: v for k, v in dask.config.get("distributed.nanny.pre-spawn-environ", {}).items() if k != "MALLOC_TRIM_THRESHOLD_"}
    return {"distributed.nanny.pre-spawn-environ": environ,
            "distributed.worker.profile.enabled": False,
            "distributed.worker.memory.monitor-interval": "1s",
            "distributed.admin.system-monitor.interval": "2s"}


def local_cluster(n_workers=None, **cluster_options):
    """A ``distributed.LocalCluster`` of single-threaded worker processes (one per core when n_workers is None)
    with :func:`worker_settings`: the cluster identify and montecarlo start when given no client.
    cluster_options: LocalCluster's other keywords."""
    import dask
    import distributed

    options = {"threads_per_worker": 1, "processes": True, "dashboard_address": ":0", **cluster_options}
    # The nanny reads the settings when it is made and hands them to its worker process.
    with dask.config.set(worker_settings()):
        return distributed.LocalCluster(n_workers=n_workers, **options)


def _factor_task(robot, log, plan):
    """Map: one log's factor, or Failed when the log cannot be read (a log too short for the plan gives a factor
    that says why, as identify reports it in segments[].why)."""
    try:
        return jacobid.factor(robot, log, plan)
    except jacobid.InputError as e:
        return Failed(_name(log), str(e))


def _merge_task(a, b):
    """Reduce: two adjacent partial results merged in order."""
    return jacobid.merge([a, b], solve=False)


def _solve_task(merged):
    """The merged factor solved: identify's dict, or None when no log gave a factor."""
    return None if merged is None else jacobid.merge([merged])


def _describe_task(result):
    """What the driver keeps of a factor without moving it: ("ok", bytes it travels as) or ("failed", message)."""
    if isinstance(result, Failed):
        return ("failed", result.message)
    return ("ok", result.nbytes)


def _plan_on_cluster(client, robot, logs, options, failed):
    """The plan, resolved on a worker on the first log that can be planned (the ones before it go to `failed`)."""
    for log in logs:
        try:
            return client.submit(jacobid.plan, robot, log, pure=False, **options).result()
        except jacobid.InputError as e:
            failed[_name(log)] = str(e)
    raise jacobid.InputError(f"logs: none of the {len(logs)} logs can be planned: " + "; ".join(failed.values()))


def _joint_of(name, joint_names):
    """The joint a base parameter belongs to, from its name's joint index (FV2, ZZ1R, XX2R: joint 2, 1, 2)."""
    m = re.search(r"(\d+)R?$", name)
    if not m or not 1 <= int(m.group(1)) <= len(joint_names):
        return None
    return joint_names[int(m.group(1)) - 1]


def _reference(estimates):
    """The median of other robots' (value, std) and its std: robust to one drifted robot among them, which would
    drag their pooled estimate (with an even count, the mean of the middle two)."""
    ranked = sorted(estimates)
    half = len(ranked) // 2
    if len(ranked) % 2:
        return ranked[half]
    (a, sa), (b, sb) = ranked[half - 1], ranked[half]
    return (a + b) / 2, math.hypot(sa, sb) / 2


def _deviations(identifications, pooled, joint_names, threshold):
    """Each robot against the others, parameter by parameter: z = (x_robot - m) / sqrt(std_robot^2 + std_m^2), m the
    median of the other robots' estimates (their logs are not the robot's, so the variances add). Returns robot id
    -> (deviation by parameter, the parameters with |z| > threshold, largest |z| first)."""
    out = {}
    for rid, own in identifications.items():
        others = [fit for other, fit in identifications.items() if other != rid and fit is not None]
        deviation, drifted = {}, []
        for name in pooled["parameter_order"] if own is not None and others else []:
            a, p = own["parameters"][name], pooled["parameters"][name]
            rest = [(o["parameters"][name]["value"], o["parameters"][name]["std"]) for o in others
                    if o["parameters"][name]["identified"] and o["parameters"][name]["std"] is not None]
            if not a["identified"] or a["std"] is None or len(rest) < len(others):
                continue
            m, sm = _reference(rest)
            z = (a["value"] - m) / math.hypot(a["std"], sm)
            deviation[name] = {"value": a["value"], "std": a["std"], "pooled": p["value"], "deviation": a["value"] - p["value"],
                               "others": m, "others_std": sm, "z": z}
            if abs(z) > threshold:
                drifted.append({"parameter": name, "joint": _joint_of(name, joint_names), "z": z, "relative": (a["value"] - m) / m if m else None})
        drifted.sort(key=lambda d: -abs(d["z"]))
        out[rid] = (deviation, drifted)
    return out


def identify(robot, logs, client=None, by_robot=None, *, plan=None, threshold=5.0, progress=None, timeout=None, **identify_options):
    """Identify from every log of ``logs`` on Dask, as ``jacobid identify --in LOG1 --in LOG2 ...`` would.

    robot: a :class:`jacobid.Robot` or the path of its description; logs: paths (on a cluster, paths every worker
    can read) or arrays as :func:`jacobid.identify` takes them. client: a ``dask.distributed.Client``; None: a
    LocalCluster of one single-threaded worker process per core, closed at the end. by_robot: a mapping log ->
    robot id; then each robot is also identified from its own logs and compared with the other robots.
    plan: a :class:`jacobid.Plan`; None: resolved on a worker on the first log (identify resolves it on the
    longest: the same when the logs are equally long). Every robot's identification uses this plan too, so that
    all are made with the same filters. threshold: |z| above which a robot's parameter is
    named as drifted. progress: called on the driver as progress(log, future) when a log's factor is done.
    timeout: seconds to wait at each step (the factors, the merges; None: no limit): a
    ``distributed.TimeoutError`` after it. identify_options: identify's keywords (as for
    :func:`jacobid.plan`; threads defaults to 1, one log per worker thread).

    Returns a dict: ``pooled`` (identify's dict for every log that gave a factor), ``failed`` (log -> the reason it
    was left out), ``factor_bytes`` (log -> bytes its factor travelled as), ``plan`` (the Plan), and with by_robot
    ``robots``: id -> {``logs``, ``identification`` (identify's dict of its logs), ``deviation`` (parameter ->
    value, std, pooled, deviation = value - pooled, others = the median of the other robots' values, others_std,
    z = (value - others) / sqrt(std^2 + others_std^2)), ``drifted`` (the parameters with |z| > threshold:
    parameter, joint, z, relative = (value - others) / others, largest |z| first)}. The median, not the pool,
    is the reference: a drifted robot's logs are in the pool and drag it towards itself.
    """
    import distributed

    logs = list(logs)
    if not logs:
        raise jacobid.InputError("logs: an empty list; expected the logs to identify")
    if by_robot is not None:
        missing = [_name(log) for log in logs if log not in by_robot]
        if missing:
            raise jacobid.InputError(f"by_robot: no robot id for {missing[0]}; expected every log of logs mapped to its robot")
    options = dict(identify_options)
    options.setdefault("threads", 1)
    own_cluster = client is None
    if own_cluster:
        client = distributed.Client(local_cluster())
    try:
        failed = {}
        if plan is None:
            plan = _plan_on_cluster(client, robot, logs, options, failed)
        factors = [client.submit(_factor_task, robot, log, plan, pure=False) for log in logs]
        described = [client.submit(_describe_task, f, pure=False) for f in factors]
        # Only the small descriptions come to the driver; the factors stay on the workers. As soon as the logs
        # before one are known, its factor joins the trees (pooled, its robot's), which merge while the other logs
        # are still factored: over the logs that gave a factor, paired as identify --in pairs those logs.
        def merge(left, right):
            return client.submit(_merge_task, left, right, pure=False)

        trees = {"pooled": OrderedTree(merge)}
        groups = {}
        statuses = [None] * len(logs)
        joined = 0  # the logs before this one are in the trees (or in failed)
        position = {d.key: k for k, d in enumerate(described)}
        pending = set(described)
        while pending:
            done, pending = distributed.wait(pending, timeout=timeout, return_when="FIRST_COMPLETED")
            done = sorted(done, key=lambda d: position[d.key])
            for d, status in zip(done, client.gather(done)):
                statuses[position[d.key]] = status
                if progress is not None:
                    progress(logs[position[d.key]], factors[position[d.key]])
            while joined < len(logs) and statuses[joined] is not None:
                log, future, (status, _) = logs[joined], factors[joined], statuses[joined]
                joined += 1
                if status != "ok":
                    continue
                trees["pooled"].add(future)
                if by_robot is not None:
                    groups.setdefault(by_robot[log], []).append((log, future))
                    trees.setdefault(by_robot[log], OrderedTree(merge)).add(future)
        factor_bytes = {}
        for log, (status, value) in zip(logs, statuses):
            (failed if status == "failed" else factor_bytes)[_name(log)] = value
        solves = {key: client.submit(_solve_task, tree.result(), pure=False) for key, tree in trees.items()}
        distributed.wait(list(solves.values()), timeout=timeout)
        keys = list(solves)
        solved = dict(zip(keys, client.gather([solves[k] for k in keys])))
        if solved["pooled"] is None:
            raise jacobid.InputError("logs: none of the logs gave a factor: " + "; ".join(f"{k}: {v}" for k, v in failed.items()))
        out = {"pooled": solved["pooled"], "failed": failed, "factor_bytes": factor_bytes, "plan": plan}
        if by_robot is not None:
            own = {rid: solved[rid] for rid in groups}
            compared = _deviations(own, solved["pooled"], plan.robot.joint_names, threshold)
            out["robots"] = {rid: {"logs": [_name(log) for log, _ in members], "identification": own[rid],
                                   "deviation": compared[rid][0], "drifted": compared[rid][1]} for rid, members in groups.items()}
        return out
    finally:
        if own_cluster:
            cluster = client.cluster
            client.close()
            cluster.close()


def _montecarlo_task(robot, first, count, options):
    """Map: runs first .. first + count - 1 of the study (each run's numbers depend on its seeds alone)."""
    return jacobid._jacobid._montecarlo_runs(robot, first, count, **options)


def montecarlo(robot=None, client=None, *, runs_per_task=1, format="table", timeout=None, **montecarlo_options):
    """The runs of ``jacobid montecarlo`` as Dask tasks: the same table (or with format="json" the same JSON).

    robot: the path of a robot description (None: the planar 2R); on a cluster, a path every worker can read.
    client: a ``dask.distributed.Client``; None: a LocalCluster of one single-threaded worker process per core,
    closed at the end. runs_per_task: runs simulated and identified by one task. montecarlo_options: the
    command's options as keywords (runs=40, seed=100, noise_seed=500, duration, rate, torque_noise, method,
    bandwidth, weighting ... as ``jacobid montecarlo --help`` lists them; threads is ignored: one run per worker
    thread). Run k has seeds seed + k and noise_seed + k wherever it runs, so the table's numbers are the
    command's; its first line gives the wall time and the number of workers instead of threads.
    """
    import time

    import distributed

    options = {k: v for k, v in montecarlo_options.items() if k != "threads"}
    runs = int(options.get("runs", 40))
    if robot is not None:
        robot = os.path.abspath(os.fsdecode(robot))
    own_cluster = client is None
    if own_cluster:
        client = distributed.Client(local_cluster())
    try:
        start = time.monotonic()
        if runs < 2:  # the command's message, before any task
            jacobid._jacobid._montecarlo_table(robot, [], 0.0, 1, format, **options)
        step = max(1, int(runs_per_task))
        tasks = [client.submit(_montecarlo_task, robot, first, min(step, runs - first), options, pure=False) for first in range(0, runs, step)]
        distributed.wait(tasks, timeout=timeout)
        estimates = [run for chunk in client.gather(tasks) for run in chunk]
        workers = len(client.scheduler_info()["workers"])
        return jacobid._jacobid._montecarlo_table(robot, estimates, time.monotonic() - start, workers, format, **options)
    finally:
        if own_cluster:
            cluster = client.cluster
            client.close()
            cluster.close()
