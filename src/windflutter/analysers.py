"""The per-point analysers of ``windflutter run`` (:mod:`windflutter.workflow`).

An analyser is a callable ``analyse(point: OperatingPoint, progress=None) -> PointResult``
(:class:`Analyser`).  :func:`make_analyser` gives the built-in one, :class:`TurbinePointAnalyser`
(one solver per ``(aero, method)`` case from :func:`windflutter.methods.stability_analysis`,
built once and reused across wind speeds), or a plug-in of :mod:`windflutter.backends`.
:func:`operating_campbell` is the run's operating-point Campbell, on the model the analyser built.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable
from typing import Any, Protocol

import numpy as np

from windflutter.backends import BUILTIN, backend_factory
from windflutter.config import AnalysisConfig
from windflutter.errors import InputError, InputWarning, ModelError, ValidityWarning, WindflutterError
from windflutter.operating import campbell_max_hz, campbell_model, operating_campbell as service
from windflutter.post.aerowork import flutter_mode_diagnostics
from windflutter.results import OperatingPoint, PointResult, point_result
from windflutter.system.campbell import campbell_point
from windflutter.methods import case_options, mesh_settings as _mesh, method as search_method, stability_analysis, turbine_options as _opts, with_span_count
from windflutter.units import RPM

# --------------------------------------------------------------------------------------------
# the per-point interface
# --------------------------------------------------------------------------------------------
ProgressCallback = Callable[..., None]


class Analyser(Protocol):
    """``analyse(point, progress=None) -> PointResult``; ``progress(fraction, text=None)``."""

    def __call__(self, point: OperatingPoint, progress: ProgressCallback | None = None) -> PointResult: ...


def make_analyser(turbine: Any, config: AnalysisConfig) -> Analyser:
    """The analyser of ``config.solver.backend``.

    ``windflutter`` gives the built-in stability solver (:func:`_builtin_analyser`); any other
    name is a plug-in of :mod:`windflutter.backends` (registered in this process or in the
    entry-point group ``windflutter.backends``) and gives ``factory(turbine, config)``.
    """
    backend = config.solver.backend
    if backend == BUILTIN:
        return _builtin_analyser(turbine, config)
    return backend_factory(backend)(turbine, config)


def _builtin_analyser(turbine: Any, config: AnalysisConfig) -> Analyser:
    """The built-in turbine stability solver (:mod:`windflutter.frozen.turbine`) behind the
    per-point interface, with the flutter mode shape and aero-work diagnostic added."""
    try:
        from windflutter.frozen import turbine as _st  # noqa: PLC0415
    except ImportError as exc:
        raise ModelError(f"the built-in turbine stability solver is not available ({exc}); use "
                         "a plug-in solver.backend (windflutter.backends) for your own analyser") from None
    if config.model.type not in ("beam", "shell"):
        raise InputError("model.type", config.model.type, "'beam' or 'shell' for the built-in turbine solver")
    return TurbinePointAnalyser(turbine, config, _st)


def mesh_settings(config: AnalysisConfig) -> dict[str, Any]:
    """Mesh-setting overrides of ``config`` (:func:`windflutter.methods.mesh_settings`)."""
    return _mesh(config)


def turbine_options(config: AnalysisConfig, aero: str, method: str, module: Any = None):
    """The seed's solver options of one ``(aero, method)`` case (methods pk, thesis), with the mesh
    (:func:`windflutter.methods.turbine_options`; ``module`` only for tests that substitute
    the solver module)."""
    if module is None:
        return _opts(config, aero, method)
    opts = module.options_from_config(with_span_count(config), aero, method)
    return dataclasses.replace(opts, mesh={**opts.mesh, **mesh_settings(config)})


class TurbinePointAnalyser:
    """Adapter: the solver of each (aero, method) case (:func:`windflutter.methods.
    stability_analysis`) -> ``analyse(point)``; one solver per case, so models are built once per
    blade pitch and reused across wind speeds.
    """

    def __init__(self, turbine: Any, config: AnalysisConfig, module: Any = None):
        self.turbine = turbine
        self.config = config
        self._cases: dict[tuple[str, str], Any] = {}
        self._size: dict[str, Any] = {}
        self._campbell = campbell_case(config)  # its points keep their operating point for the Campbell
        # validate the options now, so a bad combination fails before the first point

        for aero, method in config.cases:
            if search_method(method).config_grid and module is not None:
                turbine_options(config, aero, method, module)  # (a test's substitute solver module)
            else:
                case_options(config, aero, method)

    def _stability(self, aero: str, method: str):
        key = (aero, method)
        if key not in self._cases:
            self._cases[key] = stability_analysis(self.turbine, self.config, aero, method)
            if key == self._campbell:  # method p's OperationalStability: each sweep's operating point kept
                self._cases[key].keep_operating = True
        return self._cases[key]

    def share_campbell_model(self) -> None:
        """Build the Campbell case's solver here, its model's support and reference computed, before
        this analyser is copied to worker processes: the copies assemble their operating points with
        this support basis, so the run's Campbell (on this model, :func:`operating_campbell`) reads
        them (:attr:`PointResult.operating_system`) as its own.  A model that cannot be built here is
        left to the workers, whose points then fail with the reason as before, and they keep no
        operating points (the Campbell evaluates its own)."""
        if self._campbell is None:
            return
        try:
            self._stability(*self._campbell).model.reference()
        except WindflutterError:
            self._cases.pop(self._campbell, None)
            self._campbell = None

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

        grid = np.asarray(point.sweep_rpm, float) if search_method(point.method).config_grid else None
        s, notes = _with_validity_notes(ts.analyse_operating_point, point.wind_speed, rpm_grid=grid)
        size = self._model_size(ts, ts.pitch_at(point.wind_speed))
        if not self._size:
            self._size = {k: v for k, v in size.items() if k != "n_reduced_dof"}
        # the model size goes with each point (the reduced size may depend on its pitch), so
        # the run's attributes do not depend on which points this process computed
        res = point_result(s, info=size, reason=point_reason(notes, getattr(s.onset, "reason", "") or ""))
        if getattr(ts, "operating", None) is not None:  # the Campbell's case (keep_operating)
            limit = campbell_max_hz(self.config, ts.model)  # the Campbell's (the same model's reference)
            res.operating_system, ts.operating = campbell_point(*ts.operating, max_hz=limit), None
        on = s.onset
        if self.config.output.mode_shapes and on.flutter_vector is not None and s.flutter_rpm is not None:
            if progress is not None:
                progress(0.95, f"{point.label}: flutter mode")

            _, sections, am = ts.model(ts.pitch_at(point.wind_speed))
            sys_on = am.at(point.wind_speed, float(s.flutter_rpm) * RPM)
            u = sys_on.expand(on.flutter_vector)
            omega = float(on.flutter_frequency) if on.flutter_frequency else 2 * math.pi * res.flutter_frequency_hz
            d = flutter_mode_diagnostics(u, sys_on.strip, sections, omega)
            res.station_radius, res.flutter_shape, res.aero_work = d.radius, d.shape, d.work
            res.info["aero_work_rotor_total_J"] = d.work_total
            res.flutter_dof_vector = u
        return res


def campbell_case(config: AnalysisConfig) -> tuple[str, str] | None:
    """The ``(aero, method)`` case whose model the run's operating-point Campbell uses (its first
    method-p case), None when the run has no Campbell (``campbell.enabled`` false, no method p, a
    plug-in back-end)."""
    if not (config.campbell.enabled and "p" in config.method and config.solver.backend == BUILTIN):
        return None
    return next(a for a, m in config.cases if m == "p"), "p"


def operating_campbell(turbine: Any, config: AnalysisConfig, analyser: Any = None, progress: bool = False,
                       workers: int = 1, prepared: dict | None = None):
    """The operating-point Campbell of a run (``campbell.enabled`` with method p; None otherwise):
    every mode along the operating curve at the run's wind speeds, with the model of the run's
    first p case (its parts reused when the built-in analyser built them in this process).
    ``workers``: processes for a shell model's points (the run's local workers; a beam model's points
    take a fraction of a second and stay in this process).  ``prepared``: ``{wind speed: point}`` the
    map's analysers kept of their operating points (:attr:`PointResult.operating_system`), not
    evaluated again."""
    key = campbell_case(config)
    if key is None or getattr(turbine, "operating_curve", None) is None:
        return None
    case = getattr(analyser, "_cases", {}).get(key) if analyser is not None else None
    oc = turbine.operating_curve
    lo, hi = float(oc.wind_speed[0]), float(oc.wind_speed[-1])
    winds = [v for v in config.wind_speeds if lo - 1e-9 <= v <= hi + 1e-9]
    dropped = [v for v in config.wind_speeds if v not in winds]
    if dropped:
        warnings.warn(f"the operating-point Campbell covers the operating curve's {lo:g}-{hi:g} m/s: wind speeds "
                      f"{', '.join(f'{v:g}' for v in dropped)} m/s left out of it (no operating point there; the "
                      "stability map still analyses them)", InputWarning, stacklevel=2)
    if not winds:
        return None
    model = case.model if case is not None else campbell_model(turbine, config)
    workers = min(int(workers), len(winds)) if model.options.model == "shell" else 1
    return service(turbine, config, winds, model=model, workers=workers, prepared=prepared)


#: a point's ``reason`` (its validity notes and the search's own reason) is cut to this many characters
MAX_REASON = 2000


def point_reason(notes: list[str], onset: str = "") -> str:
    """A point's ``reason``: its validity notes whole -- each ends with the rotor speed it was found
    from (``[from 27.00 RPM]``), which the command's summary line reads back
    (:func:`windflutter.cli.warn.gather_notes`) -- then the search's own reason (where and why its
    sweep stopped), at most :data:`MAX_REASON` characters, the search's reason shortened first.  (A cut at
    500 characters took the second of two notes' rotor speed, and the run's summary lost that note.)"""
    head = "; ".join(notes)
    if not onset:
        return head[:MAX_REASON]
    room = MAX_REASON - len(head) - (2 if head else 0)
    tail = onset if len(onset) <= room else onset[:max(room - 3, 0)] + "..."
    return ("; ".join([head, tail]) if head else tail)[:MAX_REASON]


def _with_validity_notes(fn: Callable, *args, **kw):
    r"""``(fn(*args, **kw), notes)``: the messages of the
    :class:`~windflutter.errors.ValidityWarning`\ s raised inside (a model used outside its range,
    e.g. the BEM in the propeller-brake state), each with the lowest rotor speed it was raised at
    (``"... [from 17.31 RPM]"``, :func:`validity_from_rpm`), kept with the point (its ``reason``,
    shown in the report beside ``ok``); every warning is still shown as usual, each note once."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ValidityWarning)
        out = fn(*args, **kw)
    lowest: dict[str, float] = {}
    for w in caught:  # shown after the block through the caller's display
        if issubclass(w.category, ValidityWarning):
            text = str(w.message)
            rpm = getattr(w.message, "rotor_speed_rpm", None)
            rpm = float(rpm) if rpm is not None and math.isfinite(rpm) else math.inf
            if text in lowest:
                lowest[text] = min(lowest[text], rpm)
                continue
            lowest[text] = rpm
        warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    notes = [t + (f" [from {r:.2f} RPM]" if math.isfinite(r) else "") for t, r in lowest.items()]
    return out, notes
