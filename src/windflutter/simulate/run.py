"""The simulation entry point behind ``windflutter simulate`` (and its Python API).

What is simulated: ONE blade of the turbine on a rigid hub spinning at a constant rotor speed
(co-rotational beam blade in the spinning frame, clamped at the root), in vacuum or in the wind
along the shaft with the strip aerodynamics (Jones' or the Roger fit's lag states) and the BEM
induction of the steady state frozen.  Not included (yet): the other blades, the hub, the
drivetrain and the tower (so no whirling BW/FW modes and no tower motion), gravity, dynamic
inflow, dynamic stall, structural damping.  The blade's modes are the rotating-frame ones: on a
rigid hub the eigen-solver's BW/FW pair of a blade mode sits at ``f -+ Omega / 2 pi``.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.simulate.blade import BladeRun, blade_in_vacuum, blade_in_wind

__all__ = ["simulate", "INCLUDED"]

#: one line on what the simulation holds (printed by the CLI)
INCLUDED = ("one blade on a rigid hub at constant rotor speed (co-rotational beam, spinning frame); "
            "strip aerodynamics with lag states and frozen BEM induction; no tower, drivetrain, other "
            "blades, gravity, dynamic inflow or structural damping")


def simulate(turbine, rpm: float, wind_speed: float = 0.0, *, duration: float = 20.0, pitch_deg: float | None = None,
             n_span: int = 30, f_max_hz: float = 8.0, points_per_period: float = 30.0, rho_inf: float = 0.9,
             amplitude: float = 1e-3, circulation: str = "jones", air_density: float = 1.225,
             progress=None) -> BladeRun:
    """Free response of a turbine's blade (module docstring) kicked by impulses, and the
    frequency and damping of its modes identified from it.

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.turbine.Turbine` (beam blade data).
    rpm : rotor speed (rev/min).  wind_speed : m/s; 0 = in vacuum.
    duration : simulated time (s).  pitch_deg : blade pitch (deg); default the operating curve's.
    n_span : blade elements.  f_max_hz : highest frequency retained: the step gives
        ``points_per_period`` steps in its period.  rho_inf : generalized-alpha spectral radius.
    amplitude : largest initial velocity of the kick (m/s, rad/s).  circulation : ``jones`` | ``rfa``.
    progress : ``progress(step, n_steps, t)``.

    Returns
    -------
    :class:`~windflutter.simulate.blade.BladeRun`; Ctrl-C keeps what was integrated
    (``trajectory.interrupted``) and identifies from it.
    """
    for name, v, lo in (("rpm", rpm, 0.0), ("wind_speed", wind_speed, 0.0)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v < lo:
            raise InputError(name, v, "a non-negative number")
    for name, v in (("duration", duration), ("f_max_hz", f_max_hz), ("amplitude", amplitude)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v <= 0:
            raise InputError(name, v, "a positive number")
    if isinstance(n_span, bool) or not isinstance(n_span, (int, np.integer)) or not 2 <= n_span <= 200:
        raise InputError("n_span", n_span, "an integer in [2, 200] (blade elements)")
    if circulation not in ("jones", "rfa"):
        raise InputError("circulation", circulation, "jones or rfa")
    if wind_speed == 0.0:
        return blade_in_vacuum(turbine, rpm, duration=duration, n_span=int(n_span), f_max_hz=f_max_hz,
                               points_per_period=points_per_period, rho_inf=rho_inf, amplitude=amplitude,
                               progress=progress)
    if rpm == 0.0:
        raise InputError("rpm", rpm, "a positive rotor speed in the wind")
    return blade_in_wind(turbine, wind_speed, rpm, duration=duration, pitch_deg=pitch_deg, n_span=int(n_span),
                         f_max_hz=f_max_hz, points_per_period=points_per_period, rho_inf=rho_inf,
                         amplitude=amplitude, circulation=circulation, air_density=air_density, progress=progress)
