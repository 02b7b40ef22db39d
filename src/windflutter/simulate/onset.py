"""Confirm (or refute) an onset of method p by simulating in time just below and just above it.

What is compared, like for like, at one wind speed, pitch from the operating curve, without
structural damping or (the whole turbine) with the files' blade and tower damping in both
(``damping``), and (``part``):

* ``turbine`` (the default): the WHOLE TURBINE -- method p's operating-point model (blades,
  support, drivetrain) against its time-domain counterpart (:mod:`windflutter.simulate.turbine`);
  the eigenvalue and the identified mode are both ground-fixed (multi-blade coordinates), the
  identified mode the one nearest the eigenvalue's frequency;
* ``rotor``: the ROTOR ON A CLAMPED HUB (``model.part: rotor``) against one blade on a rigid hub
  (:func:`windflutter.simulate.blade.blade_in_wind`): on a clamped hub a blade mode's BW and FW
  eigenvalues are its rotating-frame eigenvalue shifted by ``-+ i Omega`` (same growth rate,
  frequency ``f_ground -+ Omega / 2 pi``), so the rotating-frame eigenvalue is compared.

Method p finds its first instability (rotor speed, mode); the simulation runs at ``factors`` x
that rotor speed and the growth rate of the identified mode is put beside the eigenvalue's.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.errors import InputError
from windflutter.methods import stability_analysis
from windflutter.simulate.blade import blade_in_wind
from windflutter.simulate.mode_kick import method_p_config, method_p_model
from windflutter.simulate.turbine_run import simulate_turbine
from windflutter.system.modes import point_modes
from windflutter.units import RPM

__all__ = ["OnsetCheck", "SpeedCheck", "confirm_onset"]


@dataclass(frozen=True)
class SpeedCheck:
    """One rotor speed: the eigenvalue's growth rate and damping ratio (ground-fixed for the
    turbine, rotating frame for the rotor on a clamped hub) and the
    simulation's, with its confidence (half-record spread of the growth rate, fit residual)."""

    factor: float
    rpm: float
    sigma_eig: float
    zeta_eig: float
    frequency_eig_hz: float
    sigma_sim: float
    zeta_sim: float
    frequency_sim_hz: float
    sigma_spread: float
    residual: float
    interrupted: bool
    #: times (s) and the tip node's translation (nt, 3) (m, rotating-frame global axes): for a plot
    t: np.ndarray = field(default=None, repr=False, compare=False)
    tip: np.ndarray = field(default=None, repr=False, compare=False)

    def summary(self) -> dict:
        """The numbers (no arrays), for JSON."""
        return {k: getattr(self, k) for k in ("factor", "rpm", "sigma_eig", "zeta_eig", "frequency_eig_hz",
                                               "sigma_sim", "zeta_sim", "frequency_sim_hz", "sigma_spread",
                                               "residual", "interrupted")}

    @property
    def agrees(self) -> bool:
        """Same sign of the growth rate (decay below the onset, growth above)."""
        return bool(np.sign(self.sigma_sim) == np.sign(self.sigma_eig))


@dataclass(frozen=True)
class OnsetCheck:
    wind_speed: float
    onset_rpm: float
    mode: str
    pitch_deg: float
    checks: tuple
    #: what was compared: ``turbine`` or ``rotor`` (module docstring)
    part: str = "rotor"

    @property
    def confirmed(self) -> bool:
        """Decay at every speed below the onset and growth at every one above, as the eigenvalues."""
        return all(c.agrees for c in self.checks)


def _rotating_frame(mode, omega):
    """(sigma, zeta, f_rot) of a ModeRecord on a clamped hub."""
    lam = complex(mode.eigenvalue)
    shift = {"BW": omega, "FW": -omega}.get(mode.whirl, 0.0)
    lr = complex(lam.real, abs(lam.imag) + shift)
    return lr.real, -lr.real / abs(lr), abs(lr.imag) / (2 * np.pi)


def confirm_onset(turbine, wind_speed: float, factors=(0.97, 1.03), n_span: int = 30, duration: float = 20.0,
                  f_max_hz: float = 8.0, part: str = "turbine", damping: str = "none", operating: bool = True,
                  kick: str | None = None, progress=None) -> OnsetCheck:
    """Method p's first instability at ``wind_speed`` (m/s) and the time-domain check at
    ``factors`` x its rotor speed and (``operating``) at the operating curve's rotor speed
    (module docstring; ``part``: ``turbine`` or ``rotor``; ``damping``: ``none`` or, for the
    turbine, ``file``: the files' blade and tower damping in both).  ``kick``: the turbine
    started in method p's mode of that name at each speed (``"onset"``: the unstable mode's
    name), else the default kick (:func:`windflutter.simulate.turbine_run.kick`)."""

    if part not in ("turbine", "rotor"):
        raise InputError("part", part, "turbine (the whole turbine) or rotor (one blade on a clamped hub)")
    if damping not in ("none", "file") or (damping == "file" and part != "turbine"):
        raise InputError("damping", damping, "none, or file with part turbine")
    if kick is not None and part != "turbine":
        raise InputError("kick", kick, "no mode kick with part rotor (one blade on a rigid hub)")
    cfg = method_p_config(wind_speed, n_span, part, damping)
    point = stability_analysis(turbine, cfg, "viscous", "p").analyse_operating_point(float(wind_speed))
    if point.flutter_rpm is None or not np.isfinite(point.flutter_rpm) or point.first_instability != "flutter":
        raise InputError("onset", point.first_instability, f"a flutter onset at {wind_speed:g} m/s "
                         f"(method p, model.part {part}) to confirm")
    om = method_p_model(turbine, wind_speed, n_span, part, damping)
    factors = [float(f) for f in factors]
    if operating:
        factors.insert(0, om.operating_point(float(wind_speed))[0] / RPM / float(point.flutter_rpm))
    kick = point.flutter_mode if kick == "onset" else kick
    checks = tuple(speed_check(turbine, om, point, float(wind_speed), f, part, n_span, duration, f_max_hz,
                               progress, damping, kick) for f in factors)
    return OnsetCheck(wind_speed=float(wind_speed), onset_rpm=float(point.flutter_rpm), mode=str(point.flutter_mode),
                      pitch_deg=float(point.pitch_deg), checks=checks, part=part)


def speed_check(turbine, om, point, wind_speed, factor, part, n_span, duration, f_max_hz, progress=None,
                damping="none", kick=None) -> SpeedCheck:
    """The eigenvalue of ``point.flutter_mode`` at ``factor`` x the onset and the simulation's."""

    rpm = factor * float(point.flutter_rpm)
    ps = om.at(wind_speed, rpm=rpm, pitch=np.radians(point.pitch_deg))
    modes = [m for m in point_modes(ps, max_hz=f_max_hz) if m.name == point.flutter_mode]
    if not modes:
        raise InputError("flutter_mode", point.flutter_mode, f"the mode found again at {rpm:.3f} RPM")
    if part == "rotor":
        s_e, z_e, f_e = _rotating_frame(modes[0], rpm * RPM)
        run = blade_in_wind(turbine, wind_speed, rpm, duration=duration, pitch_deg=point.pitch_deg, n_span=n_span,
                            f_max_hz=f_max_hz, progress=progress)
        tip = run.trajectory.y[:, -6:-3]
    else:
        lam = complex(modes[0].eigenvalue)
        s_e, z_e, f_e = lam.real, -lam.real / abs(lam), abs(lam.imag) / (2 * np.pi)
        run = simulate_turbine(turbine, rpm, wind_speed, duration=duration, pitch_deg=point.pitch_deg, n_span=n_span,
                               f_max_hz=f_max_hz, damping=damping, kick_mode=kick, progress=progress)
        nr = 6 * len(run.nodes)
        tip = run.trajectory.y[:, 6 + nr - 6: 6 + nr - 3]  # blade 1's tip, its own frame
    m = min(run.modes, key=lambda x: abs(x.frequency_hz - f_e))
    return SpeedCheck(factor=float(factor), rpm=rpm, sigma_eig=s_e, zeta_eig=z_e, frequency_eig_hz=f_e,
                      sigma_sim=m.sigma, zeta_sim=m.zeta, frequency_sim_hz=m.frequency_hz, sigma_spread=m.sigma_spread,
                      residual=run.identification.residual, interrupted=run.trajectory.interrupted,
                      t=run.trajectory.t, tip=tip)
