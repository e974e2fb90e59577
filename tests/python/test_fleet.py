# SPDX-License-Identifier: MIT
# identify --in a --in b ... as a map-reduce (docs/fleet.md): jacobid.plan / factor / merge in this process, and
# jacobid.fleet.identify on a LocalCluster of 2 worker processes. The reference is the command line's JSON of the
# same logs; a worker killed mid-run and a corrupt log are checked against it too.
import os
import pickle
import signal
from pathlib import Path

import pytest

import jacobid
from conftest import ROBOT, assert_same_json

RTOL = 1e-12
LOGS = 6


def assert_same_cli_json(mine, reference):
    """Every key and value of the command line's JSON, floats to 1e-12 (timings left out)."""
    assert_same_json(mine, reference, rel=RTOL, ignored=lambda key: key.endswith("seconds"))


@pytest.fixture(scope="module")
def fleet_logs(cli, tmp_path_factory):
    """Six 20 s planar 2R logs of the main job's sensors, each with its own seeds."""
    out = tmp_path_factory.mktemp("fleet")
    logs = []
    for k in range(LOGS):
        path = out / f"log{k}.csv"
        status, _, err = cli("simulate", "--quiet", "--robot", ROBOT, "--out", path, "--duration", "20", "--encoder-counts", "65536",
                             "--torque-noise", "0.05,0.01", "--seed", 11 + k, "--noise-seed", 31 + k)
        assert status == 0, err
        logs.append(str(path))
    return logs


def cli_reference(cli_json, logs):
    args = ["identify", "--quiet", "--robot", ROBOT, "--format", "json"]
    for log in logs:
        args += ["--in", log]
    return cli_json(*args)


def test_plan_factor_merge_is_identify_in_a_in_b(cli_json, fleet_logs):
    plan = pickle.loads(pickle.dumps(jacobid.plan(ROBOT, fleet_logs[0], quiet=True)))
    factors = [pickle.loads(pickle.dumps(jacobid.factor(ROBOT, log, plan))) for log in fleet_logs]
    reference = cli_reference(cli_json, fleet_logs)
    assert_same_cli_json(jacobid.merge(factors), reference)
    # Partial merges (solve=False) merge again: with identify's bracketing (the ordered binary tree: pairs, then
    # pairs of pairs) to the same bits, with any other to rounding (the std's HAC terms cancel ~4 digits).
    left, right = jacobid.merge(factors[:4], solve=False), jacobid.merge(factors[4:], solve=False)
    assert_same_cli_json(jacobid.merge([left, right]), reference)
    chain = factors[0]
    for f in factors[1:]:
        chain = jacobid.merge([chain, f], solve=False)
    assert_same_json(jacobid.merge([chain]), reference, rel=1e-8, ignored=lambda key: key.endswith("seconds"))
    # What travels is independent of the log's length: triangles, lagged products, report lines.
    assert len({f.nbytes for f in factors}) == 1 and 0 < factors[0].nbytes < 100_000
    assert right.logs == fleet_logs[4:] and chain.logs == fleet_logs


def test_a_factor_travels_exactly(fleet_logs):
    # What a worker receives (the matrices' non-zero entries and where they are, the plan once per process) merges
    # to the same bits as the factors it was made from.
    plan = jacobid.plan(ROBOT, fleet_logs[0], quiet=True)
    factors = [jacobid.factor(ROBOT, log, plan) for log in fleet_logs[:3]]
    travelled = [pickle.loads(pickle.dumps(f)) for f in factors]
    assert all(t.plan.nbytes == plan.nbytes for t in travelled)
    assert_same_json(jacobid.merge(travelled), jacobid.merge(factors), rel=0, abs=0, ignored=lambda key: key.endswith("seconds"))


def test_the_fleets_tree_brackets_as_identify():
    from jacobid._fleet_tree import OrderedTree

    def level_by_level(items):  # identify's bracketing: adjacent pairs, then adjacent pairs of those, an odd last one carried up
        while len(items) > 1:
            items = [(items[i], items[i + 1]) if i + 1 < len(items) else items[i] for i in range(0, len(items), 2)]
        return items[0] if items else None

    for n in range(34):
        tree = OrderedTree(lambda left, right: (left, right))
        for k in range(n):
            tree.add(k)
        assert tree.result() == level_by_level(list(range(n))), n


def test_merge_refuses_what_identify_would_not_count(fleet_logs):
    plan = jacobid.plan(ROBOT, fleet_logs[0], quiet=True)
    other = jacobid.plan(ROBOT, fleet_logs[0], quiet=True, bandwidth=3)
    a, b = jacobid.factor(ROBOT, fleet_logs[0], plan), jacobid.factor(ROBOT, fleet_logs[1], other)
    with pytest.raises(jacobid.InputError, match=r"factors\[1\] \(.*log1.csv\): made with another plan"):
        jacobid.merge([a, b])
    with pytest.raises(jacobid.InputError, match=r"factors\[1\]: the log .*log0.csv is in an earlier factor too"):
        jacobid.merge([a, a])
    with pytest.raises(jacobid.InputError, match=r"^factors: expected a non-empty list"):
        jacobid.merge([])
    with pytest.raises(jacobid.InputError, match=r"^period: not available in plan"):
        jacobid.plan(ROBOT, fleet_logs[0], period="auto")
    with pytest.raises(jacobid.InputError, match=r"^plan: expected jacobid.plan\(\)'s result, got dict"):
        jacobid.factor(ROBOT, fleet_logs[0], {})


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")
    import jacobid.fleet

    with jacobid.fleet.local_cluster(2) as cluster, distributed.Client(cluster) as c:
        yield c


def _worker_state():
    """What a worker process runs with: the nanny's malloc variable, the profiler, the memory monitor's period."""
    import distributed

    worker = distributed.get_worker()
    return (os.environ.get("MALLOC_TRIM_THRESHOLD_"), "profile" in worker.periodic_callbacks,
            worker.periodic_callbacks["memory_monitor"].callback_time if "memory_monitor" in worker.periodic_callbacks else None)


def test_the_fleets_own_cluster_runs_its_workers_with_the_worker_settings(client):
    import dask
    import jacobid.fleet

    # Dask's defaults, which the settings must change: otherwise this test would pass on any cluster
    assert "MALLOC_TRIM_THRESHOLD_" in dask.config.get("distributed.nanny.pre-spawn-environ")
    assert dask.config.get("distributed.worker.profile.enabled") is True
    states = client.run(_worker_state)
    assert len(states) == 2
    for worker, (malloc_trim, profiler, monitor_ms) in states.items():
        assert malloc_trim is None, worker  # glibc's adaptive mmap threshold left on
        assert not profiler, worker
        assert monitor_ms == 1000, worker
    # the settings were scoped to the cluster's creation: the driver's configuration is Dask's again
    assert "MALLOC_TRIM_THRESHOLD_" in dask.config.get("distributed.nanny.pre-spawn-environ")
    assert set(jacobid.fleet.worker_settings()) >= {"distributed.nanny.pre-spawn-environ", "distributed.worker.profile.enabled"}


def test_fleet_is_identify_in_a_in_b_with_one_identification_per_robot(cli_json, fleet_logs, client):
    import jacobid.fleet

    by_robot = {log: "even" if k % 2 == 0 else "odd" for k, log in enumerate(fleet_logs)}
    out = jacobid.fleet.identify(ROBOT, fleet_logs, client=client, by_robot=by_robot, quiet=True, timeout=120)
    assert_same_cli_json(out["pooled"], cli_reference(cli_json, fleet_logs))
    assert out["failed"] == {} and set(out["factor_bytes"]) == set(fleet_logs)
    with pytest.raises(jacobid.InputError, match=r"^by_robot: no robot id for .*log5.csv; expected every log"):
        jacobid.fleet.identify(ROBOT, fleet_logs, client=client, by_robot={log: "a" for log in fleet_logs[:5]})
    for rid in ("even", "odd"):
        own = [log for log in fleet_logs if by_robot[log] == rid]
        assert out["robots"][rid]["logs"] == own
        # With the fleet's plan (the same filters for every robot), not one of its own.
        expected = jacobid.merge([jacobid.factor(ROBOT, log, out["plan"]) for log in own])
        assert_same_cli_json(out["robots"][rid]["identification"], expected)
        # The same robot twice: no parameter beyond 5 std of the other.
        assert out["robots"][rid]["drifted"] == [], out["robots"][rid]["drifted"]
        assert set(out["robots"][rid]["deviation"]) == set(out["pooled"]["parameter_order"])


def test_a_worker_killed_mid_run_changes_no_result(cli_json, fleet_logs, client):
    import jacobid.fleet

    killed = []

    def kill_the_holder(log, future):
        # The first factor done: the worker that holds it is killed, so that Dask must compute it again (and
        # reschedule whatever ran there); its nanny starts a new worker.
        if killed:
            return
        (address,) = client.who_has([future])[future.key]
        pid = client.run(os.getpid, workers=[address])[address]
        os.kill(pid, signal.SIGKILL)
        killed.append(pid)

    out = jacobid.fleet.identify(ROBOT, fleet_logs, client=client, progress=kill_the_holder, quiet=True, timeout=120)
    assert killed, "progress was never called"
    with pytest.raises(ProcessLookupError):
        os.kill(killed[0], 0)
    assert_same_cli_json(out["pooled"], cli_reference(cli_json, fleet_logs))


def test_a_corrupt_log_is_reported_by_path_and_left_out(cli_json, fleet_logs, client, tmp_path):
    import jacobid.fleet

    corrupt = tmp_path / "corrupt.csv"
    corrupt.write_text("t,q1,q2,tau1,tau2\n0,0,0,0,0\n0.001,0,zero,0,0\n")
    logs = fleet_logs[:3] + [str(corrupt)] + fleet_logs[3:]
    out = jacobid.fleet.identify(ROBOT, logs, client=client, quiet=True, timeout=120)
    assert list(out["failed"]) == [str(corrupt)]
    assert out["failed"][str(corrupt)].startswith(f"{corrupt}:3"), out["failed"]
    assert_same_cli_json(out["pooled"], cli_reference(cli_json, fleet_logs))


def test_montecarlo_on_dask_is_the_commands_table(cli, cli_json, client):
    import jacobid.fleet

    options = ["--runs", "3", "--duration", "8", "--method", "both", "--quiet"]
    mine = jacobid.fleet.montecarlo(None, client, runs=3, duration=8, method="both", quiet=True, timeout=120)
    status, table, err = cli("montecarlo", *options)
    assert status == 0, err
    # The first line gives the wall time and the threads (here: the workers); every other line is the command's.
    assert mine.splitlines()[1:] == table.splitlines()[1:]
    as_json = jacobid.fleet.montecarlo(None, client, runs=3, duration=8, method="both", quiet=True, format="json", runs_per_task=2, timeout=120)
    assert_same_json(as_json, cli_json("montecarlo", *options, "--format", "json"), rel=1e-9,
                     ignored=lambda key: key in ("wall_seconds", "threads"))


def test_dask_worker_with_the_fleets_preload_runs_with_the_worker_settings(tmp_path):
    """docs/fleet.md's command for a worker host: `dask worker ... --preload-nanny jacobid.fleet_settings`."""
    import dask
    import jacobid.fleet
    import shutil
    import subprocess

    distributed = pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")
    dask_cli = shutil.which("dask")
    if dask_cli is None:
        pytest.skip("the dask command (python3-dask) is not installed")
    scheduler_file = tmp_path / "scheduler.json"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(jacobid.__file__).parents[1]), os.environ.get("PYTHONPATH", "")]))
    scheduler = subprocess.Popen([dask_cli, "scheduler", "--port", "0", "--dashboard-address", ":0", "--scheduler-file", str(scheduler_file)],
                                 env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = None
    try:
        worker = subprocess.Popen([dask_cli, "worker", "--scheduler-file", str(scheduler_file), "--nthreads", "1", "--nworkers", "1",
                                   "--dashboard-address", ":0", "--preload-nanny", "jacobid.fleet_settings"],
                                  env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with distributed.Client(scheduler_file=str(scheduler_file), timeout=60) as c:
            c.wait_for_workers(1, timeout=60)
            # functions the worker can import (this test module is not on its path)
            malloc_trim = list(c.run(os.environ.get, "MALLOC_TRIM_THRESHOLD_").values())
            settings = [list(c.run(dask.config.get, key).values()) for key in jacobid.fleet.worker_settings()]
        assert malloc_trim == [None]
        assert settings == [[value] for value in jacobid.fleet.worker_settings().values()]
    finally:
        for process in (worker, scheduler):
            if process is not None:
                process.terminate()
                process.wait(timeout=60)
