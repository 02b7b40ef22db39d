"""Run independent tasks (operating points, design variants) serially, on local cores or on Dask.

A stability map is a set of independent operating points; each one is an eigen-solve sweep
that takes seconds to minutes. :func:`run_tasks` runs ``fn(task)`` for every task

* in this process (``workers=1``),
* on the local cores with a :class:`concurrent.futures.ProcessPoolExecutor` (default: one worker
  per core), or
* on a Dask cluster (``scheduler="tcp://host:8786"``, a :class:`distributed.Client` or a
  :class:`distributed.LocalCluster`),

and returns one :class:`TaskResult` per task **in input order**, whatever order they finished
in. The result of a task does not depend on where it ran (each task is a pure function of its
input; nothing is shared between tasks), so serial, local-parallel and Dask runs give identical
results -- ``tests/perf/test_perf_parallel.py`` checks this bit for bit.

An exception inside a task does not stop the run: that task comes back with ``ok=False`` and
the error text and traceback. A local worker process that dies (segfault, out of memory)
breaks the pool: the tasks not finished by then come back failed (``BrokenProcessPool``) and the
call returns; on Dask the scheduler retries them on other workers first.

The function and tasks are serialised with ``cloudpickle`` (installed with dask), so closures
and lambdas work; the function is sent to each local worker once, not once per task, so it may
carry a large model. :func:`iter_tasks` yields results as they complete, for callers that store
each point as soon as it is done (``windflutter run``).
"""

from __future__ import annotations

import os
import pickle
import time
import traceback
import warnings
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import Any, Callable, Iterable, Iterator, Sequence

from windflutter.errors import InputError, one_line
from windflutter.heap import keep_freed_memory
from windflutter.threads import blas_limit, set_process_threads

try:  # cloudpickle ships with dask; fall back to pickle (module-level functions only)
    import cloudpickle as _cp
except Exception:  # pragma: no cover - depends on the environment
    _cp = pickle

__all__ = ["TaskResult", "run_tasks", "iter_tasks", "default_workers", "check_workers", "connect",
           "check_scheduler_address", "runs_in_process", "WorkerPool"]

ProgressCallback = Callable[[int, int, "TaskResult"], None]


@dataclass
class TaskResult:
    """Outcome of one task.

    Attributes
    ----------
    index
        Position of the task in the input sequence.
    ok
        ``True`` if ``fn(task)`` returned; ``False`` if it raised (or its worker died).
    value
        The return value (``None`` when failed).
    error
        ``"ExceptionType: message"`` when failed, else ``""``.
    traceback
        Formatted traceback of the failure (from the worker), else ``""``.
    elapsed
        Wall time of the task inside the worker (s).
    worker
        Where it ran: ``"local"``, ``"pid:<n>"`` or the Dask worker address.
    """

    index: int
    ok: bool
    value: Any = None
    error: str = ""
    traceback: str = ""
    elapsed: float = 0.0
    worker: str = ""


def default_workers() -> int:
    """Number of local worker processes used by default: the usable cores (at least 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def check_workers(workers: Any, field_name: str = "workers") -> int:
    """``workers`` as a positive int (``None``: :func:`default_workers`); else ``InputError``."""
    if workers is None:
        return default_workers()
    if isinstance(workers, bool) or not isinstance(workers, (int,)) or workers < 1:
        raise InputError(field_name, workers, "a positive integer number of worker processes "
                         "(1 = serial, in this process)")
    return int(workers)


def runs_in_process(n_tasks: int, workers: int | None = None, scheduler: Any = None) -> bool:
    """True when :func:`iter_tasks` would run the tasks serially in this process."""
    return scheduler is None and (check_workers(workers) == 1 or n_tasks <= 1)


_SCHEMES = ("tcp", "tls", "ws", "wss", "inproc", "ucx")
_EXAMPLE = "the address of a running Dask scheduler, e.g. tcp://host:8786"


def check_scheduler_address(address: Any, field_name: str = "scheduler", probe_timeout: float = 3.0) -> str:
    """A Dask scheduler address that can be connected to, checked without making a Client.

    A malformed address (``tcp://host:abc``, an unknown scheme, no host, a port outside 1-65535)
    is refused at once; for ``tcp``/``tls``/``ws`` addresses a plain socket connection is tried
    first (``probe_timeout`` s), so nothing is left behind -- a half-made ``distributed.Client``
    printed a traceback from its ``__del__`` twenty seconds after the error.

    Raises
    ------
    InputError
        naming ``field_name``.
    """
    if not isinstance(address, str) or not address.strip():
        raise InputError(field_name, address, _EXAMPLE)
    try:
        from distributed.comm.addressing import parse_address, parse_host_port
    except ImportError:  # pragma: no cover - depends on the environment
        raise InputError(field_name, address, "dask.distributed installed (pip install windflutter[dist])") from None
    addr = address.strip()
    try:
        scheme, loc = parse_address(addr, strict=False)
        host, port = parse_host_port(loc, default_port=8786) if scheme in ("tcp", "tls", "ws", "wss") else (loc, 1)
    except (ValueError, TypeError) as exc:
        raise InputError(field_name, address, f"{_EXAMPLE} ({exc})") from None
    if scheme not in _SCHEMES or not host or not 0 < int(port) < 65536:
        raise InputError(field_name, address, f"{_EXAMPLE} (scheme one of {', '.join(_SCHEMES)}, a host, "
                         "a port in 1-65535)")
    if scheme in ("tcp", "tls", "ws", "wss"):
        import socket

        try:
            socket.create_connection((host, int(port)), timeout=probe_timeout).close()
        except OSError as exc:
            raise InputError(field_name, address, f"{_EXAMPLE} (nothing answers at {host}:{port}: "
                             f"{exc.strerror or type(exc).__name__})") from None
    return addr


def connect(scheduler: Any, timeout: float = 10.0):
    """A ``distributed.Client`` for ``scheduler`` (an address, a ``LocalCluster`` or a Client).

    Raises
    ------
    InputError
        ``dask.distributed`` is not installed, or no scheduler answers at the address within
        ``timeout`` seconds (field ``scheduler``).
    """
    try:
        from distributed import Client
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise InputError("scheduler", scheduler,
                         "dask.distributed installed (pip install windflutter[dist])") from exc
    if isinstance(scheduler, Client):
        return scheduler
    if hasattr(scheduler, "scheduler_address") and not hasattr(scheduler, "submit"):
        scheduler = scheduler.scheduler_address  # a LocalCluster / SpecCluster object
    scheduler = check_scheduler_address(scheduler, "scheduler")
    try:
        return Client(scheduler, timeout=timeout, set_as_default=False)
    except Exception as exc:  # noqa: BLE001 - unreachable address, bad string
        raise InputError("scheduler", str(scheduler),
                         f"the address of a running Dask scheduler, e.g. tcp://host:8786 "
                         f"({type(exc).__name__}: {str(exc).strip().splitlines()[0] if str(exc).strip() else ''})"
                         ) from exc


def _execute(fn: Callable, index: int, task: Any, where: str) -> TaskResult:
    t0 = time.perf_counter()
    try:
        value = fn(task)
    except Exception as exc:  # noqa: BLE001 - every task failure is reported, not raised
        msg = str(exc).strip()
        return TaskResult(index, False, None, f"{type(exc).__name__}: {msg}" if msg else type(exc).__name__,
                          traceback.format_exc(), time.perf_counter() - t0, where)
    return TaskResult(index, True, value, "", "", time.perf_counter() - t0, where)


# --- local process pool -------------------------------------------------------------------
# The task function lives in a per-worker-process slot, set once by the pool initializer, so a
# large callable (e.g. one holding an assembled FE model) is transferred once per worker.
_WORKER_FN: Callable | None = None


def _die_with_parent() -> None:
    """Linux: have the kernel SIGKILL this worker when the parent process dies (e.g. a killed
    ``windflutter run``), so no orphan keeps computing or writing files. Best effort."""
    try:
        import ctypes
        import signal

        libc = ctypes.CDLL(None, use_errno=True)
        PR_SET_PDEATHSIG = 1
        libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
    except Exception:  # noqa: BLE001 - not Linux / no libc: workers end with the pool instead
        pass


def _init_worker(fn_bytes: bytes, blas_threads: int | None) -> None:
    global _WORKER_FN
    _die_with_parent()
    # for the life of the worker process, also for BLAS libraries it loads later (windflutter.threads)
    set_process_threads(blas_threads)
    keep_freed_memory()  # the arrays of each point reused, not mapped again (windflutter.heap)
    worker_warning_display()
    _WORKER_FN = _cp.loads(fn_bytes)


def worker_warning_display() -> None:
    """A worker process's warnings reach the user's terminal in one line, like the command's own;
    a warning of a kind at a wind speed (a ValidityWarning with ``kind`` and ``wind_speed``) is not
    printed: it returns with the point's notes and the command prints one line per kind
    (:mod:`windflutter.cli.warn`)."""
    warnings.formatwarning = _one_line_warning
    shown = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        if getattr(message, "kind", None) and getattr(message, "wind_speed", None) is not None:
            return
        shown(message, category, filename, lineno, file, line)

    warnings.showwarning = show


def _one_line_warning(message, category, filename, lineno, line=None) -> str:  # noqa: ARG001
    return f"windflutter worker: warning: {one_line(message)}\n"


def _run_in_worker(index: int, task_bytes: bytes) -> bytes:
    where = f"pid:{os.getpid()}"
    try:
        task = _cp.loads(task_bytes)
    except Exception as exc:  # noqa: BLE001
        res = TaskResult(index, False, None, f"{type(exc).__name__}: cannot unpickle task: {exc}",
                         traceback.format_exc(), 0.0, where)
    else:
        res = _execute(_WORKER_FN, index, task, where)
    try:
        return _cp.dumps(res)
    except Exception as exc:  # noqa: BLE001 - an unpicklable return value fails that task only
        return _cp.dumps(TaskResult(index, False, None,
                                    f"{type(exc).__name__}: result cannot be sent back: {exc}",
                                    traceback.format_exc(), res.elapsed, where))


def _dumps_task(index: int, task: Any) -> tuple[bytes | None, TaskResult | None]:
    try:
        return _cp.dumps(task), None
    except Exception as exc:  # noqa: BLE001
        return None, TaskResult(index, False, None, f"{type(exc).__name__}: cannot pickle task: {exc}",
                                traceback.format_exc(), 0.0, "local")


def _iter_pool(fn, tasks, workers, start_method, blas_threads) -> Iterator[TaskResult]:
    # on Ctrl-C / an abandoned generator the pool does not wait for the running tasks to end
    with WorkerPool(fn, max(1, min(workers, len(tasks))), blas_threads=blas_threads,
                    start_method=start_method) as pool:
        pending = {pool.submit(t) for t in tasks}
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                yield pool.result(fut)


def _terminate_workers(ex: ProcessPoolExecutor) -> None:
    """Stop the pool's worker processes now (interrupted run: their tasks are abandoned)."""
    term = getattr(ex, "terminate_workers", None)  # Python >= 3.14
    if callable(term):
        term()
        return
    for proc in list((getattr(ex, "_processes", None) or {}).values()):
        try:
            proc.terminate()
        except Exception:  # noqa: BLE001 - already gone
            pass


class WorkerPool:
    """A local process pool fed one task at a time, for callers whose next tasks depend on the
    results so far (the Campbell's refined steps, :func:`windflutter.system.campbell.campbell`).

    ``fn`` is sent to each worker once (as :func:`run_tasks` does), the workers run under the
    BLAS-thread limit ``blas_threads`` and die with this process; :meth:`submit` returns a future
    whose :meth:`result` is a :class:`TaskResult`.  Used as a context manager: leaving the block by
    an exception (Ctrl-C) cancels the queued tasks and terminates the running ones.
    """

    def __init__(self, fn: Callable[[Any], Any], workers: int, *, blas_threads: int | None = 1,
                 start_method: str | None = None):
        import multiprocessing as mp

        try:
            fn_bytes = _cp.dumps(fn)
        except Exception as exc:
            raise InputError("fn", repr(fn), f"a picklable callable ({type(exc).__name__}: {exc})") from exc
        ctx = mp.get_context(start_method) if start_method else None
        self.workers = check_workers(workers)
        self._ex = ProcessPoolExecutor(max_workers=self.workers, mp_context=ctx, initializer=_init_worker,
                                       initargs=(fn_bytes, blas_threads))
        self._index = 0
        self._task_of: dict = {}

    def submit(self, task: Any):
        """Queue ``fn(task)`` (the pool's next task index); :meth:`result` of the returned future is
        its :class:`TaskResult` (a task that cannot be pickled: a failed one, at once)."""
        from concurrent.futures import Future

        i, self._index = self._index, self._index + 1
        payload, failed = _dumps_task(i, task)
        if failed is not None:
            fut: Future = Future()
            fut.set_result(_cp.dumps(failed))
        else:
            fut = self._ex.submit(_run_in_worker, i, payload)
        self._task_of[fut] = i
        return fut

    def result(self, future) -> TaskResult:
        """The :class:`TaskResult` of a future from :meth:`submit` (waits for it); a worker that died
        fails its task."""
        i = self._task_of.pop(future)
        try:
            return _cp.loads(future.result())
        except BrokenProcessPool as exc:
            return TaskResult(i, False, None, f"BrokenProcessPool: worker process died ({exc})", "", 0.0, "local")
        except Exception as exc:  # noqa: BLE001
            return TaskResult(i, False, None, f"{type(exc).__name__}: {exc}", traceback.format_exc(), 0.0, "local")

    def __enter__(self) -> "WorkerPool":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self._ex.shutdown(wait=exc_type is None, cancel_futures=True)
        if exc_type is not None:
            _terminate_workers(self._ex)


# --- Dask ---------------------------------------------------------------------------------
def _dask_execute(fn: Callable, index: int, task: Any, blas_threads: int | None) -> TaskResult:
    try:
        from distributed import get_worker

        where = get_worker().address
    except Exception:  # noqa: BLE001
        where = "dask"
    with blas_limit(blas_threads):
        return _execute(fn, index, task, where)


def _iter_dask(fn, tasks, scheduler, connect_timeout: float, blas_threads) -> Iterator[TaskResult]:
    from distributed import Client, as_completed

    own = not isinstance(scheduler, Client)
    client = connect(scheduler, connect_timeout)
    futs = []
    finished = False
    try:
        fn_future = client.scatter(fn, broadcast=True, hash=False) if len(tasks) > 1 else fn
        futs = [client.submit(_dask_execute, fn_future, i, t, blas_threads, pure=False) for i, t in enumerate(tasks)]
        index_of = {f.key: i for i, f in enumerate(futs)}
        for fut in as_completed(futs, loop=client.loop):
            i = index_of[fut.key]
            try:
                yield fut.result()
            except Exception as exc:  # noqa: BLE001 - e.g. KilledWorker
                yield TaskResult(i, False, None, f"{type(exc).__name__}: {exc}",
                                 traceback.format_exc(), 0.0, "dask")
            fut.release()
        finished = True
    finally:
        if not finished and futs:
            try:  # interrupted: do not leave the tasks running on the cluster
                client.cancel(futs)
            except Exception:  # noqa: BLE001
                pass
        if own:
            client.close()


# --- public API ---------------------------------------------------------------------------
def iter_tasks(
    fn: Callable[[Any], Any],
    tasks: Sequence[Any] | Iterable[Any],
    *,
    workers: int | None = None,
    scheduler: Any = None,
    start_method: str | None = None,
    connect_timeout: float = 10.0,
    blas_threads: int | None = 1,
) -> Iterator[TaskResult]:
    """Run ``fn(task)`` for every task; yield :class:`TaskResult` objects as they complete.

    Same parameters as :func:`run_tasks`; the order is completion order (use ``.index``).
    """
    tasks = list(tasks)
    if scheduler is not None:
        yield from _iter_dask(fn, tasks, scheduler, connect_timeout, blas_threads)
        return
    workers = check_workers(workers)
    if workers == 1 or len(tasks) <= 1:
        for i, t in enumerate(tasks):
            with blas_limit(blas_threads):  # same BLAS threading as the workers: same rounding
                res = _execute(fn, i, t, "local")
            yield res
        return
    yield from _iter_pool(fn, tasks, workers, start_method, blas_threads)


def run_tasks(
    fn: Callable[[Any], Any],
    tasks: Sequence[Any] | Iterable[Any],
    *,
    workers: int | None = None,
    scheduler: Any = None,
    progress: ProgressCallback | None = None,
    start_method: str | None = None,
    connect_timeout: float = 10.0,
    blas_threads: int | None = 1,
) -> list[TaskResult]:
    """Run ``fn(task)`` for every task and return the results in input order.

    Parameters
    ----------
    fn
        The task function; any callable that ``cloudpickle`` can serialise (closures and lambdas
        included). It should be a pure function of its argument.
    tasks
        The task arguments (each serialisable), e.g. operating points.
    workers
        Local worker processes; default: the number of usable cores; ``1`` runs serially in this
        process (no pickling). Ignored when ``scheduler`` is given.
    scheduler
        Dask scheduler address (``"tcp://host:8786"``), a ``distributed.Client`` or a
        ``distributed.LocalCluster``; the workers must have windflutter installed.
    progress
        Called in this process as ``progress(n_done, n_total, result)`` after each task.
    start_method
        ``multiprocessing`` start method for the local pool (``"fork"``, ``"forkserver"``,
        ``"spawn"``); default: the platform's.
    connect_timeout
        Seconds to wait for the Dask scheduler at ``scheduler`` (an address).
    blas_threads
        BLAS threads per local worker process / per Dask task (``None``: library default).
        1 avoids oversubscribing the cores (several workers x multi-threaded OpenBLAS), which
        was measured to slow sparse factorizations by 30x or more.

    Returns
    -------
    list of TaskResult
        ``results[i]`` belongs to ``tasks[i]``; failed tasks have ``ok=False``.
    """
    tasks = list(tasks)
    out: list[TaskResult | None] = [None] * len(tasks)
    n_done = 0
    for res in iter_tasks(fn, tasks, workers=workers, scheduler=scheduler, start_method=start_method,
                          connect_timeout=connect_timeout, blas_threads=blas_threads):
        out[res.index] = res
        n_done += 1
        if progress is not None:
            progress(n_done, len(tasks), res)
    return out  # type: ignore[return-value]
