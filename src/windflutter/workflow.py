"""``windflutter run``: from a turbine and an analysis config to stored results, plots and report.

The run is a loop over *operating points*: one wind speed with one aerodynamic variant and one
search method.  Each point is handed to an **analyser**, a callable

    ``analyse(point: OperatingPoint, progress=None) -> PointResult``

which finds the flutter and divergence onset over the rotor-speed range, sweeps the rotor speed
for the Campbell diagram and returns the flutter mode.  The workflow owns everything around it:

* planning the points from the config;
* storing each finished point at once (atomic NetCDF, :mod:`windflutter.post.store`);
* recording a failing point (any exception, e.g. no convergence) as ``failed`` with the reason,
  and going on;
* keeping finished points on Ctrl-C or a kill; ``resume=True`` skips them, and the final dataset
  equals that of an uninterrupted run (apart from the wall-clock times);
* progress bars, the combined dataset with units and attributes, the plots and the HTML report.

The built-in analyser comes from :func:`make_analyser` (the stability solver); a user analyser can
be plugged in with ``solver.backend: NAME``, a name registered with
:func:`windflutter.backends.register_backend` or published in the entry-point group
``windflutter.backends``, whose ``factory(turbine, config)`` returns the callable (it may also
have a ``describe() -> dict`` method giving model size and the operating curve; see
``docs/workflow.md``).  The output folder, its record and ``--resume`` are
:mod:`windflutter.post.runfolder`.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import inspect
import shutil
import signal
import sys
import threading
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from windflutter import parallel
from windflutter.config import AnalysisConfig, check_config
from windflutter.errors import InputWarning
from windflutter.exporters import get_exporter
from windflutter.post import runfolder, store
from windflutter.post.animation import write_mode_animation
from windflutter.post.progress import RunProgress
from windflutter.post.rundata import MODEL_SIZE_KEYS, assemble_dataset, check_operating, describe_run  # noqa: F401
from windflutter.post.runfolder import RUN_FILE  # noqa: F401  (re-exported: the run's record)
from windflutter.results import OperatingPoint, PointResult  # noqa: F401  (the per-point types; importable here)
from windflutter.analysers import (  # noqa: F401  (re-exported: the per-point interface)
    Analyser, ProgressCallback, TurbinePointAnalyser, make_analyser, mesh_settings, operating_campbell,
    turbine_options)


# --------------------------------------------------------------------------------------------
# planning and analysers
# --------------------------------------------------------------------------------------------
def plan_points(config: AnalysisConfig) -> list[OperatingPoint]:
    """The run's operating points: for each (aero, method) case, every wind speed."""
    r = config.rotor_speed
    sweep = tuple(config.sweep_rpm())
    pts = []
    for aero, method in config.cases:
        for v in config.wind_speeds:
            pts.append(OperatingPoint(len(pts), float(v), aero, method, r.min_rpm, r.max_rpm,
                                      r.tolerance_rpm, sweep))
    return pts


def _accepts_progress(fn: Callable) -> bool:
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):
        return False
    return "progress" in sig.parameters or any(
        p.kind is inspect.Parameter.VAR_KEYWORD for p in sig.parameters.values())


# --------------------------------------------------------------------------------------------
# the run
# --------------------------------------------------------------------------------------------
@contextlib.contextmanager
def _sigint_deferred():
    """Hold a Ctrl-C (SIGINT) until the block has finished, then raise it.

    Storing a point writes NetCDF files under library locks (xarray's / HDF5's): a
    ``KeyboardInterrupt`` raised inside that region left a lock held, and the interrupt
    handler's own final write then waited on it forever (seen as a rare hang of
    ``tests/workflow/test_kill_resume.py``).  Main thread only; elsewhere a no-op.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught = []
    old = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
    if caught:
        raise KeyboardInterrupt


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C during a run; finished points are stored.  ``done`` / ``total`` / ``outdir``."""

    def __init__(self, done: int, total: int, outdir: Path):
        super().__init__(f"{done} of {total} points stored in {outdir}")
        self.done, self.total, self.outdir = done, total, outdir


def _analyse_one(analyse: Analyser, point: OperatingPoint, prog: RunProgress | None,
                 with_progress: bool) -> PointResult:
    """Run the analyser on one point; any exception (but Ctrl-C) becomes a ``failed`` result.

    ``prog`` (the run's progress display, in-process runs only) receives the fraction of the
    point done when ``with_progress``; ``None`` in worker processes.
    """
    t0 = time.perf_counter()
    try:
        if with_progress and prog is not None:
            res = analyse(point, progress=prog.update_point)
        else:
            res = analyse(point)
        if not isinstance(res, PointResult):
            raise TypeError(f"analyser returned {type(res).__name__}, expected PointResult")
    except KeyboardInterrupt:
        raise
    except Exception as exc:  # a failing point must not stop the run
        msg = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        res = PointResult(status="failed", reason=f"{type(exc).__name__}: {msg}"[:500])
    res.elapsed = time.perf_counter() - t0
    return res


@dataclass
class _PointJob:
    """One operating point, wherever it runs (this process, a local worker, a Dask worker).

    Analyses the point and returns ``(PointResult, analyser.describe())``; the describe dict
    carries the model size learned while analysing, which a worker process cannot leave in the
    caller's analyser object.  With ``animate`` (this process and local workers: same file
    system) it also writes the point's mode animation, a file of its own, and drops the
    DOF-sized flutter vector (it is not stored), so little data travels back.  Dask workers may
    not see ``outdir``: there the caller writes the animation.  ``prog`` is set only for
    in-process (serial) runs.
    """

    analyser: Any
    config: AnalysisConfig
    outdir: Path
    with_progress: bool
    animate: bool = True
    prog: RunProgress | None = None

    def __call__(self, point: OperatingPoint) -> tuple[PointResult, dict[str, Any]]:
        if self.prog is not None:
            self.prog.start_point(point.label)
        res = _analyse_one(self.analyser, point, self.prog, self.with_progress)
        if self.animate:
            _write_animation(self.analyser, point, res, self.config, self.outdir)
            res.flutter_dof_vector = None
        return res, _describe(self.analyser)

    def __getstate__(self):  # the progress display stays in the calling process
        return {**self.__dict__, "prog": None}


def _describe(analyser: Any) -> dict[str, Any]:
    describe = getattr(analyser, "describe", None)
    if not callable(describe):
        return {}
    try:
        return dict(describe() or {})
    except Exception:  # noqa: BLE001 - a description must not cost the point
        return {}


class _Described:
    """The caller's analyser with the ``describe()`` entries reported by the workers added."""

    def __init__(self, analyser: Any, extra: dict[str, Any]):
        self._analyser, self._extra = analyser, extra

    def describe(self) -> dict[str, Any]:
        return {**_describe(self._analyser), **self._extra}


def _task_point_result(task: Any) -> tuple[PointResult, dict[str, Any]]:
    """``(PointResult, describe)`` from a :class:`windflutter.parallel.TaskResult`; a task that
    could not run (worker died, result not transferable) becomes a ``failed`` point."""
    if task.ok:
        return task.value
    res = PointResult(status="failed", reason=(task.error or "worker failed")[:500])
    res.elapsed = float(task.elapsed)
    return res, {}


def run(turbine: Any, config: AnalysisConfig, outdir: str | Path, resume: bool = False,
        progress: bool = True, analyser: Analyser | None = None, stream=None,
        workers: int | None = 1, scheduler: Any = None) -> xr.Dataset:
    """Run the analysis: every operating point, stored as it finishes; then plots and report.

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.turbine.Turbine` (or whatever the analyser needs).
    config : the analysis.
    outdir : output folder (created).  Without ``resume``, stored points of an earlier run in it
        are discarded.
    resume : keep the stored points of an interrupted run with the same config, turbine and
        windflutter version (:mod:`windflutter.post.runfolder`) and compute only the missing
        ones; a stored point file that cannot be read is computed again.
    progress : draw progress bars (``False``: quiet).
    analyser : per-point analyser; default :func:`make_analyser`.
    stream : where progress and warnings go (default stderr).
    workers : local worker processes for the operating points (1, the default here: serial in
        this process, with progress inside each point; ``None``:
        :func:`windflutter.parallel.default_workers`, the usable cores; ``windflutter run``
        defaults to that).  With more than one, the analyser is sent to each worker once
        (``cloudpickle``) and each worker builds its own models.
    scheduler : Dask scheduler address (``"tcp://host:8786"``), ``distributed.Client`` or
        ``LocalCluster``: run the points on that cluster (``workers`` is then ignored); its
        workers need windflutter (and a plug-in analyser's module) installed.

    Every point is stored as soon as it finishes, in completion order, whatever runs it; the
    results equal those of a serial run (each point is a pure function of its input).

    Returns
    -------
    xarray.Dataset
        the combined results (also in ``outdir/results.nc``).

    Raises
    ------
    RunInterrupted
        on Ctrl-C, after storing what was finished (running workers are stopped).
    InputError
        before ``outdir`` is touched: bad ``workers``; ``outdir`` not a writable folder (field
        ``outdir``); ``resume`` of a folder that is not an earlier run of the same config,
        turbine and version (field ``--resume``); an unknown back-end; no Dask scheduler at
        ``scheduler``.
    """

    config = check_config(config)  # a config built in Python is checked like a file
    if scheduler is None:
        workers = parallel.check_workers(workers)
    outdir = runfolder.check_run_folder(outdir, "outdir")
    record = runfolder.run_record(config, turbine, str(getattr(turbine, "name", turbine)))
    if resume:
        runfolder.check_resume(outdir, record)
    check_operating(turbine, config)
    if analyser is None:
        analyser = make_analyser(turbine, config)
    client = own_client = None
    if scheduler is not None:
        client = parallel.connect(scheduler)
        own_client = client if client is not scheduler else None
    try:
        return _run(turbine, config, outdir, resume, progress, analyser, stream, workers, client, record)
    finally:
        if own_client is not None:
            own_client.close()


def _stored_points(outdir: Path, points: list[OperatingPoint], config: AnalysisConfig,
                   stream) -> dict[int, xr.Dataset]:
    """The stored points of an interrupted run that belong to this plan (resume)."""
    store.clean_temporaries(outdir)
    problems: list[str] = []
    stored = store.read_points(outdir, problems)
    planned = {p.index: p for p in points}
    done = {}
    for i, ds in stored.items():
        p = planned.get(i)
        same = (p is not None and float(ds["wind_speed"].values[0]) == p.wind_speed
                and str(ds["aero"].values[0]) == p.aero and str(ds["method"].values[0]) == p.method)
        if same and ds.attrs.get("config_fingerprint", config.fingerprint()) != config.fingerprint():
            problems.append(f"{store.POINTS_DIR}/{store.point_path('.', i).name}: another config's point")
            same = False
        if same:
            done[i] = ds
    for msg in problems:
        print(f"windflutter run: {msg}; computed again", file=stream or sys.stderr)
    return done


def _run(turbine: Any, config: AnalysisConfig, outdir: Path, resume: bool, progress: bool,
         analyser: Any, stream, workers: int | None, client: Any, record: dict[str, Any]) -> xr.Dataset:
    """The body of :func:`run` (``client``: a connected Dask client or ``None``)."""

    outdir.mkdir(parents=True, exist_ok=True)
    points = plan_points(config)
    info = describe_run(turbine, config, analyser)
    if resume:
        done = _stored_points(outdir, points, config, stream)
    else:
        shutil.rmtree(outdir / store.POINTS_DIR, ignore_errors=True)
        (outdir / store.RESULTS_FILE).unlink(missing_ok=True)
        done = {}
    runfolder.write_run_record(outdir, record)

    todo = [p for p in points if p.index not in done]
    in_process = parallel.runs_in_process(len(todo), workers, client)
    if todo and not in_process and hasattr(analyser, "share_campbell_model"):
        analyser.share_campbell_model()  # the workers' copies then share the Campbell's support basis
    job = _PointJob(analyser, config, outdir, _accepts_progress(analyser), animate=client is None)
    reported: dict[str, Any] = {}  # describe() entries from the workers
    prepared: dict[float, Any] = {}  # the Campbell's points the map evaluated (its sweeps' first)
    point_attrs = {"config_fingerprint": config.fingerprint(), "run_fingerprint": record["fingerprint"]}
    with RunProgress(len(points), len(done), quiet=not progress, stream=stream) as prog:
        if in_process:
            job.prog = prog
        elif todo:
            where = (f"the Dask scheduler {getattr(client.scheduler, 'address', '?')}"
                     if client is not None else f"{min(workers, len(todo))} local worker processes")
            prog.log(f"{len(todo)} operating points on {where}")
        tasks = parallel.iter_tasks(job, todo, workers=workers, scheduler=client)
        try:
            with contextlib.closing(tasks):
                for task in tasks:
                    p = todo[task.index]
                    res, desc = _task_point_result(task)
                    if res.operating_system is not None:  # the Campbell's own case: its operating point
                        prepared[p.wind_speed], res.operating_system = res.operating_system, None
                    reported.update(desc)
                    if not in_process:
                        prog.start_point(p.label)
                    if not job.animate:
                        _write_animation(analyser, p, res, config, outdir)
                    ds = store.point_dataset(p, res, point_attrs)
                    with _sigint_deferred():  # the files are written whole, never interrupted
                        store.write_point(outdir, ds)
                        done[p.index] = ds
                        store.atomic_write_netcdf(assemble_dataset(done, config, info, len(points)),
                                                  outdir / store.RESULTS_FILE)
                    msg = None
                    if res.status != "ok":
                        msg = f"[yellow]point {p.label} failed: {res.reason}[/yellow]"
                    prog.finish_point(res.status, msg)
        except KeyboardInterrupt:
            if done:
                store.atomic_write_netcdf(assemble_dataset(done, config, info, len(points)),
                                          outdir / store.RESULTS_FILE)
            raise RunInterrupted(len(done), len(points), outdir) from None

    info = describe_run(turbine, config, _Described(analyser, reported) if reported else analyser)
    ds = assemble_dataset(done, config, info, len(points))
    ds.attrs["finished_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    # the Campbell's shell points on the run's local workers (its beam points stay here)
    camp = operating_campbell(turbine, config, analyser, progress,
                              workers=1 if in_process or client is not None else workers, prepared=prepared)
    if camp is not None:
        store.write_campbell(outdir, camp)
        for k, v in camp.assumptions.items():
            ds.attrs[f"assumption_{k}"] = str(v)
    write_exports(camp, config, outdir)
    store.atomic_write_netcdf(ds, outdir / store.RESULTS_FILE)
    write_outputs(ds, config, outdir, campbell=camp)
    return ds


def _write_animation(analyser: Any, point: OperatingPoint, res: PointResult, config: AnalysisConfig,
                     outdir: Path) -> Path | None:
    """``OUTDIR/animations/flutter_pNNNN.pvd``: one cycle of the flutter mode (before the point
    is stored, so a resumed run has every animation of its stored points)."""
    if not config.output.animations or res.flutter_dof_vector is None or res.status != "ok":
        return None
    fe_model = getattr(analyser, "fe_model", None)
    if not callable(fe_model):
        return None
    try:
        fe = fe_model(point)
        f = res.flutter_frequency_hz
        return write_mode_animation(fe, res.flutter_dof_vector, outdir / "animations" / f"flutter_p{point.index:04d}.pvd",
                                    n_frames=config.output.animation_frames, name=f"flutter_p{point.index:04d}",
                                    frequency_hz=float(f) if np.isfinite(f) and f > 0 else None)
    except Exception as exc:  # a picture must not cost the point
        res.info["animation_error"] = f"{type(exc).__name__}: {exc}"[:300]
        return None


def write_exports(campbell, config: AnalysisConfig, outdir: str | Path) -> dict[str, Path]:
    """The operating-point Campbell in each format of ``output.exports`` (:mod:`windflutter.exporters`),
    to ``OUTDIR/campbell<suffix>`` (the format's first suffix; a plug-in without one: ``campbell.<name>``).
    The CF NetCDF ``campbell.nc`` is the run's own store and is written whether listed or not."""
    written: dict[str, Path] = {}
    if not config.output.exports:
        return written
    if campbell is None:
        warnings.warn("output.exports: this run has no operating-point Campbell (it needs campbell.enabled, method "
                      "p, the built-in back-end and an operating curve): nothing exported", InputWarning, stacklevel=2)
        return written
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    for name in config.output.exports:
        exporter = get_exporter(name, "output.exports")
        path = outdir / f"campbell{exporter.suffixes[0] if exporter.suffixes else '.' + exporter.name}"
        if path.name == store.CAMPBELL_FILE:
            written[name] = path
            continue
        written[name] = exporter.write(campbell, path, field="output.exports", dpi=config.output.dpi)
    return written


def write_outputs(ds: xr.Dataset, config: AnalysisConfig, outdir: str | Path, campbell=None) -> dict[str, Path]:
    """Figures and report of a finished run (``outdir/figures/*``, ``outdir/report.html``), with the
    operating-point Campbell (a :class:`~windflutter.system.campbell.CampbellResult`) when given."""
    outdir = Path(outdir)
    written: dict[str, Path] = {}
    if not (config.output.plots or config.output.report):
        return written
    from windflutter.post import plots, report  # noqa: PLC0415  (matplotlib is slow to import)

    figs = plots.all_figures(ds, operating=campbell)
    try:
        png = plots.render_png(figs, config.output.dpi)
        if config.output.plots:
            written.update(plots.save_figures(figs, outdir / "figures", config.output.formats,
                                              config.output.dpi, png=png))
        if config.output.report:
            html = report.build_report(ds, figs, dpi=config.output.dpi, png=png, campbell=campbell)
            written["report"] = store.atomic_write_text(html, outdir / "report.html")
    finally:
        plots.close_figures(figs)
    return written
