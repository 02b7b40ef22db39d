"""The simulation entry point behind ``windflutter simulate`` (and its Python API).

What is simulated (``part``):

* ``turbine`` (the default): the WHOLE TURBINE -- the N co-rotational beam blades, each in its own
  frame turning with the rotor and carried by the hub, on the support (tower beams, nacelle mass,
  hub node: linear, about its static deflection under the mean rotor loads) and the drivetrain
  (rotor azimuth, shaft spring and damper, generator inertia; the generator torque held at the
  steady aerodynamic torque), in vacuum or in the wind along the shaft
  (:mod:`windflutter.simulate.turbine`): method p's operating-point model, integrated in time;
* ``blade``: ONE blade on a rigid hub at constant rotor speed (no BW/FW whirl, no tower motion;
  the blade's modes are the rotating-frame ones: on a rigid hub the eigen-solver's BW/FW pair of
  a blade mode sits at ``f -+ Omega / 2 pi``).

Both: co-rotational beams (the blades' own motion kept whole; the hub's small motion to first
order in the blades' kinematics), strip aerodynamics with lag states (Jones' or the Roger fit's)
and the BEM induction of the steady state frozen; with ``dynamic_stall``, Oye's separation point
per strip on the Kirchhoff decomposition of its polar (the nonlinear form of method p's
``solver.dynamic_stall``, :mod:`windflutter.simulate.strips`).  Structural damping: none, or (the
turbine) the files' blade and tower damping as method p defines it.  Not included: gravity,
dynamic inflow, a controller.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.simulate.blade import blade_in_vacuum, blade_in_wind
from windflutter.simulate.turbine_run import simulate_turbine

__all__ = ["simulate", "INCLUDED", "included"]

#: one line on what each simulation holds (printed by the CLI), up to what it leaves out
INCLUDED = {
    "turbine": ("the whole turbine: co-rotational beam blades in frames turning with the hub, the tower and "
                "nacelle (linear beams) and the drivetrain (shaft spring, generator inertia, constant generator "
                "torque); strip aerodynamics with lag states and frozen BEM induction"),
    "blade": ("one blade on a rigid hub at constant rotor speed (co-rotational beam, spinning frame); "
              "strip aerodynamics with lag states and frozen BEM induction"),
}
#: what each simulation leaves out, besides structural damping unless it runs with the files'
LEFT_OUT = {"turbine": ("gravity", "dynamic inflow"),
            "blade": ("tower", "drivetrain", "other blades", "gravity", "dynamic inflow")}


def included(part: str, damping: str = "none", dynamic_stall: bool = False) -> str:
    """The line on what the simulation of ``part`` holds and leaves out, with the structural damping
    it runs with (``file``: the turbine files' blade and tower damping) and dynamic stall if on."""
    out = list(LEFT_OUT[part]) + (["structural damping"] if damping != "file" else [])
    line = f"{INCLUDED[part]}; no {', '.join(out[:-1])} or {out[-1]}"
    line += "; with the turbine files' structural damping" if damping == "file" else ""
    return line + ("; with Oye's dynamic stall (separation-point lag)" if dynamic_stall else "")


def simulate(turbine, rpm: float, wind_speed: float = 0.0, *, duration: float = 20.0, pitch_deg: float | None = None,
             n_span: int = 30, f_max_hz: float = 8.0, points_per_period: float = 30.0, rho_inf: float = 0.9,
             amplitude: float | None = None, circulation: str = "jones", air_density: float = 1.225,
             part: str = "turbine", damping: str = "none", kick: str | None = None, progress=None,
             dynamic_stall: bool = False):
    """Free response of a turbine's blade (module docstring) kicked by impulses, and the
    frequency and damping of its modes identified from it.

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.turbine.Turbine` (beam blade data).
    rpm : rotor speed (rev/min).  wind_speed : m/s; 0 = in vacuum.
    duration : simulated time (s).  pitch_deg : blade pitch (deg); default the operating curve's.
    n_span : blade elements.  f_max_hz : highest frequency retained: the step gives
        ``points_per_period`` steps in its period.  rho_inf : generalized-alpha spectral radius.
    amplitude : size of the kick (m): the turbine's blade 1 deflection (default 1e-2), the blade's
        largest initial velocity (m/s, rad/s; default 1e-3).  circulation : ``jones`` | ``rfa``.
    part : ``turbine`` | ``blade`` (module docstring).  damping : ``none`` | ``file`` (the turbine
        files' blade and tower damping, ``part="turbine"``).  kick : the name of one of method p's
        modes at the point (``"1st edge BW"``; ``part="turbine"``): the run starts in that mode,
        its largest translation ``amplitude`` (:mod:`windflutter.simulate.mode_kick`); None: the
        default kick (unit loads at blade 1's recorded nodes and the tower top).
        progress : ``progress(step, n_steps, t)``.  dynamic_stall : Oye's separation-point lag
        per strip (in the wind; method p's ``solver.dynamic_stall``, its ``T_f = 6``).

    Returns
    -------
    :class:`~windflutter.simulate.turbine_run.TurbineRun` or
    :class:`~windflutter.simulate.blade.BladeRun`; Ctrl-C keeps what was integrated
    (``trajectory.interrupted``) and identifies from it.
    """
    for name, v, lo in (("rpm", rpm, 0.0), ("wind_speed", wind_speed, 0.0)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v < lo:
            raise InputError(name, v, "a non-negative number")
    if part not in INCLUDED:
        raise InputError("part", part, "turbine or blade")
    if amplitude is None:
        amplitude = 1e-2 if part == "turbine" else 1e-3
    for name, v in (("duration", duration), ("f_max_hz", f_max_hz), ("amplitude", amplitude)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v <= 0:
            raise InputError(name, v, "a positive number")
    if isinstance(n_span, bool) or not isinstance(n_span, (int, np.integer)) or not 2 <= n_span <= 200:
        raise InputError("n_span", n_span, "an integer in [2, 200] (blade elements)")
    if circulation not in ("jones", "rfa"):
        raise InputError("circulation", circulation, "jones or rfa")
    if damping not in ("none", "file") or (damping == "file" and part != "turbine"):
        raise InputError("damping", damping, "none, or file with part turbine")
    if kick is not None and (part != "turbine" or not isinstance(kick, str) or not kick.strip()):
        raise InputError("kick", kick, "the name of one of method p's modes, with part turbine")
    if not isinstance(dynamic_stall, (bool, np.bool_)):
        raise InputError("dynamic_stall", dynamic_stall, "true or false")
    if dynamic_stall and wind_speed == 0.0:
        raise InputError("dynamic_stall", True, "a wind speed above 0 (the strips' separation points)")
    if wind_speed > 0.0 and rpm == 0.0:
        raise InputError("rpm", rpm, "a positive rotor speed in the wind")
    if part == "turbine":

        return simulate_turbine(turbine, rpm, wind_speed, duration=duration, pitch_deg=pitch_deg, n_span=int(n_span),
                                f_max_hz=f_max_hz, points_per_period=points_per_period, rho_inf=rho_inf,
                                amplitude=amplitude, circulation=circulation, air_density=air_density,
                                damping=damping, kick_mode=kick, progress=progress, dynamic_stall=dynamic_stall)
    if wind_speed == 0.0:
        return blade_in_vacuum(turbine, rpm, duration=duration, n_span=int(n_span), f_max_hz=f_max_hz,
                               points_per_period=points_per_period, rho_inf=rho_inf, amplitude=amplitude,
                               progress=progress)
    return blade_in_wind(turbine, wind_speed, rpm, duration=duration, pitch_deg=pitch_deg, n_span=int(n_span),
                         f_max_hz=f_max_hz, points_per_period=points_per_period, rho_inf=rho_inf,
                         amplitude=amplitude, circulation=circulation, air_density=air_density, progress=progress,
                         dynamic_stall=dynamic_stall)
