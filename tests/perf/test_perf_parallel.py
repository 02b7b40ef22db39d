"""Parallel sweeps: serial, 2 local workers and a Dask LocalCluster give identical, ordered results;
a failing task is reported, not raised."""

import os
import threading

import numpy as np
import pytest

from windflutter.errors import InputError
from windflutter.parallel import TaskResult, iter_tasks, run_tasks
from testproblems import demo_point

TASKS = [{"speed": s, "n_around": 4, "n_along": 3, "n_modes": 8} for s in (0.5, 0.0, 1.5, 1.0, 2.0)]


def _values(results):
    return [r.value["eigenvalues"] for r in results]


@pytest.fixture(scope="module")
def serial():
    return run_tasks(demo_point, TASKS, workers=1)


@pytest.fixture
def cluster(dask_cluster):
    return dask_cluster  # tests/conftest.py


def test_serial_results_in_order(serial):
    assert [r.index for r in serial] == list(range(len(TASKS)))
    assert all(r.ok and r.worker == "local" for r in serial)
    assert [r.value["speed"] for r in serial] == [t["speed"] for t in TASKS]


def test_two_local_workers_identical_to_serial(serial):
    seen = []
    res = run_tasks(demo_point, TASKS, workers=2, progress=lambda d, n, r: seen.append((d, n, r.index)))
    assert [r.index for r in res] == list(range(len(TASKS)))
    assert all(r.ok for r in res)
    # bit-for-bit identical: same code, same BLAS, each task independent of the others
    for a, b in zip(_values(serial), _values(res)):
        assert np.array_equal(a, b)
    # ran in other processes, progress called once per task in this process
    assert all(r.value["pid"] != os.getpid() for r in res)
    assert [d for d, _, _ in seen] == list(range(1, len(TASKS) + 1))
    assert sorted(i for _, _, i in seen) == list(range(len(TASKS)))


def test_failed_task_is_reported_not_raised():
    tasks = [TASKS[0], {"speed": -1.0}, TASKS[1]]
    for workers in (1, 2):
        res = run_tasks(demo_point, tasks, workers=workers)
        assert [r.ok for r in res] == [True, False, True]
        assert res[1].error.startswith("InputError: speed = -1.0")
        assert "Traceback" in res[1].traceback
        assert res[1].value is None


def test_closure_and_unpicklable_result():
    offset = 3.0
    res = run_tasks(lambda x: x * x + offset, [1.0, 2.0, 3.0], workers=2)
    assert [r.value for r in res] == [4.0, 7.0, 12.0]
    # a result that cannot be sent back from a worker fails that task only
    res = run_tasks(lambda x: threading.Lock() if x == 2 else x, [1, 2, 3], workers=2)
    assert [r.ok for r in res] == [True, False, True]
    assert "result cannot be sent back" in res[1].error


def test_dask_local_cluster_identical_to_serial(serial, cluster):
    res = run_tasks(demo_point, TASKS, scheduler=cluster)
    assert [r.index for r in res] == list(range(len(TASKS)))
    assert all(r.ok for r in res)
    for a, b in zip(_values(serial), _values(res)):
        assert np.array_equal(a, b)
    assert all(r.worker.startswith("tcp://") for r in res)
    # by address as well (what `--scheduler ADDRESS` passes), with a failing task
    res = run_tasks(demo_point, [TASKS[0], {"speed": -2.0}], scheduler=cluster.scheduler_address)
    assert res[0].ok and not res[1].ok and res[1].error.startswith("InputError")


def test_iter_tasks_yields_every_index_once():
    got = sorted(r.index for r in iter_tasks(demo_point, TASKS[:3], workers=2))
    assert got == [0, 1, 2]


def test_bad_arguments():
    with pytest.raises(InputError, match="workers"):
        run_tasks(demo_point, TASKS, workers=0)
    with pytest.raises(InputError, match="scheduler"):
        run_tasks(demo_point, TASKS, scheduler="tcp://127.0.0.1:1", connect_timeout=1)
    assert run_tasks(demo_point, [], workers=2) == []
    assert isinstance(run_tasks(abs, [-1], workers=2)[0], TaskResult)


def _die_on_two(x):
    if x == 2:
        os._exit(3)  # simulates a worker killed by a segfault / the OOM killer
    return x


def test_dead_worker_fails_tasks_without_hanging():
    res = run_tasks(_die_on_two, [1, 2, 3, 4], workers=2)
    assert len(res) == 4 and [r.index for r in res] == [0, 1, 2, 3]
    assert not res[1].ok and "BrokenProcessPool" in res[1].error
    assert all(r.ok or "BrokenProcessPool" in r.error for r in res)
