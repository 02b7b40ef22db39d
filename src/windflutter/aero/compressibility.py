"""Where the strips' incompressible aerodynamics end: the blade's relative Mach number.

Every aerodynamic model of windflutter is incompressible: Theodorsen's and Wagner's unsteady thin
airfoil, the quasi-steady strips, and airfoil polars measured at low Mach number (wind-tunnel data at
M = 0.1-0.2).  Compressibility raises the lift slope by the Prandtl-Glauert factor
``1 / sqrt(1 - M^2)`` (Anderson, *Fundamentals of Aerodynamics*, 6th ed., sec. 11.4): 5 % at M = 0.3,
15 % at M = 0.5, 25 % at M = 0.6.  Operating turbines stay below M = 0.35 (tip speeds 80-105 m/s), but
an overspeed search reaches twice or three times the rated rotor speed: the NREL 5 MW's 40 RPM is a tip
speed of 264 m/s, M = 0.78.  Above :data:`MACH_LIMIT` a result is the model's extrapolation, and the
point says so (a :class:`~windflutter.errors.ValidityWarning` with the rotor speed, kept with the point
and shown as a caution on an onset above it, :mod:`windflutter.analysers`).
"""

from __future__ import annotations

import warnings

import numpy as np

from windflutter.errors import ValidityWarning

#: speed of sound (m/s) of the air the aerodynamics is evaluated in: the 340 m/s the windIO files of
#: the NREL 5 MW, IEA 15 MW and IEA 22 MW give (``environment.air_speed_sound``; ISA at 15 C: 340.3)
SPEED_OF_SOUND = 340.0
#: relative Mach number of the fastest strip above which the incompressible strips are noted as
#: outside their range: the Prandtl-Glauert lift slope 15 % above the incompressible one
MACH_LIMIT = 0.5


def warn_compressible(W, wind_speed: float, omega: float = float("nan")) -> None:
    """One :class:`~windflutter.errors.ValidityWarning` when the fastest of the strips' relative speeds
    ``W`` (m/s, e.g. :attr:`~windflutter.aero.induction.BEMResult.W`) is above :data:`MACH_LIMIT` times
    the speed of sound; with the wind speed (m/s) and the rotor speed ``omega`` (rad/s) it was found at."""
    w = np.asarray(W, float)
    w = w[np.isfinite(w)]
    if not w.size or float(w.max()) <= MACH_LIMIT * SPEED_OF_SOUND:
        return
    kind = (f"the blade's relative Mach number exceeds {MACH_LIMIT:g} at high rotor speed: the incompressible "
            "strips (Theodorsen, low-Mach polars) underestimate the lift slope there by more than 15 % "
            "(Prandtl-Glauert); onsets in that range are indicative")
    warnings.warn(ValidityWarning(f"at V = {wind_speed:.1f} m/s {kind}", rotor_speed_rpm=omega * 30.0 / np.pi,
                                  wind_speed=float(wind_speed), kind=kind), stacklevel=3)
