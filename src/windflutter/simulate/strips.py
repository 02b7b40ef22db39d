"""The strip force law in its nonlinear form, for the time domain.

The same definitions as the state-space strips of :mod:`windflutter.aero.unsteady` (whose
linearization about a steady state they are), evaluated at the current motion instead of
linearized.  Per strip, in the plane of its section at rest (axes: ``x`` along the chord from
the leading to the trailing edge, ``y`` normal to it, towards the suction side; pitch ``alpha``
nose-up about the elastic axis, which lies ``a b`` aft of mid-chord)::

    t = (cos alpha, -sin alpha), n = (sin alpha, cos alpha)     chord and normal, turned
    v34 = v_ea - alpha' d34 n                                  3/4-chord velocity, d34 = b (1/2 - a)
    W = V_air - v34                                            relative wind there
    alpha34 = alpha + atan2(W_y, W_x)                          its angle of attack
    z_j' = (beta_j |W| / b) (alpha34 - z_j)                    lag states of C(s) = A0 + sum c_j s/(s + beta_j)
    alpha_E = (A0 + sum c_j) alpha34 - sum c_j z_j             effective angle of attack
    q = rho |W|^2 / 2
    L = q c Cl(alpha_E)   normal to the effective inflow (at angle alpha_E - alpha), or to W
    D = q c Cd(alpha_E)   along W
    M = q c^2 Cm(alpha_E) + the moment of L and D at the quarter chord (d14 = b (a + 1/2) ahead)

With dynamic stall (``stall`` given: Oye's separation-point lag, the nonlinear form of
:mod:`windflutter.aero.unsteady`'s linearized one) one more state per strip, the separation point
``f`` (the last column of ``z``), and the lift blended between the attached and fully separated
curves of the Kirchhoff decomposition (:func:`windflutter.aero.linearization.kirchhoff_curves`:
``f_st``, ``Cl_fs``, ``Cl_att`` at ``alpha_E``)::

    f' = (f_st(alpha_E) - f) / tau,   tau = T_f b / |W|
    Cl = Cl(alpha_E) + (f - f_st(alpha_E)) (Cl_att(alpha_E) - Cl_fs(alpha_E))

which is ``f Cl_att + (1 - f) Cl_fs`` wherever the decomposition holds (``f_st < 1``) and the
polar's own ``Cl`` at every angle when ``f = f_st`` (steady state).  Linearized about a steady state
it is method p's model: the lift per ``alpha_E`` at fixed ``f`` is ``dCl/dalpha - dCl/df f_st'``,
the lift per ``f`` is ``dCl/df = Cl_att - Cl_fs`` (acting like the rest of the lift), and ``f' =
(U / (T_f b)) (f_st' alpha_E - f)``.  Drag and moment stay the polar's at ``alpha_E``.

The non-circulatory (apparent-mass) forces are linear by definition (Theodorsen): the caller
adds :func:`windflutter.aero.strip.apparent_mass` on the section's (h, alpha, s) motion.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from windflutter.aero.unsteady import SEPARATION_TIME, Circulation

__all__ = ["StripGeometry", "strip_forces", "flat_plate"]


@dataclass(frozen=True)
class StripGeometry:
    """Per strip (ns,): semi-chord ``b`` (m), elastic axis ``a`` (semi-chords aft of mid-chord),
    air density ``rho`` (kg/m^3) and the lift direction (``effective`` or ``instantaneous``)."""

    b: np.ndarray
    a: np.ndarray
    rho: float
    lift_direction: str = "effective"


def flat_plate(slope: float = 2.0 * np.pi) -> Callable:
    """``coefficients(alpha) -> (Cl, Cd, Cm)`` of the potential-flow flat plate (Cl = slope alpha)."""

    def coefficients(alpha):
        alpha = np.asarray(alpha, float)
        return slope * alpha, np.zeros_like(alpha), np.zeros_like(alpha)

    return coefficients


def strip_forces(geo: StripGeometry, circ: Circulation, coefficients: Callable, V_air, v_ea, alpha, alpha_dot, z,
                 stall: Callable | None = None, separation_time: float = SEPARATION_TIME):
    """Circulatory strip loads and lag-state rates (module docstring), vectorized over strips.

    Parameters
    ----------
    V_air : (ns, 2) air velocity in the section's rest axes (m/s).
    v_ea : (ns, 2) elastic-axis velocity, rest axes (m/s).
    alpha, alpha_dot : (ns,) pitch (rad, nose-up from rest) and its rate (rad/s).
    z : (ns, n_lag) lag states (rad); with ``stall`` (ns, n_lag + 1): the separation point last.
    coefficients : ``coefficients(alpha_E) -> (Cl, Cd, Cm)`` (ns,) each.
    stall : ``stall(alpha_E) -> (f_st, Cl_fs, Cl_att)`` (ns,) each, or None (no dynamic stall).
    separation_time : ``T_f`` of the separation lag (semi-chords travelled, ``b / |W|`` units).

    Returns
    -------
    ``(F (ns, 2) force per unit span in rest axes (N/m), M (ns,) nose-up moment about the
    elastic axis (N m/m), zdot (ns, n_lag [+ 1]), alpha_E (ns,))``.
    """
    b, a = geo.b, geo.a
    c, d34, d14 = 2.0 * b, b * (0.5 - a), b * (a + 0.5)
    ca, sa = np.cos(alpha), np.sin(alpha)
    n = np.stack([sa, ca], axis=1)
    W = np.asarray(V_air, float) - (np.asarray(v_ea, float) - (alpha_dot * d34)[:, None] * n)
    speed = np.hypot(W[:, 0], W[:, 1])
    phi = np.arctan2(W[:, 1], W[:, 0])
    a34 = alpha + phi
    nl = circ.n_lag
    rate = circ.poles[None, :] * (speed / b)[:, None]
    zdot = rate * (a34[:, None] - z[:, :nl])
    aE = circ.c_inf * a34 - z[:, :nl] @ circ.gains
    cl, cd, cm = coefficients(aE)
    if stall is not None:
        f = z[:, nl]
        f_st, cl_fs, cl_att = stall(aE)
        cl = cl + (f - f_st) * (cl_att - cl_fs)
        zdot = np.concatenate([zdot, ((f_st - f) * speed / (separation_time * b))[:, None]], axis=1)
    q = 0.5 * geo.rho * speed**2
    lift_angle = (aE - alpha) if geo.lift_direction == "effective" else phi
    e_w = W / speed[:, None]
    e_l = np.stack([-np.sin(lift_angle), np.cos(lift_angle)], axis=1)
    F = (q * c * cl)[:, None] * e_l + (q * c * cd)[:, None] * e_w
    # moment of F at the quarter chord (r = -d14 t from the elastic axis), nose-up positive
    M = d14 * (ca * F[:, 1] + sa * F[:, 0]) + q * c * c * cm
    return F, M, zdot, aE
