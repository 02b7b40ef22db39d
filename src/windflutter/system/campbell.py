"""The operating-point Campbell analysis: every mode of the turbine along its operating curve.

:func:`campbell` runs :class:`~windflutter.system.operational.OperationalModel` at each wind speed
(rotor speed and pitch from the turbine's operating curve), names the modes
(:mod:`windflutter.system.modes`) and follows them from one wind speed to the next by the MAC of
their physical signatures (:func:`windflutter.system.modes.mode_signature`: tower and nacelle
motion, drivetrain, the strips' flap/edge/torsion motion per multi-blade coordinate -- a
comparison that does not depend on the reduction bases, which change with the operating point).

The result (:class:`CampbellResult`) is what the CLI prints (``--json``), exports (CSV,
HAWCStab2-style ``.cmb``) and plots.
"""

from __future__ import annotations

import dataclasses
import math
import pickle
import warnings
from concurrent.futures import FIRST_COMPLETED, wait
from dataclasses import dataclass, field

import numpy as np

from windflutter.errors import ModelError, ValidityWarning, WindflutterError
from windflutter.linalg_tools import mac_matrix
from windflutter.parallel import WorkerPool, check_workers, default_workers
from windflutter.structure.labels import frame_components
from windflutter.system.modes import (ModeRecord, basis_components, point_modes, rotating_damping_ratio,
                                     state_eig)
from windflutter.system.operational import OperationalModel, missing_curve_error, structural_margin
from windflutter.units import RPM


@dataclass
class CampbellPoint:
    """One operating point: wind speed (m/s), rotor speed (RPM), pitch (deg), its modes (in
    ascending frequency) and the steady state's rotor power (W), thrust (N) and blade-tip
    flapwise deflection (m) (NaN without aerodynamics)."""

    wind_speed: float
    rotor_speed_rpm: float
    pitch_deg: float
    modes: list[ModeRecord]
    power: float = float("nan")
    thrust: float = float("nan")
    tip_deflection: float = float("nan")

    def as_dict(self) -> dict:
        return {"wind_speed": float(self.wind_speed), "rotor_speed_rpm": float(self.rotor_speed_rpm),
                "pitch_deg": float(self.pitch_deg), "modes": [m.as_dict() for m in self.modes]}


@dataclass
class Track:
    """A mode followed along the wind speeds: ``index[i]`` is its position in point ``i``'s mode
    list (-1 where it is not found); ``names`` the distinct names it carried, in order (a mixed mode's
    name shows its second participation, which can change along the curve)."""

    index: list[int]
    names: list[str] = field(default_factory=list)
    #: the structural identity the track follows (``"1st edge BW"``; empty for modes without one)
    identity: str = ""

    @property
    def name(self) -> str:
        return self.identity or (self.names[-1] if self.names else "")

    @property
    def changes_identity(self) -> bool:
        return len(self.names) > 1


@dataclass
class CampbellResult:
    """Modes of the whole turbine (or the rotor on a fixed nacelle) along the operating curve."""

    turbine: str
    part: str
    points: list[CampbellPoint]
    tracks: list[Track] = field(default_factory=list)
    frame: str = "ground-fixed"
    assumptions: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        """The JSON of ``windflutter campbell --json`` (exactly these keys)."""
        return {"turbine": self.turbine, "part": self.part, "frame": self.frame,
                "points": [p.as_dict() for p in self.points]}

    def least_damped(self, exclude_rigid: bool = True):
        """``(point, mode)`` of the least damped mode over all points (None if no modes)."""
        best = None
        for p in self.points:
            for m in p.modes:
                if exclude_rigid and (m.rigid or _structural(p, m)):
                    continue
                if best is None or m.damping_ratio < best[1].damping_ratio:
                    best = (p, m)
        return best

    def unstable(self):
        """``[(point, mode)]`` with negative damping (the rigid-body drivetrain root and the blade
        structure's own static instabilities, :meth:`structure_unstable`, excluded)."""
        return [(p, m) for p in self.points for m in p.modes
                if m.damping_ratio < 0 and not m.rigid and not _structural(p, m)]

    def structure_unstable(self):
        """``[(point, mode)]`` made mostly of a statically unstable own mode of the prestressed blade
        (no aerodynamics: a local buckling of the mesh, family ``buckling``), or growing aperiodically
        at a point that has one (:data:`APERIODIC`) -- a defect of the FE model at that operating
        point, not an aeroelastic instability."""
        return [(p, m) for p in self.points for m in p.modes if _structural(p, m)]


#: a root growing at least this fast for its frequency (``-zeta``; its damped frequency 0.87 of its
#: frequency or less), in the ground-fixed or in the rotating frame, is aperiodic: at a point whose
#: blade structure is statically unstable on its own, it is that static instability showing through a
#: global mode, not an oscillating aeroelastic one (the IEA 15 MW shell with MITC4's shear: at 12 m/s
#: a "1st flap FW" at 0.19 Hz, -78 %; at 10 m/s one at 0.115 Hz, -29 % in the ground-fixed frame, at
#: the rotor speed's 0.118 Hz: -99.5 % in the rotating frame)
APERIODIC = 0.5


def _structural(p: CampbellPoint, m: ModeRecord) -> bool:
    """``m`` at ``p`` is the blade structure's own static instability (:meth:`CampbellResult.
    structure_unstable`)."""
    if m.family == "buckling":
        return True
    if m.rigid or m.damping_ratio >= 0 or not any(o.family == "buckling" for o in p.modes):
        return False
    return min(m.damping_ratio, rotating_damping_ratio(m, p.rotor_speed_rpm * RPM)) <= -APERIODIC


def track_modes(points: list[CampbellPoint], min_mac: float = 0.5) -> list[Track]:
    """Follow the modes from point to point: one track per structural identity (a mode keeps its
    identity along the curve by participation, :mod:`windflutter.system.identity`, each identity used
    once per point); the modes without one (mixed beyond naming) by the assignment of maximum MAC of
    their signatures (Hungarian algorithm) among themselves, a pair with MAC below ``min_mac``
    starting a new track."""
    from scipy.optimize import linear_sum_assignment


    n = len(points)
    tracks: list[Track] = []
    by_identity: dict = {}
    live: dict[int, int] = {}  # unnamed mode index at the previous point -> track
    for i, p in enumerate(points):
        where: dict[int, int] = {}
        for k, m in enumerate(p.modes):
            key = getattr(m, "identity", None)
            if key is not None:
                if key not in by_identity:
                    tracks.append(Track(index=[-1] * n, identity=key.name))
                    by_identity[key] = len(tracks) - 1
                where[k] = by_identity[key]
        rest = [k for k in range(len(p.modes)) if k not in where]
        new_live: dict[int, int] = {}
        if i > 0 and live and rest:
            prev = points[i - 1].modes
            keys = list(live)
            mac = mac_matrix(np.stack([prev[j].signature for j in keys], 1),
                             np.stack([p.modes[k].signature for k in rest], 1))
            for r, c in zip(*linear_sum_assignment(-mac)):
                if mac[r, c] >= min_mac:
                    new_live[rest[c]] = live[keys[r]]
        for k in rest:
            if k not in new_live:
                tracks.append(Track(index=[-1] * n))
                new_live[k] = len(tracks) - 1
            where[k] = new_live[k]
        for k, t in where.items():
            tr = tracks[t]
            tr.index[i] = k
            name = p.modes[k].name
            if not tr.names or tr.names[-1] != name:
                tr.names.append(name)
        live = {k: t for k, t in new_live.items()}
    return tracks


#: a named mode whose natural frequency moves more than this between neighbouring points (both damped
#: below :data:`HEAVILY_DAMPED`) makes the step ambiguous: it is refined
JUMP = 0.12
#: a mode damped above this ratio is heavily damped: its names are not checked for jumps (its damped
#: frequency moves fast and means little), and the rotor-speed Campbell draws it without lines
HEAVILY_DAMPED = 0.3


def ambiguous(before: list[ModeRecord], after: list[ModeRecord]) -> bool:
    """An identity whose lightly damped mode's natural frequency jumps by more than :data:`JUMP`
    between two neighbouring points (the names may have been swapped across a veering).  Rigid-body
    roots (the drivetrain's free rotation, 0.003-0.03 Hz on the IEA 22 MW) are left out: their
    frequency is the small remainder of a zero one, and its relative change names nothing (it made
    11 of the IEA 22 MW shell Campbell's 12 refined steps)."""
    was = {m.identity: m for m in before if m.identity is not None}
    for m in after:
        q = was.get(m.identity)
        light = q is not None and not m.rigid and max(m.damping_ratio, q.damping_ratio) < HEAVILY_DAMPED
        if light and abs(m.frequency_hz / q.frequency_hz - 1) > JUMP:
            return True
    return False


def default_wind_speeds(turbine) -> np.ndarray:
    """The operating curve's wind speeds within 3-25 m/s (its own range if narrower)."""
    oc = turbine.operating_curve
    if oc is None:

        raise missing_curve_error(turbine)
    v = np.asarray(oc.wind_speed, float)
    sel = v[(v >= 3.0 - 1e-9) & (v <= 25.0 + 1e-9)]
    return sel if sel.size else v


def campbell_workers(model: OperationalModel, n_points: int, workers: int | None = None) -> int:
    """Processes for a Campbell of ``n_points`` wind speeds: ``workers`` if given, else (``None``) the
    usable cores (at most one per point) for a shell model -- a deflected shell point takes seconds
    (6.5 s on the IEA 22 MW), a worker's start about as long as one -- and 1 (this process) for a beam
    model, whose points take a fraction of a second."""
    if workers is not None:
        return check_workers(workers)
    return max(1, min(default_workers(), n_points)) if model.options.model == "shell" else 1


def campbell(turbine, wind_speeds=None, options=None, max_hz: float = 2.5, progress=None,
             model=None, workers: int | None = 1, prepared: dict | None = None) -> CampbellResult:
    """The Campbell analysis of ``turbine`` (see module docstring).  Each point continues the
    previous one's identities; where a named mode's frequency jumps (:func:`ambiguous`) the step is
    refined once: the names are carried through the middle of the step (not reported).

    Parameters
    ----------
    wind_speeds : m/s; default :func:`default_wind_speeds`.
    options : :class:`~windflutter.system.operational.OperationalOptions`.
    max_hz : modes up to this undamped frequency (Hz).
    progress : optional ``progress(fraction, text)``.
    model : an :class:`~windflutter.system.operational.OperationalModel` to reuse (its parts are cached).
    workers : processes evaluating the points (:func:`campbell_workers`; ``None``: its default): with
        more than one, the operating points (steady state, linearization, blade basis, eigen-solve) are
        evaluated in worker processes (:class:`PooledPoints`) and named here in wind-speed order, the
        same names as serially; frequencies and damping equal to the iterative blade basis's tolerance
        (its warm start is a worker's own previous point).
    prepared : ``{wind speed: campbell_point(...)}`` of points already evaluated with ``model``'s
        options (:func:`campbell_point`; a stability map's operating points): used as they are, the
        other wind speeds and any refined step's middle evaluated as above (:class:`PreparedPoints`).
    """

    om = model or OperationalModel(turbine, options)
    ws = default_wind_speeds(turbine) if wind_speeds is None else np.asarray(wind_speeds, float)
    n_workers = campbell_workers(om, len(ws), workers)

    def evaluated(winds):  # a shell's points in worker processes (also a prepared run's middles only)
        pooled = n_workers > 1 and (len(winds) > 1 or bool(prepared))
        return PooledPoints(om, winds, max(1, min(n_workers, len(winds)))) if pooled else SerialPoints(om)

    source = PreparedPoints(om, prepared, ws, evaluated) if prepared else evaluated(ws)
    with source:
        pts = _named_points(source, ws, max_hz, progress)
    if progress is not None:
        progress(1.0, "done")
    return CampbellResult(turbine=str(getattr(turbine, "name", "")), part=om.options.part, points=pts,
                          tracks=track_modes(pts), assumptions=om.describe())


def _named_points(source, ws, max_hz: float, progress) -> list[CampbellPoint]:
    """The points of ``ws`` from ``source`` (:class:`SerialPoints` or :class:`PooledPoints`), named in
    wind-speed order, each continuing the previous one's names."""
    pts: list[CampbellPoint] = []
    for i, v in enumerate(ws):
        if progress is not None:
            progress(i / len(ws), f"V = {v:g} m/s")
        ps, eig, st = source.point(float(v))
        warn_indefinite_blade(ps)
        prev = pts[-1] if pts else None
        modes = point_modes(ps, max_hz=max_hz, previous=prev.modes if prev else None, eig=eig)
        if prev is not None and ambiguous(prev.modes, modes):  # refine the step: carry the names through its middle
            mps, meig, _ = source.point(0.5 * (prev.wind_speed + float(v)), middle=True)
            mid = point_modes(mps, max_hz=max_hz, previous=prev.modes, eig=meig)
            modes = point_modes(ps, max_hz=max_hz, previous=mid, eig=eig)
        pts.append(CampbellPoint(wind_speed=float(v), rotor_speed_rpm=ps.omega / RPM, pitch_deg=math.degrees(ps.pitch),
                                 modes=modes, **st))
    return pts


def warn_indefinite_blade(ps) -> None:
    """A :class:`~windflutter.errors.ValidityWarning` when the blade's structure at the operating point
    ``ps`` is statically unstable on its own (:func:`~windflutter.system.operational.structural_margin`
    not positive: a mode of its basis with a negative stiffness, or negative eigenvalues of its full-order
    stiffness outside the basis, ``ps.blade_negative``): a local buckling under the steady stress (a thin
    skin panel, or the mesh), so the point's modes are linearized about a statically unstable structure,
    and its divergent root is not among the Campbell's oscillating modes.  Found at every operating point
    of the IEA 15 MW shell (its outboard single skin; docs/verification.md, "Not verified, or known to
    disagree", item 5); point sources without a blade structure (duck-typed in tests) are not checked."""
    if getattr(ps, "blade_structure", None) is None:
        return
    margin = structural_margin(ps)
    if margin > 0:
        return
    n = getattr(ps, "blade_negative", None)
    where = (f"{n} negative eigenvalue(s) of its full-order stiffness, outside the modes of its basis"
             if not np.isfinite(margin) else "a mode of its basis with a negative stiffness")
    kind = ("the blade's FE structure under its steady stress is statically unstable at the operating point "
            f"without aerodynamics ({where}: a local buckling, of a thin skin panel or of the mesh, is likely); "
            "its modes there are linearized about an unstable structure")
    warnings.warn(ValidityWarning(f"at V = {ps.wind_speed:.1f} m/s {kind}", rotor_speed_rpm=ps.omega / RPM,
                                  wind_speed=float(ps.wind_speed), kind=kind), stacklevel=2)


def _steady_summary(st) -> dict:
    nan = float("nan")
    return {"power": float(st.power) if st is not None else nan, "thrust": float(st.thrust) if st is not None else nan,
            "tip_deflection": float(st.tip_flap) if st is not None else nan}


class SerialPoints:
    """The operating points evaluated in this process, in the order asked: ``point(v)`` is
    ``(PointSystem, state_eig, steady summary)``."""

    def __init__(self, model: OperationalModel):
        self.model = model

    def point(self, v: float, middle: bool = False):  # noqa: ARG002 - same signature as PooledPoints
        ps = self.model.at(v)
        return ps, state_eig(ps.mbc), _steady_summary(ps.steady)

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        return None


@dataclass
class NamingBlade:
    """What naming a point's modes reads of its blade once the basis's strip and tip motions are
    computed (:func:`portable_point`): the strips."""

    sections: object


def portable_point(ps):
    """A copy of the :class:`~windflutter.system.operational.PointSystem` ``ps`` with what its modes'
    naming needs and little else, to cross a process boundary: the blade basis's strip and tip motions
    computed (:func:`~windflutter.system.modes.basis_components`, ``tip_basis``), the blade reduced to
    its strips, no support, reference, steady state or initial-stress matrices (the receiver attaches
    its own support and reference, the same objects).  Full-order points (no basis) keep their blade."""
    if ps.Phi is None:
        return dataclasses.replace(ps, support=None, reference=None, steady=None, ksigma=None, klink=None)
    basis_components(ps)
    if ps.tip_frame is not None and ps.tip_basis is None:
        ps.tip_basis = frame_components(ps.blade.sections, np.asarray(ps.blade.struct.T @ ps.Phi), ps.tip_frame)
    return dataclasses.replace(ps, blade=NamingBlade(ps.blade.sections), support=None, reference=None, steady=None,
                               ksigma=None, klink=None)


def campbell_point(ps, eig: tuple, max_hz: float | None = None) -> tuple:
    """``(portable_point(ps), eig, steady summary)``: what the Campbell reads of an operating point
    evaluated in another process (:class:`PointEvaluator`, or a stability map's worker, whose
    sweep starts at the operating point) by a copy of the receiver's model made once its reference
    was computed: the receiver attaches its own support and reference, which are then the ones the
    point was assembled with (the support's modal basis is an iterative eigen-solve's, and the
    tower's degenerate pairs: two models' bases may differ by a rotation, and a point named through
    another model's support is named wrong).  ``eig`` (:func:`~windflutter.system.modes.state_eig`)
    keeps the roots with ``Im lambda > 0`` only, and with ``max_hz`` (the Campbell's limit, Hz) those with
    ``|lambda| <= 2 pi max_hz``: naming reads no others (:func:`~windflutter.system.modes.point_modes`,
    the same test), and the rest is most of the transfer and of what a run holds until its Campbell
    (1126 states on the IEA 22 MW shell: 20 MB of eigenvectors a point, about 2 MB below the limit)."""
    lam, left, right = eig
    up = lam.imag > 0
    if max_hz is not None:
        up &= np.abs(lam) <= 2 * np.pi * max_hz
    return portable_point(ps), (lam[up], left[:, up], right[:, up]), _steady_summary(ps.steady)


class PreparedPoints:
    """Operating points already evaluated (``prepared``: ``{wind speed: campbell_point(...)}``, by
    ``model`` or copies of it made after its reference was computed, e.g. a stability map's workers)
    served as they are; the wind speeds of ``wind_speeds`` not prepared
    and a refined step's middles from ``evaluated(wind_speeds)`` (a :class:`PooledPoints` or
    :class:`SerialPoints`), opened at once when some wind speed is missing, else when a middle is
    first asked for (none: no worker is started)."""

    def __init__(self, model: OperationalModel, prepared: dict, wind_speeds, evaluated):
        self.model, self.prepared = model, {float(v): p for v, p in prepared.items()}
        self.missing = [float(v) for v in wind_speeds if float(v) not in self.prepared]
        self.evaluated, self.source = evaluated, None

    def _source(self):
        if self.source is None:
            self.source = self.evaluated(self.missing).__enter__()
        return self.source

    def point(self, v: float, middle: bool = False):
        if middle or float(v) not in self.prepared:
            return self._source().point(v, middle)
        ps, eig, st = self.prepared.pop(float(v))
        ps.support, ps.reference = self.model.support(), self.model.reference()
        return ps, eig, st

    def __enter__(self):
        if self.missing:
            self._source()
        return self

    def __exit__(self, *exc) -> None:
        if self.source is not None:
            self.source.__exit__(*exc)


class PointEvaluator:
    """The worker's task: ``(portable_point, state_eig, steady summary)`` of the point at ``v``; the
    worker's model keeps the blade of the last pitch only (:meth:`OperationalModel.keep_blades`)."""

    def __init__(self, model: OperationalModel):
        self.model = model

    def __call__(self, v: float):
        try:
            ps = self.model.at(v)
        except WindflutterError as exc:  # the parent raises it as the serial run would (one clear line)
            return PointFailure(exc)
        eig = state_eig(ps.mbc)
        self.model.keep_blades([ps.pitch])
        return campbell_point(ps, eig)


class PointFailure:
    """A worker's own error at a point (no steady state, a structural instability, ...), carried back to
    be raised in the parent: the exception itself when it survives pickling, else a
    :class:`~windflutter.errors.ModelError` with its message (e.g. an error holding an unpicklable value)."""

    def __init__(self, exc: WindflutterError):
        try:
            self.exc = pickle.loads(pickle.dumps(exc))
        except Exception:  # noqa: BLE001 - any pickling failure: the message is what matters
            self.exc = ModelError(str(exc))


class PooledPoints:
    """The operating points evaluated in ``workers`` processes (:class:`~windflutter.parallel.WorkerPool`):
    the wind speeds in order, one task per idle worker, a refined step's middle (``middle=True``)
    ahead of the wind speeds not started; ``point(v)`` waits for ``v``'s result and attaches this
    process's support and reference."""

    def __init__(self, model: OperationalModel, wind_speeds, workers: int):
        self.model = model
        model.reference()  # computed once here, sent to the workers with the model
        self.pool = WorkerPool(PointEvaluator(model), workers)
        self.workers = workers
        self.queue = [(float(v), False) for v in wind_speeds]
        self.running: dict = {}
        self.done: dict = {}

    def _top_up(self) -> None:
        while self.queue and len(self.running) < self.workers:
            key = self.queue.pop(0)
            self.running[self.pool.submit(key[0])] = key

    def point(self, v: float, middle: bool = False):
        key = (float(v), bool(middle))
        if key not in self.done and key not in self.running.values():
            if key in self.queue:
                self.queue.remove(key)
            self.queue.insert(0, key)
        self._top_up()
        while key not in self.done:
            finished, _ = wait(list(self.running), return_when=FIRST_COMPLETED)
            for fut in finished:
                self.done[self.running.pop(fut)] = self.pool.result(fut)
            self._top_up()
        res = self.done.pop(key)
        if not res.ok:
            raise RuntimeError(f"the operating point at {key[0]:g} m/s failed in a worker process: {res.error}\n"
                               f"{res.traceback}")
        if isinstance(res.value, PointFailure):
            raise res.value.exc
        ps, eig, st = res.value
        ps.support, ps.reference = self.model.support(), self.model.reference()
        return ps, eig, st

    def __enter__(self):
        self.pool.__enter__()
        return self

    def __exit__(self, *exc) -> None:
        self.pool.__exit__(*exc)
