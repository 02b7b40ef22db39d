"""The typical section's input: :class:`TypicalSection` and the checks of its numbers."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from windflutter.errors import InputError

TWO_PI = 2.0 * math.pi


def is_number(v: Any) -> bool:
    """A real number (Python or NumPy), not a bool."""
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)


def check_finite(name: str, v: Any, source: str | None = None) -> None:
    """Raise :class:`InputError` naming ``name`` unless ``v`` is a finite number."""
    if not is_number(v) or not math.isfinite(float(v)):
        raise InputError(name, v, "a finite number", source)


def check_positive(name: str, v: Any, source: str | None = None) -> None:
    """Raise :class:`InputError` naming ``name`` unless ``v`` is a positive finite number."""
    if not is_number(v) or not math.isfinite(float(v)) or float(v) <= 0.0:
        raise InputError(name, v, "a positive finite number", source)


#: the check of each numeric field, in the order they are checked
_FIELD_CHECKS = (
    ("semi_chord", check_positive),
    ("elastic_axis", check_finite),
    ("mass", check_positive),
    ("static_moment", check_finite),
    ("inertia", check_positive),
    ("plunge_stiffness", check_positive),
    ("pitch_stiffness", check_positive),
    ("air_density", check_positive),
    ("lift_slope", check_positive),
    ("plunge_angle", check_finite),
)


@dataclass(frozen=True)
class TypicalSection:
    """A 2-DOF typical section, dimensional form (SI, per unit span).

    Attributes
    ----------
    semi_chord
        b (m).
    elastic_axis
        a, elastic axis aft of mid-chord in semi-chords (-).
    mass
        m (kg/m).
    static_moment
        S = m x_alpha b (kg m / m), CG aft of the elastic axis positive.
    inertia
        I_alpha about the elastic axis (kg m^2 / m).
    plunge_stiffness
        K_h (N/m^2).
    pitch_stiffness
        K_alpha (N m / rad / m = N).
    air_density
        rho (kg/m^3).
    lift_slope
        Cla (1/rad), replaces 2 pi in the circulatory terms.
    plunge_angle
        Angle (rad) between the plunge DOF and the lift direction (0 for the classic section).
    scale_apparent_mass
        If True the non-circulatory (apparent-mass) terms are scaled by ``Cla / 2 pi`` too, as
        in the seed thesis's "viscous" variant (docs/typical_section.md, "What it does"); default
        False.
    """

    semi_chord: float
    elastic_axis: float
    mass: float
    static_moment: float
    inertia: float
    plunge_stiffness: float
    pitch_stiffness: float
    air_density: float = 1.225
    lift_slope: float = TWO_PI
    plunge_angle: float = 0.0
    scale_apparent_mass: bool = False

    def __post_init__(self) -> None:
        for name, check in _FIELD_CHECKS:
            check(name, getattr(self, name))
        if self.mass * self.inertia <= self.static_moment**2:
            raise InputError(
                "inertia",
                self.inertia,
                f"I_alpha > S^2/m = {self.static_moment**2 / self.mass:.6g} kg m^2/m "
                "(r_alpha^2 > x_alpha^2: positive-definite mass matrix)",
            )

    # nondimensional views ---------------------------------------------------------------
    @property
    def mass_ratio(self) -> float:
        """mu = m / (pi rho b^2)."""
        return self.mass / (math.pi * self.air_density * self.semi_chord**2)

    @property
    def x_alpha(self) -> float:
        """x_alpha = S / (m b)."""
        return self.static_moment / (self.mass * self.semi_chord)

    @property
    def r_alpha_squared(self) -> float:
        """r_alpha^2 = I / (m b^2)."""
        return self.inertia / (self.mass * self.semi_chord**2)

    @property
    def omega_h(self) -> float:
        """Uncoupled plunge frequency sqrt(K_h/m) (rad/s)."""
        return math.sqrt(self.plunge_stiffness / self.mass)

    @property
    def omega_alpha(self) -> float:
        """Uncoupled pitch frequency sqrt(K_alpha/I) (rad/s)."""
        return math.sqrt(self.pitch_stiffness / self.inertia)

    @classmethod
    def from_nondimensional(
        cls,
        semi_chord: float,
        elastic_axis: float,
        mass_ratio: float,
        x_alpha: float,
        r_alpha_squared: float,
        omega_h: float,
        omega_alpha: float,
        air_density: float = 1.225,
        lift_slope: float = TWO_PI,
        plunge_angle: float = 0.0,
    ) -> "TypicalSection":
        """Build from mu, x_alpha, r_alpha^2, omega_h, omega_alpha (rad/s) and b (m), rho (kg/m^3)."""
        check_positive("semi_chord", semi_chord)
        check_positive("air_density", air_density)
        check_positive("mass_ratio", mass_ratio)
        check_finite("x_alpha", x_alpha)
        check_positive("r_alpha_squared", r_alpha_squared)
        check_positive("omega_h", omega_h)
        check_positive("omega_alpha", omega_alpha)
        if r_alpha_squared <= x_alpha**2:
            raise InputError(
                "r_alpha_squared",
                r_alpha_squared,
                f"r_alpha^2 > x_alpha^2 = {x_alpha**2:.6g} (positive-definite mass matrix)",
            )
        m = mass_ratio * math.pi * air_density * semi_chord**2
        inertia = m * r_alpha_squared * semi_chord**2
        return cls(
            semi_chord=semi_chord,
            elastic_axis=elastic_axis,
            mass=m,
            static_moment=m * x_alpha * semi_chord,
            inertia=inertia,
            plunge_stiffness=m * omega_h**2,
            pitch_stiffness=inertia * omega_alpha**2,
            air_density=air_density,
            lift_slope=lift_slope,
            plunge_angle=plunge_angle,
        )
