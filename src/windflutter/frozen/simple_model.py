"""The seed's rotor "simple model" (Castillo Capponi 2010, ch. 4.1.8, fig. 4.6;
docs/typical_section.md, "The seed's simple model").

A 2-DOF (plunge ``h`` along the blade's flapwise direction, pitch ``alpha``) typical section at
75 % of the blade radius, with Theodorsen aerodynamics and the inflow of a rotor:

* relative speed ``U = sqrt(V^2 + (Omega r)^2)`` (induction neglected, as in the thesis);
* inflow angle ``phi = atan(V / (Omega r))``, pitch ``theta_p(V)`` from the control curve and
  structural twist ``theta_s``;
* the plunge DOF is normal to the chord, the lift normal to ``U``: the angle between them is the
  angle of attack ``theta_n = phi - theta_s - theta_p``, so the aerodynamics sees the plunge
  ``h cos(theta_n)`` and the lift acts on the plunge DOF as ``L cos(theta_n)`` (thesis eq. 4.3).

For each wind speed the rotor speed is increased from a stable value; the first unstable rotor
speed is the lower of the flutter onset (located by p-k tracking + Brent root-finding on the
tracked mode's real part) and the static divergence (closed form in U, converted to rotor
speed).  ``frozen_k=True`` reproduces the thesis's assumption: ``k = omega_s b / U`` with a fixed
structural frequency (0.20 Hz for the 5 MW, 0.11 Hz for the 20 MW) at every operating point,
i.e. a p-method with C frozen at that k.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from importlib import resources
from typing import Any

import numpy as np

from windflutter.errors import InputError
from windflutter.model.yamlio import load_yaml_text
from windflutter.section import (
    TypicalSection,
    divergence_speed,
    locate_pk_onset,
    natural_frequencies,
)
from windflutter.units import RPM

__all__ = [
    "RotorSection",
    "OnsetPoint",
    "SimpleModelResult",
    "load_simple_models",
    "inflow",
    "section_at",
    "first_unstable",
    "run_simple_model",
]


@dataclass(frozen=True)
class RotorSection:
    """Section data of the simple model of one turbine (SI; degrees/RPM only where named)."""

    name: str
    label: str
    chord: float
    mass: float
    inertia: float
    static_moment: float
    plunge_stiffness: float
    pitch_stiffness: float
    radius: float
    frozen_frequency_hz: float
    elastic_axis: float
    structural_twist_deg: float
    wind_speed: np.ndarray = field(repr=False)
    pitch_deg: np.ndarray = field(repr=False)
    reported_rpm: tuple[float, float] | None = None
    air_density: float = 1.225
    lift_slope: float = 2.0 * math.pi

    def pitch(self, V: float) -> float:
        """Blade pitch (rad) at wind speed V (m/s), linear interpolation of the control curve."""
        return math.radians(float(np.interp(V, self.wind_speed, self.pitch_deg)))


#: numeric fields of a turbine entry in ``simple_model.yaml`` (SI; degrees where named)
_NUMBERS = ("chord", "mass", "inertia", "plunge_stiffness", "pitch_stiffness", "radius",
            "frozen_frequency_hz", "elastic_axis", "structural_twist_deg")


def load_simple_models(path: str | None = None) -> dict[str, RotorSection]:
    """Read ``data/seed_simple_model/simple_model.yaml`` (or ``path``) into RotorSections.

    Raises
    ------
    InputError
        For an unreadable file, invalid YAML or a missing / non-numeric entry (named).
    """
    if path is None:
        text = (resources.files("windflutter") / "data" / "seed_simple_model" /
                "simple_model.yaml").read_text()
        src = "simple_model.yaml"
    else:
        try:
            with open(path, encoding="utf-8") as fh:
                text = fh.read()
        except OSError as exc:
            raise InputError("path", path, f"a readable YAML file ({exc.strerror})") from None
        src = path
    doc = load_yaml_text(text, source=src)
    curves = _entry(doc, "control_curves", "", src)
    out = {}
    for name, d in _entry(doc, "turbines", "", src).items():
        where = f"turbines.{name}."
        cc = _entry(curves, str(_entry(d, "control", where, src)), "control_curves.", src)
        nums = {k: _number(_entry(d, k, where, src), where + k, src) for k in _NUMBERS}
        out[name] = RotorSection(
            name=name,
            label=d.get("label", name),
            static_moment=_number(d.get("static_moment", 0.0), where + "static_moment", src),
            wind_speed=np.asarray(_entry(cc, "wind_speed", "control_curves.", src), dtype=float),
            pitch_deg=np.asarray(_entry(cc, "pitch_deg", "control_curves.", src), dtype=float),
            reported_rpm=tuple(d["reported_rpm"]) if "reported_rpm" in d else None,
            **nums,
        )
    return out


def _entry(d: Any, key: str, where: str, src: str) -> Any:
    """``d[key]``, or :class:`InputError` naming ``where + key``."""
    if not isinstance(d, dict) or key not in d:
        raise InputError(where + key, None, "an entry of the simple-model file; the key is missing", src)
    return d[key]


def _number(v: Any, field: str, src: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise InputError(field, v, "a finite number", src)
    return float(v)


def inflow(V: float, omega_rotor: float, radius: float) -> tuple[float, float]:
    """Relative speed ``U`` (m/s) and inflow angle ``phi`` (rad, from the rotor plane)."""
    return math.hypot(V, omega_rotor * radius), math.atan2(V, omega_rotor * radius)


def section_at(rs: RotorSection, V: float, omega_rotor: float,
               with_angle: bool = True) -> tuple[TypicalSection, float]:
    """The typical section and its relative speed at wind speed V (m/s), rotor speed (rad/s)."""
    U, phi = inflow(V, omega_rotor, rs.radius)
    theta_n = phi - math.radians(rs.structural_twist_deg) - rs.pitch(V) if with_angle else 0.0
    sec = TypicalSection(
        semi_chord=rs.chord / 2.0,
        elastic_axis=rs.elastic_axis,
        mass=rs.mass,
        static_moment=rs.static_moment,
        inertia=rs.inertia,
        plunge_stiffness=rs.plunge_stiffness,
        pitch_stiffness=rs.pitch_stiffness,
        air_density=rs.air_density,
        lift_slope=rs.lift_slope,
        plunge_angle=theta_n,
    )
    return sec, U


@dataclass
class OnsetPoint:
    """First instability at one wind speed (rotor speeds in RPM; NaN if none up to the limit)."""

    wind_speed: float
    flutter_rpm: float
    flutter_frequency: float  # rad/s (NaN if no flutter)
    reduced_frequency: float
    divergence_rpm: float

    @property
    def first_unstable_rpm(self) -> float:
        return float(np.nanmin([self.flutter_rpm, self.divergence_rpm, np.inf]))

    @property
    def kind(self) -> str:
        if not math.isfinite(self.first_unstable_rpm):
            return "none"
        return "flutter" if self.first_unstable_rpm == self.flutter_rpm else "divergence"


@dataclass
class SimpleModelResult:
    """Onset curve of one turbine."""

    turbine: RotorSection
    frozen_k: bool
    points: list[OnsetPoint]

    def to_dict(self) -> dict[str, Any]:
        def clean(x: float) -> float | None:
            return None if not math.isfinite(x) else float(x)

        return {
            "turbine": self.turbine.name,
            "label": self.turbine.label,
            "method": "frozen-k" if self.frozen_k else "p-k",
            "frozen_frequency_hz": self.turbine.frozen_frequency_hz if self.frozen_k else None,
            "wind_speed": [p.wind_speed for p in self.points],
            "first_unstable_rpm": [clean(p.first_unstable_rpm) for p in self.points],
            "kind": [p.kind for p in self.points],
            "flutter_rpm": [clean(p.flutter_rpm) for p in self.points],
            "flutter_frequency_hz": [clean(p.flutter_frequency / (2 * math.pi)) for p in self.points],
            "reduced_frequency": [clean(p.reduced_frequency) for p in self.points],
            "divergence_rpm": [clean(p.divergence_rpm) for p in self.points],
            "thesis_reported_rpm": list(self.turbine.reported_rpm) if self.turbine.reported_rpm else None,
        }

    @property
    def first_unstable_rpm(self) -> np.ndarray:
        return np.array([p.first_unstable_rpm for p in self.points])


def first_unstable(
    rs: RotorSection,
    V: float,
    *,
    frozen_k: bool = False,
    max_rpm: float = 100.0,
    n_grid: int = 40,
) -> OnsetPoint:
    """First unstable rotor speed at wind speed ``V`` (m/s) for rotor speeds up to ``max_rpm``.

    The two modes are followed upwards on ``n_grid`` rotor speeds up to ``max_rpm`` (or 1.5 x
    the divergence rotor speed)
    (p-k with k iterated to each mode's frequency, or with k frozen), the first crossing of a
    mode's real part through 0 is refined by Brent's method (rotor speed to 1e-10 rad/s).
    Divergence: closed form ``U_D`` converted with ``Omega = sqrt(U_D^2 - V^2) / r``.
    """
    if not (V >= 0 and math.isfinite(V)):
        raise InputError("wind_speed", V, "a non-negative wind speed (m/s)")
    sec0, _ = section_at(rs, V, max_rpm / n_grid * RPM)
    ud = divergence_speed(sec0)
    d_rpm = float("nan")
    if ud is not None and ud > V:
        d_rpm = math.sqrt(ud * ud - V * V) / rs.radius / RPM
    if d_rpm > max_rpm:
        d_rpm = float("nan")
    # flutter is searched up to min(max_rpm, 1.5 x divergence), i.e. also beyond divergence
    # (reported for information; the first instability is then the divergence).  p-k tracking
    # stops where the iteration has no oscillatory solution any more (real root pairs).
    top = min(max_rpm, 1.5 * d_rpm) if math.isfinite(d_rpm) else max_rpm
    omegas = np.linspace(top / n_grid, top, n_grid) * RPM
    lam0 = 1j * natural_frequencies(sec0)
    kw = {"frozen_omega": 2 * math.pi * rs.frozen_frequency_hz} if frozen_k else {}
    res = locate_pk_onset(lambda om: section_at(rs, V, om), omegas, lam0, **kw)
    if res["x"] is None:
        f_rpm = w_f = k_f = float("nan")
    else:
        f_rpm = res["x"] / RPM
        w_f = abs(res["lam_f"].imag)
        k_f = float(res["k"])
    return OnsetPoint(float(V), float(f_rpm), float(w_f), float(k_f), d_rpm)


def run_simple_model(
    rs: RotorSection,
    wind_speeds: np.ndarray | None = None,
    *,
    frozen_k: bool = False,
    max_rpm: float = 100.0,
    n_grid: int = 40,
) -> SimpleModelResult:
    """First unstable rotor speed for each wind speed (default 4, 5, ..., 25 m/s)."""
    if wind_speeds is None:
        wind_speeds = np.arange(4.0, 25.0 + 1e-9, 1.0)
    pts = [first_unstable(rs, float(V), frozen_k=frozen_k, max_rpm=max_rpm, n_grid=n_grid)
           for V in wind_speeds]
    return SimpleModelResult(rs, frozen_k, pts)
