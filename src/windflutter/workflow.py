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
import dataclasses
import datetime as _dt
import inspect
import math
import shutil
import signal
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import xarray as xr

from windflutter.config import AnalysisConfig
from windflutter.errors import InputError, ModelError
from windflutter.post import runfolder, store
from windflutter.post.progress import RunProgress
from windflutter.post.rundata import MODEL_SIZE_KEYS, assemble_dataset, check_operating, describe_run  # noqa: F401
from windflutter.post.runfolder import RUN_FILE  # noqa: F401  (re-exported: the run's record)
from windflutter.results import OperatingPoint, PointResult  # noqa: F401  (the per-point types; importable here)
from windflutter.units import RPM


# --------------------------------------------------------------------------------------------
# the per-point interface
# --------------------------------------------------------------------------------------------
ProgressCallback = Callable[..., None]


class Analyser(Protocol):
    """``analyse(point, progress=None) -> PointResult``; ``progress(fraction, text=None)``."""

    def __call__(self, point: OperatingPoint, progress: ProgressCallback | None = None) -> PointResult: ...


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


def make_analyser(turbine: Any, config: AnalysisConfig) -> Analyser:
    """The analyser of ``config.solver.backend``.

    ``windflutter`` gives the built-in stability solver (:func:`_builtin_analyser`); any other
    name is a plug-in of :mod:`windflutter.backends` (registered in this process or in the
    entry-point group ``windflutter.backends``) and gives ``factory(turbine, config)``.
    """
    from windflutter.backends import BUILTIN, backend_factory  # noqa: PLC0415

    backend = config.solver.backend
    if backend == BUILTIN:
        return _builtin_analyser(turbine, config)
    return backend_factory(backend)(turbine, config)


def _builtin_analyser(turbine: Any, config: AnalysisConfig) -> Analyser:
    """The built-in turbine stability solver (:mod:`windflutter.stability.turbine`) behind the
    per-point interface, with the flutter mode shape and aero-work diagnostic added."""
    try:
        from windflutter.stability import turbine as _st  # noqa: PLC0415
    except ImportError as exc:
        raise ModelError(f"the built-in turbine stability solver is not available ({exc}); use "
                         "a plug-in solver.backend (windflutter.backends) for your own analyser") from None
    if config.model.type not in ("beam", "shell"):
        raise InputError("model.type", config.model.type, "'beam' or 'shell' for the built-in turbine solver")
    return TurbinePointAnalyser(turbine, config, _st)


def mesh_settings(config: AnalysisConfig) -> dict[str, Any]:
    """Mesh-setting overrides of ``config`` (:func:`windflutter.stability.build.mesh_settings`)."""
    from windflutter.stability.build import mesh_settings as _mesh  # noqa: PLC0415

    return _mesh(config)


def turbine_options(config: AnalysisConfig, aero: str, method: str, module: Any = None):
    """The seed's solver options of one ``(aero, method)`` case (methods pk, thesis), with the mesh
    (:func:`windflutter.stability.build.turbine_options`; ``module`` only for tests that substitute
    the solver module)."""
    if module is None:
        from windflutter.stability.build import turbine_options as _opts  # noqa: PLC0415

        return _opts(config, aero, method)
    opts = module.options_from_config(config, aero, method)
    return dataclasses.replace(opts, mesh={**opts.mesh, **mesh_settings(config)})


class TurbinePointAnalyser:
    """Adapter: the solver of each (aero, method) case (:func:`windflutter.stability.build.
    stability_analysis`) -> ``analyse(point)``; one solver per case, so models are built once per
    blade pitch and reused across wind speeds.
    """

    def __init__(self, turbine: Any, config: AnalysisConfig, module: Any = None):
        self.turbine = turbine
        self.config = config
        self._cases: dict[tuple[str, str], Any] = {}
        self._size: dict[str, Any] = {}
        # validate the options now, so a bad combination fails before the first point
        from windflutter.stability.build import operational_options  # noqa: PLC0415

        for aero, method in config.cases:
            if method == "p":
                operational_options(config, aero)
            else:
                turbine_options(config, aero, method, module)

    def _stability(self, aero: str, method: str):
        key = (aero, method)
        if key not in self._cases:
            from windflutter.stability.build import stability_analysis  # noqa: PLC0415

            self._cases[key] = stability_analysis(self.turbine, self.config, aero, method)
        return self._cases[key]

    def fe_model(self, point: OperatingPoint):
        """The FE model of ``point`` (its blade pitch), for the mode animation (seed's methods)."""
        ts = self._stability(point.aero, point.method)
        return ts.model(ts.pitch_at(point.wind_speed))[0] if hasattr(ts, "model") and callable(ts.model) else None

    def describe(self) -> dict[str, Any]:
        info: dict[str, Any] = {"model_type": self.config.model.type,
                                "mesh_density": self.config.model.mesh_density}
        info.update(self._size)
        return info

    def _model_size(self, ts, pitch: float) -> dict[str, int]:
        if hasattr(ts, "model") and callable(ts.model):
            fe, sections, am = ts.model(pitch)
            return {"n_nodes": int(len(fe.nodes)), "n_dof": int(6 * len(fe.nodes)),
                    "n_aero_sections": int(sections.n_sections), "n_reduced_dof": int(am.size)}
        rb = ts.model.blade(pitch)
        n_b = int(ts.model.n_blades)
        return {"n_nodes": int(rb.fe.n_nodes) * n_b, "n_dof": int(rb.fe.n_dof) * n_b,
                "n_aero_sections": int(rb.sections.n_sections) * n_b}

    def __call__(self, point: OperatingPoint, progress: ProgressCallback | None = None) -> PointResult:
        ts = self._stability(point.aero, point.method)
        if progress is not None:
            progress(0.02, f"{point.label}: model and search")
        grid = None if point.method == "p" else np.asarray(point.sweep_rpm, float)
        s = ts.analyse_operating_point(point.wind_speed, rpm_grid=grid)
        size = self._model_size(ts, ts.pitch_at(point.wind_speed))
        if not self._size:
            self._size = {k: v for k, v in size.items() if k != "n_reduced_dof"}
        nan = float("nan")
        res = PointResult(
            flutter_rpm=nan if s.flutter_rpm is None else float(s.flutter_rpm),
            flutter_frequency_hz=nan if s.flutter_frequency_hz is None else float(s.flutter_frequency_hz),
            flutter_mode=s.flutter_mode or "",
            divergence_rpm=nan if s.divergence_rpm is None else float(s.divergence_rpm),
            sweep_rpm=np.asarray(s.sweep_rpm, float), frequency_hz=np.asarray(s.frequency_hz, float),
            damping_ratio=np.asarray(s.damping_ratio, float), mode_labels=list(s.mode_labels),
            # the model size goes with each point (the reduced size may depend on its pitch), so
            # the run's attributes do not depend on which points this process computed
            info={"pitch_deg": float(s.pitch_deg), **size})
        on = s.onset
        if self.config.output.mode_shapes and on.flutter_vector is not None and s.flutter_rpm is not None:
            if progress is not None:
                progress(0.95, f"{point.label}: flutter mode")
            from windflutter.post.aerowork import flutter_mode_diagnostics  # noqa: PLC0415

            _, sections, am = ts.model(ts.pitch_at(point.wind_speed))
            sys_on = am.at(point.wind_speed, float(s.flutter_rpm) * RPM)
            u = sys_on.expand(on.flutter_vector)
            omega = float(on.flutter_frequency) if on.flutter_frequency else 2 * math.pi * res.flutter_frequency_hz
            d = flutter_mode_diagnostics(u, sys_on.strip, sections, omega)
            res.station_radius, res.flutter_shape, res.aero_work = d.radius, d.shape, d.work
            res.info["aero_work_rotor_total_J"] = d.work_total
            res.flutter_dof_vector = u
        return res


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
    from windflutter import parallel  # noqa: PLC0415
    from windflutter.config import check_config  # noqa: PLC0415

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
    from windflutter import parallel  # noqa: PLC0415

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
    job = _PointJob(analyser, config, outdir, _accepts_progress(analyser), animate=client is None)
    reported: dict[str, Any] = {}  # describe() entries from the workers
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
    camp = operating_campbell(turbine, config, analyser, progress)
    if camp is not None:
        store.write_campbell(outdir, camp)
        for k, v in camp.assumptions.items():
            ds.attrs[f"assumption_{k}"] = str(v)
    store.atomic_write_netcdf(ds, outdir / store.RESULTS_FILE)
    write_outputs(ds, config, outdir, campbell=camp)
    return ds


def operating_campbell(turbine: Any, config: AnalysisConfig, analyser: Any = None, progress: bool = False):
    """The operating-point Campbell of a run (``campbell.enabled`` with method p; None otherwise):
    every mode along the operating curve at the run's wind speeds, with the model of the run's
    first p case (its parts reused when the built-in analyser built them in this process)."""
    if not (config.campbell.enabled and "p" in config.method and config.solver.backend == "windflutter"):
        return None
    if getattr(turbine, "operating_curve", None) is None:
        return None
    from windflutter.stability.build import operational_options  # noqa: PLC0415
    from windflutter.stability.operational import torsion_frequency  # noqa: PLC0415
    from windflutter.system.campbell import campbell  # noqa: PLC0415
    from windflutter.system.operational import OperationalModel  # noqa: PLC0415

    aero = next(a for a, m in config.cases if m == "p")
    case = getattr(analyser, "_cases", {}).get((aero, "p")) if analyser is not None else None
    model = case.model if case is not None else OperationalModel(turbine, operational_options(config, aero))
    oc = turbine.operating_curve
    winds = [v for v in config.wind_speeds if oc.wind_speed[0] - 1e-9 <= v <= oc.wind_speed[-1] + 1e-9]
    if not winds:
        return None
    max_hz = config.campbell.max_hz or 1.25 * torsion_frequency(model, 0.0)
    return campbell(turbine, winds, max_hz=max_hz, model=model)


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
        from windflutter.post.animation import write_mode_animation  # noqa: PLC0415

        fe = fe_model(point)
        f = res.flutter_frequency_hz
        return write_mode_animation(fe, res.flutter_dof_vector, outdir / "animations" / f"flutter_p{point.index:04d}.pvd",
                                    n_frames=config.output.animation_frames, name=f"flutter_p{point.index:04d}",
                                    frequency_hz=float(f) if np.isfinite(f) and f > 0 else None)
    except Exception as exc:  # a picture must not cost the point
        res.info["animation_error"] = f"{type(exc).__name__}: {exc}"[:300]
        return None


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
