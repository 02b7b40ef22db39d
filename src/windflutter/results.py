"""Result types of an analysis (bottom layer: imports only NumPy and :mod:`windflutter.units`).

The per-point interface of ``windflutter run`` (``docs/workflow.md``): an analyser is handed an
:class:`OperatingPoint` and returns a :class:`PointResult`; the workflow stores it
(:mod:`windflutter.post.store`), plots it and reports it. The types live here, below every layer
that makes or reads them, so the store does not import the workflow. They stay importable from
:mod:`windflutter.workflow`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from windflutter.units import RPM

__all__ = ["OperatingPoint", "PointResult", "Onset", "PointSummary", "point_result"]


@dataclass(frozen=True)
class OperatingPoint:
    """One operating point of a run (user units at this edge: m/s, RPM).

    Attributes
    ----------
    index : position in the run (0-based), stable across resumes.
    wind_speed : free wind speed (m/s).
    aero : ``potential`` or ``viscous``.
    method : ``pk`` or ``thesis``.
    min_rpm, max_rpm : rotor-speed search range (RPM), the config's ``rotor_speed.min_rpm`` and
        ``max_rpm`` (``rpm_min`` and ``rpm_max``, the names before issue 29, still read them).
    tolerance_rpm : onset tolerance (RPM).
    sweep_rpm : rotor speeds of the Campbell / damping sweep (RPM).
    """

    index: int
    wind_speed: float
    aero: str
    method: str
    min_rpm: float
    max_rpm: float
    tolerance_rpm: float
    sweep_rpm: tuple[float, ...]

    @property
    def label(self) -> str:
        return f"V = {self.wind_speed:g} m/s, {self.aero}, {self.method}"

    @property
    def rpm_min(self) -> float:
        """The old name of :attr:`min_rpm`."""
        return self.min_rpm

    @property
    def rpm_max(self) -> float:
        """The old name of :attr:`max_rpm`."""
        return self.max_rpm

    @property
    def omega_range(self) -> tuple[float, float]:
        """Search range in rad/s."""
        return self.min_rpm * RPM, self.max_rpm * RPM


@dataclass
class PointResult:
    """What an analyser returns for one operating point (NaN / None = not found / not given).

    Attributes
    ----------
    flutter_rpm : lowest rotor speed with a flutter mode (RPM); NaN if stable in the range.
    flutter_frequency_hz : frequency of the flutter mode at onset (Hz).
    flutter_mode : label of the flutter mode (e.g. ``"1st edge"``).
    divergence_rpm : lowest rotor speed with static divergence (RPM); NaN if none.
    sweep_rpm : (nr,) rotor speeds of the sweep (RPM).
    damped_frequency_hz, damping_ratio : (nr, nm) tracked modes over the sweep: the DAMPED frequency
        ``|Im lambda| / 2 pi`` (Hz) and the damping ratio (-); stored in ``results.nc`` as
        ``damped_frequency`` beside the undamped ``frequency`` ``|lambda| / 2 pi``.
    mode_labels : (nm,) labels of the tracked modes.
    station_radius : (ns,) radii of the span stations (m).
    flutter_shape : (ns, 3) complex flap, edge (m) and torsion (rad) of the flutter mode at onset
        at each station, any common normalisation.
    aero_work : (ns, 3) aerodynamic work per cycle on the flutter mode at each station, split
        into plunge, pitch and edgewise (J, same normalisation as ``flutter_shape``); see
        :mod:`windflutter.post.aerowork`.
    info : extra scalars stored as attributes of the point (e.g. iterations, pitch).
    flutter_dof_vector : (n_dof,) complex flutter mode in the FE model's DOF numbering, for the
        VTK animation (not stored in the dataset); needs ``analyser.fe_model(point)``.
    operating_system : the operating point's linearized system and eigen-solution
        (:func:`windflutter.system.campbell.campbell_point`), which the run's Campbell reads instead
        of evaluating the point again (method p; not stored in the dataset).
    status, reason : ``ok`` / ``failed`` and why (set by the workflow on an exception).
    elapsed : wall-clock time (s), set by the workflow.
    """

    flutter_rpm: float = float("nan")
    flutter_frequency_hz: float = float("nan")
    flutter_mode: str = ""
    divergence_rpm: float = float("nan")
    sweep_rpm: np.ndarray | None = None
    damped_frequency_hz: np.ndarray | None = None
    damping_ratio: np.ndarray | None = None
    mode_labels: list[str] | None = None
    station_radius: np.ndarray | None = None
    flutter_shape: np.ndarray | None = None
    aero_work: np.ndarray | None = None
    info: dict[str, Any] = field(default_factory=dict)
    flutter_dof_vector: np.ndarray | None = None
    operating_system: Any = None
    status: str = "ok"
    reason: str = ""
    elapsed: float = float("nan")


# ---------------------------------------------------------------- the searches' result types
@dataclass
class Onset:
    """First unstable point along the parameter.

    Attributes
    ----------
    flutter : parameter at flutter onset (None if none found in range).
    flutter_frequency : circular frequency at onset (rad/s).
    flutter_mode : index of the tracked mode (pk) / label.
    flutter_vector : mode shape at onset (working basis).
    divergence : parameter at divergence onset or None.
    history : per-grid-point data (params, eigenvalues of tracked modes (n_p, n_modes)).
    """

    flutter: float | None = None
    flutter_frequency: float | None = None
    flutter_mode: int | None = None
    flutter_vector: np.ndarray | None = None
    divergence: float | None = None
    params: np.ndarray = field(default_factory=lambda: np.zeros(0))
    eigenvalues: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), complex))
    method: str = "pk"
    vectors0: list | None = None
    reason: str = ""


@dataclass
class PointSummary:
    """Result at one wind speed (user units).

    flutter_rpm, flutter_frequency_hz, flutter_mode, divergence_rpm: None when not found in
    range.  pitch_deg: blade pitch used.  sweep_rpm, damped_frequency_hz, damping_ratio, mode_labels:
    the tracked modes over the grid (Campbell; ``damped_frequency_hz`` the damped frequency ``|Im lambda| /
    2 pi`` for every method, as ``results.nc``'s ``frequency`` declares it).  onset: raw search result.
    """

    wind_speed: float
    pitch_deg: float
    flutter_rpm: float | None
    flutter_frequency_hz: float | None
    flutter_mode: str | None
    divergence_rpm: float | None
    sweep_rpm: np.ndarray
    damped_frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    mode_labels: list[str]
    onset: Onset

    @property
    def first_instability(self) -> str | None:
        """``"flutter"``, ``"divergence"`` or None: which onset comes first in rotor speed.

        A flutter crossing above the divergence speed is still reported (like a V-g plot shows
        it), but the turbine's stability limit is the divergence: the linearization about the
        undeformed state no longer describes an equilibrium beyond it.
        """
        fl, dv = self.flutter_rpm, self.divergence_rpm
        if fl is None and dv is None:
            return None
        if dv is None or (fl is not None and fl <= dv):
            return "flutter"
        return "divergence"

    def as_dict(self) -> dict:
        f = (lambda v: None if v is None else float(v))
        return {"wind_speed": float(self.wind_speed), "flutter_rpm": f(self.flutter_rpm),
                "flutter_frequency_hz": f(self.flutter_frequency_hz), "flutter_mode": self.flutter_mode,
                "divergence_rpm": f(self.divergence_rpm), "first_instability": self.first_instability,
                "pitch_deg": float(self.pitch_deg), "note": (getattr(self.onset, "reason", "") or None)}


def point_result(s: PointSummary, info: dict | None = None, reason: str = "") -> PointResult:
    """A search's :class:`PointSummary` as the run's :class:`PointResult` (None -> NaN): what
    ``run`` stores and ``windflutter stability --plot`` draws with the run's figures."""
    nan = float("nan")
    return PointResult(
        flutter_rpm=nan if s.flutter_rpm is None else float(s.flutter_rpm),
        flutter_frequency_hz=nan if s.flutter_frequency_hz is None else float(s.flutter_frequency_hz),
        flutter_mode=s.flutter_mode or "",
        divergence_rpm=nan if s.divergence_rpm is None else float(s.divergence_rpm),
        sweep_rpm=np.asarray(s.sweep_rpm, float), damped_frequency_hz=np.asarray(s.damped_frequency_hz, float),
        damping_ratio=np.asarray(s.damping_ratio, float), mode_labels=list(s.mode_labels),
        info={"pitch_deg": float(s.pitch_deg), **(info or {})}, reason=reason)
