"""Steady blade-element momentum (BEM) induction of a rotor, strip by strip.

The thesis (and the default solver) lets every strip see ``U = sqrt(V^2 + (Omega r)^2)``: the
rotor does not slow the wind down.  This module computes the steady axial and tangential
induction factors ``a`` and ``a'`` of each strip so that the inflow can be

    ``U = sqrt((V (1 - a))^2 + (Omega r (1 + a'))^2)``,  ``phi = atan2(V (1 - a), Omega r (1 + a'))``

(:func:`windflutter.aero.flow.section_flow` with ``OperatingPoint.induction``).

Method (annular momentum balance = blade-element loads, one annulus per strip):

* blade element: ``alpha = phi - theta`` (``theta`` = local twist + pitch, nose-down positive),
  ``Cl, Cd`` from the strip's static polar, ``cn = Cl cos phi + Cd sin phi`` (normal to the rotor
  plane), ``ct = Cl sin phi - Cd cos phi`` (in the plane, driving);
* ``k = sigma' cn / (4 F sin^2 phi)``, ``k' = sigma' ct / (4 F sin phi cos phi)`` with the local
  solidity ``sigma' = B c / (2 pi r)``;
* axial: by the thrust--induction relation ``high_thrust`` (:mod:`windflutter.aero.momentum`):
  by default momentum ``a = k / (1 + k)`` while ``a <= 0.4`` (``k <= 2/3``) and Buhl's (2005)
  empirical thrust ``C_T = 8/9 + (4F - 40/9) a + (50/9 - 4F) a^2`` above (equal to the momentum
  ``4 F a (1 - a)`` in value and slope at ``a = 0.4``), solved for ``a`` in the stable form
  :func:`~windflutter.aero.momentum.buhl_axial`; or HAWC2's cubic ``a(C_T)`` (Madsen et al.
  2020); tangential ``a' = k' / (1 - k')``;
* Prandtl's tip and hub loss ``F = F_tip F_hub``,
  ``F_tip = 2/pi acos(exp(-B (R - r) / (2 r sin phi)))``,
  ``F_hub = 2/pi acos(exp(-B (r - R_hub) / (2 R_hub sin phi)))``;
* one unknown per strip, the inflow angle ``phi``, root of
  ``R(phi) = sin(phi) / (1 - a) - cos(phi) (1 - k') / lambda_r`` (``lambda_r = Omega r / V``),
  the formulation of Ning (2014, Wind Energy 17, "A simple solution method for the blade element
  momentum equations with guaranteed convergence"): a sign change of ``R`` is bracketed in
  ``(0, pi/2]`` (windmill state), else ``(pi/2, pi)`` or ``[-pi/4, 0)`` (propeller brake,
  ``a = k / (k - 1)``), and the root is found by vectorized bisection across all strips.

What is frozen (linear stability): the induction is the **steady, quasi-steady** state of the
undeformed rotor at the operating point (V, Omega, pitch).  The stability problem linearizes
about it with ``a`` and ``a'`` held fixed: no dynamic inflow (the wake does not respond to the
blade vibration; Theodorsen's ``C(k)`` remains the only unsteady aerodynamics), no feedback of
the static deflection on the loads, axisymmetric inflow (no shear, yaw or tower shadow; tilt and
precone only enter through the normal wind component and the strip geometry).

Units: SI (m, s, rad, kg/m^3, N, N m, W).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from windflutter.aero.compressibility import warn_compressible
from windflutter.aero.flow import OperatingPoint, section_flow
from windflutter.aero.momentum import axial_from_k, buhl_axial, high_thrust_model
from windflutter.aero.sections import AeroSections, Polar, RotorGeometry
from windflutter.errors import InputError, ValidityWarning

__all__ = ["BEMResult", "prandtl_factor", "buhl_axial", "axial_from_k", "bem_induction",
           "sections_induction", "theta_from_geometry", "rotor_extent"]

_PHI_EPS = 1e-7  # rad, bracket end close to phi = 0


@dataclass(frozen=True)
class BEMResult:
    """Steady BEM state (arrays over the elements, rotor totals as floats).

    Attributes
    ----------
    a, ap : axial and tangential induction factors (-).
    phi : inflow angle from the rotor plane (rad).  alpha : angle of attack (rad).
    cl, cd : lift and drag coefficients at ``alpha`` (-).  F : Prandtl loss factor (-).
    W : relative speed (m/s).
    fn, ft : normal (thrust) and tangential (driving) force per unit span (N/m).
    converged : (n,) bool, a bracketed root was found (False: no induction, ``a = a' = 0``).
    thrust (N), torque (N m), power (W), cp, ct (-) : rotor totals (``n_blades`` blades).
    tsr : tip-speed ratio ``Omega R / V`` (-).
    """

    a: np.ndarray
    ap: np.ndarray
    phi: np.ndarray
    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    F: np.ndarray
    W: np.ndarray
    fn: np.ndarray
    ft: np.ndarray
    converged: np.ndarray
    thrust: float
    torque: float
    power: float
    cp: float
    ct: float
    tsr: float


def prandtl_factor(r, phi, n_blades: int, r_tip: float, r_hub: float | None = None,
                   tip: bool = True, hub: bool = True) -> np.ndarray:
    """Prandtl tip and hub loss ``F = F_tip F_hub`` (-), vectorized.

    Parameters
    ----------
    r : radius (m).  phi : inflow angle (rad).  n_blades : B.  r_tip, r_hub : tip and hub radius (m).
    tip, hub : include the tip / hub factor.

    ``F_tip = 2/pi acos(exp(-B (R - r) / (2 r |sin phi|)))`` and the hub analogue with
    ``(r - R_hub) / (2 R_hub |sin phi|)``; ``F -> 1`` far from both ends, ``F -> 0`` at them.
    """
    r = np.asarray(r, float)
    s = np.abs(np.sin(np.asarray(phi, float)))
    s = np.maximum(s, 1e-12)
    F = np.ones(np.broadcast(r, s).shape)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        if tip:
            f = 0.5 * n_blades * np.maximum(r_tip - r, 0.0) / (np.maximum(r, 1e-12) * s)
            F = F * (2.0 / np.pi) * np.arccos(np.clip(np.exp(-f), 0.0, 1.0))
        if hub and r_hub is not None and r_hub > 0:
            f = 0.5 * n_blades * np.maximum(r - r_hub, 0.0) / (r_hub * s)
            F = F * (2.0 / np.pi) * np.arccos(np.clip(np.exp(-f), 0.0, 1.0))
    return F


class _PolarTable:
    """Static Cl, Cd of every element from its polar (linear interpolation, alpha wrapped to +-pi).

    The polars are resampled once onto the union of their angle grids (so each one's piecewise-
    linear curve is unchanged) and every call interpolates all elements at once: one search in the
    common grid and a gather of the two bracketing table entries of each element's own polar.
    """

    def __init__(self, polars: list[Polar], index):
        self.index = np.asarray(index, dtype=np.int64)
        used = np.unique(self.index)
        grid = np.unique(np.concatenate([np.asarray(polars[int(p)].alpha, float) for p in used]))
        self.grid = grid
        rows = np.zeros(int(used.max()) + 1 if used.size else 1, dtype=np.int64)
        rows[used] = np.arange(used.size)
        self.row = rows[self.index]
        self.cl = np.stack([np.interp(grid, polars[int(p)].alpha, polars[int(p)].cl) for p in used])
        self.cd = np.stack([np.interp(grid, polars[int(p)].alpha, polars[int(p)].cd) for p in used])

    def __call__(self, alpha: np.ndarray, sel: np.ndarray | None = None):
        al = np.mod(np.asarray(alpha, float) + np.pi, 2 * np.pi) - np.pi
        row = self.row if sel is None else self.row[sel]
        g = self.grid
        if g.size == 1:
            return self.cl[row, 0] + 0 * al, self.cd[row, 0] + 0 * al
        x = np.clip(al, g[0], g[-1])  # constant beyond the tables, as np.interp
        j = np.clip(np.searchsorted(g, x, side="right") - 1, 0, g.size - 2)
        t = (x - g[j]) / (g[j + 1] - g[j])
        cl = self.cl[row, j] * (1.0 - t) + self.cl[row, j + 1] * t
        cd = self.cd[row, j] * (1.0 - t) + self.cd[row, j + 1] * t
        return cl, cd


def _state(phi, sel, r, chord, theta, lam, sig, polar, n_blades, r_tip, r_hub, tip, hub, high_thrust):
    """Residual and induction at inflow angles ``phi`` of the elements ``sel``."""
    alpha = phi - theta[sel]
    cl, cd = polar(alpha, sel)
    sp_, cp_ = np.sin(phi), np.cos(phi)
    cn = cl * cp_ + cd * sp_
    ctn = cl * sp_ - cd * cp_
    F = prandtl_factor(r[sel], phi, n_blades, r_tip, r_hub, tip, hub)
    F = np.maximum(F, 1e-12)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        k = sig[sel] * cn / (4.0 * F * sp_**2)
        kp = sig[sel] * ctn / (4.0 * F * sp_ * cp_)
        brake = phi < 0
        a = np.where(brake, np.where(k > 1.0, k / (k - 1.0), np.nan), axial_from_k(k, F, high_thrust))
        # cos(phi) (1 - k') written without the 1 / cos(phi) of k' (finite at phi = pi/2)
        res = sp_ / (1.0 - a) - (cp_ - sig[sel] * ctn / (4.0 * F * sp_)) / lam[sel]
        ap = kp / (1.0 - kp)
    return res, a, ap, alpha, cl, cd, F


def bem_induction(r, chord, theta, polars: list[Polar], airfoil, wind_speed: float, omega: float,
                  n_blades: int, r_tip: float, r_hub: float = 0.0, dr=None, air_density: float = 1.225,
                  tip_loss: bool = True, hub_loss: bool = True, high_thrust="buhl",
                  xtol: float = 1e-12, normal_factor=None) -> BEMResult:
    """Steady BEM induction of every element (vectorized across elements).

    Parameters
    ----------
    r : (n,) radius from the shaft axis (m).  chord : (n,) chord (m).
    theta : (n,) local blade angle twist + pitch (rad, nose-down / towards feather positive):
        ``alpha = phi - theta``.
    polars : static polars; ``airfoil`` : (n,) index of each element's polar.
    wind_speed : wind speed normal to the rotor plane (m/s).  omega : rotor speed (rad/s; sign
        ignored).  n_blades : B.  r_tip, r_hub : tip and hub radius (m) for the Prandtl factors
        and the rotor area ``pi r_tip^2``.
    dr : (n,) radial length each element stands for in the rotor totals (m); for the elements of
        one blade its strip widths, for the elements of all B blades the widths / B.  None: no
        totals (zeros).
    air_density : kg/m^3.  tip_loss, hub_loss : corrections on/off.
    high_thrust : the thrust--induction relation, ``"buhl"`` (default), ``"madsen"`` (HAWC2's) or
        ``"momentum"`` (:mod:`windflutter.aero.momentum`; True / False: buhl / momentum).
    xtol : bisection tolerance on ``phi`` (rad).
    normal_factor : optional (n,) fraction in (0, 1] of the normal wind that each element sees in
        its own plane, the cosine of its local cone angle (coned BEM: ``V_j = V cos gamma_j`` in
        the velocity triangle, induction relative to ``V_j``); None: 1 (the rotor-plane BEM).
        The totals stay normalized with ``wind_speed``.

    Returns
    -------
    BEMResult.  With ``V = 0`` or ``Omega = 0`` there is no momentum balance to solve: ``a = a' = 0``
    and ``phi = atan2(V, Omega r)`` (the uninduced inflow).  Elements without a bracketed root
    (e.g. no lift) also get ``a = a' = 0`` and ``converged = False``.
    """
    r, chord, theta, idx, V, Om, Vj = _checked_bem_inputs(r, chord, theta, polars, airfoil, wind_speed, omega,
                                                          n_blades, r_tip, normal_factor)
    polar = _PolarTable(polars, idx)
    phi, a, ap, conv = _solve_inflow(r, chord, theta, polar, Vj, Om, V, n_blades, r_tip, r_hub,
                                     (tip_loss, hub_loss, high_thrust_model(high_thrust)), xtol)
    alpha = phi - theta
    cl, cd = polar(alpha)
    F = prandtl_factor(r, phi, n_blades, r_tip, r_hub, tip_loss, hub_loss)
    W = np.hypot(Vj * (1.0 - a), Om * r * (1.0 + ap))
    q = 0.5 * air_density * W**2 * chord
    fn = q * (cl * np.cos(phi) + cd * np.sin(phi))
    ft = q * (cl * np.sin(phi) - cd * np.cos(phi))
    T, Q, P, cp, ct, tsr = _rotor_totals(fn, ft, r, dr, V, Om, n_blades, r_tip, air_density)
    return BEMResult(a=a, ap=ap, phi=phi, alpha=alpha, cl=cl, cd=cd, F=F, W=W, fn=fn, ft=ft, converged=conv,
                     thrust=T, torque=Q, power=P, cp=float(cp), ct=float(ct), tsr=float(tsr))


def _checked_bem_inputs(r, chord, theta, polars, airfoil, wind_speed, omega, n_blades, r_tip, normal_factor):
    """Validated, broadcast inputs of :func:`bem_induction` (same meaning and units).

    Returns
    -------
    r, chord, theta : (n,) radius (m), chord (m), blade angle (rad).  idx : (n,) polar indices.
    V : wind speed (m/s).  Om : ``|omega|`` (rad/s).  Vj : (n,) normal wind of each element
    (m/s), ``V`` times its ``normal_factor``.

    Raises InputError on a negative or non-finite speed, a bad blade count, radii outside
    ``(0, r_tip]``, negative chords, polar indices out of range or a factor outside (0, 1].
    """
    r = np.atleast_1d(np.asarray(r, float))
    n = r.size
    chord = np.broadcast_to(np.asarray(chord, float), (n,))
    theta = np.broadcast_to(np.asarray(theta, float), (n,))
    idx = np.broadcast_to(np.asarray(airfoil, dtype=np.int64), (n,))
    V = float(wind_speed)
    Om = abs(float(omega))
    if not (np.isfinite(V) and V >= 0):
        raise InputError("wind_speed", wind_speed, "a non-negative speed (m/s)")
    if not np.isfinite(Om):
        raise InputError("omega", omega, "a finite rotor speed (rad/s)")
    if not (isinstance(n_blades, (int, np.integer)) and n_blades >= 1):
        raise InputError("n_blades", n_blades, "a positive number of blades")
    if not (np.isfinite(r_tip) and r_tip > 0 and np.all(r > 0) and np.all(r <= r_tip * (1 + 1e-9))):
        raise InputError("r_tip", r_tip, f"a tip radius >= every element radius (max {r.max():.4g} m) and > 0")
    if not (np.all(chord >= 0) and np.all(np.isfinite(chord))):
        raise InputError("chord", "negative or non-finite", "chords >= 0 (m)")
    if len(polars) == 0 or idx.min() < 0 or idx.max() >= len(polars):
        raise InputError("airfoil", (int(idx.min()), int(idx.max())) if n else (), f"indices into {len(polars)} polars")
    Vj = np.full(n, V)
    if normal_factor is not None:
        nf = np.broadcast_to(np.asarray(normal_factor, float), (n,))
        if not np.all((nf > 0) & (nf <= 1 + 1e-12)):
            raise InputError("normal_factor", "outside (0, 1]", "cosines of the local cone angles in (0, 1]")
        Vj = V * nf
    return r, chord, theta, idx, V, Om, Vj


def _solve_inflow(r, chord, theta, polar, Vj, Om, V, n_blades, r_tip, r_hub, flags, xtol):
    """Inflow angle and induction of every element: the root of the BEM residual per bracket.

    Parameters
    ----------
    r, chord, theta : (n,) radius (m), chord (m), blade angle (rad).  polar : :class:`_PolarTable`.
    Vj : (n,) normal wind of each element (m/s).  Om : rotor speed (rad/s, >= 0).  V : wind (m/s).
    n_blades, r_tip (m), r_hub (m) : as :func:`bem_induction`.
    flags : (tip_loss, hub_loss, high_thrust).  xtol : bisection tolerance on ``phi`` (rad).

    Returns
    -------
    phi (rad), a, ap (-), conv : (n,) arrays; the windmill bracket ``(0, pi/2]`` is tried first,
    then ``(pi/2, pi)``, then ``[-pi/4, 0)``; elements without a root keep the uninduced
    ``phi = atan2(V_j, Omega r)``, ``a = a' = 0`` and ``conv = False``.
    """
    n = r.size
    a = np.zeros(n)
    ap = np.zeros(n)
    phi = np.arctan2(Vj, Om * r)
    conv = np.zeros(n, bool)
    if V > 0 and Om > 0:
        lam = Om * r / Vj
        sig = n_blades * chord / (2.0 * np.pi * r)
        args = (r, chord, theta, lam, sig, polar, n_blades, r_tip, r_hub, *flags)
        todo = np.ones(n, bool)
        for lo_, hi_ in ((_PHI_EPS, 0.5 * np.pi), (0.5 * np.pi, np.pi - _PHI_EPS), (-0.25 * np.pi, -_PHI_EPS)):
            sel = np.flatnonzero(todo)
            if sel.size == 0:
                break
            found = _bisect_bracket(lo_, hi_, sel, args, xtol)
            if found is None:
                continue
            sel, ph, aa, aap = found
            phi[sel], a[sel], ap[sel] = ph, aa, aap
            conv[sel] = True
            todo[sel] = False
    return phi, a, ap, conv


def _bisect_bracket(lo_: float, hi_: float, sel: np.ndarray, args: tuple, xtol: float):
    """Vectorized bisection of the residual of :func:`_state` on ``[lo_, hi_]`` (rad).

    Parameters
    ----------
    lo_, hi_ : bracket ends (rad).  sel : indices of the elements still unsolved.
    args : the arguments of :func:`_state` after ``phi, sel``.  xtol : tolerance on ``phi`` (rad).

    Returns
    -------
    None if no element has a sign change in the bracket, else ``(sel, phi, a, ap)`` of the
    elements whose root gives finite inductions: indices, inflow angle (rad), ``a``, ``a'`` (-).
    """
    lo = np.full(sel.size, lo_)
    hi = np.full(sel.size, hi_)
    flo = _state(lo, sel, *args)[0]
    fhi = _state(hi, sel, *args)[0]
    ok = np.isfinite(flo) & np.isfinite(fhi) & (flo * fhi <= 0)
    if not np.any(ok):
        return None
    sel, lo, hi, flo = sel[ok], lo[ok], hi[ok], flo[ok]
    n_it = int(np.ceil(np.log2(max(hi_ - lo_, xtol) / xtol))) + 1
    for _ in range(n_it):
        mid = 0.5 * (lo + hi)
        fm = _state(mid, sel, *args)[0]
        left = (fm * flo <= 0) | ~np.isfinite(fm)
        hi = np.where(left, mid, hi)
        lo = np.where(left, lo, mid)
        flo = np.where(left, flo, fm)
    ph = 0.5 * (lo + hi)
    _, aa, aap, *_ = _state(ph, sel, *args)
    good = np.isfinite(aa) & np.isfinite(aap)
    return sel[good], ph[good], aa[good], aap[good]


def _rotor_totals(fn, ft, r, dr, V, Om, n_blades, r_tip, air_density):
    """Rotor thrust (N), torque (N m), power (W), cp, ct (-) and tip-speed ratio (-).

    Parameters
    ----------
    fn, ft : (n,) normal and tangential force per unit span (N/m).  r : (n,) radius (m).
    dr : (n,) radial length of each element (m), or None (totals zero).  V : wind (m/s).
    Om : rotor speed (rad/s, >= 0).  n_blades : B.  r_tip : tip radius (m).  air_density : kg/m^3.

    With ``V = 0``: ``cp = ct = nan`` and ``tsr = inf``.
    """
    n = r.size
    if dr is None:
        T = Q = 0.0
    else:
        dr = np.broadcast_to(np.asarray(dr, float), (n,))
        T = float(n_blades * np.sum(fn * dr))
        Q = float(n_blades * np.sum(ft * r * dr))
    P = Om * Q
    area = np.pi * r_tip**2
    qV = 0.5 * air_density * area * V**2
    cp = P / (qV * V) if V > 0 else float("nan")
    ct = T / qV if V > 0 else float("nan")
    tsr = Om * r_tip / V if V > 0 else float("inf")
    return T, Q, P, cp, ct, tsr


def theta_from_geometry(sections: AeroSections, rotor: RotorGeometry, pitch: float = 0.0) -> np.ndarray:
    """Local blade angle twist + pitch (rad) of every strip, read from its chord direction.

    The strip's angle of attack in a purely rotational inflow (``V = 0``) is ``-theta``, so
    ``theta = -alpha(V=0, Omega=1)`` of :func:`windflutter.aero.flow.section_flow`; this holds the
    pitch and twist the mesh already put into ``e_chord`` (plus the extra ``pitch``).
    """
    op = OperatingPoint(wind_speed=0.0, omega=1.0, rotor=rotor, pitch=pitch)
    return -section_flow(sections, op).alpha


def rotor_extent(sections: AeroSections, rotor: RotorGeometry) -> tuple[float, float, np.ndarray]:
    """``(r_hub, r_tip, dr)``: radial extent of the strips (m) and each strip's radial width (m).

    The width is projected on the plane normal to the shaft (precone), ``r_tip`` is the largest
    outer strip edge and ``r_hub`` the smallest inner edge.
    """
    axis = np.asarray(rotor.shaft_axis, float)
    axis = axis / np.linalg.norm(axis)
    span = np.asarray(sections.e_span, float)
    span = span / np.linalg.norm(span, axis=1, keepdims=True)
    radial = np.sqrt(np.maximum(1.0 - (span @ axis) ** 2, 0.0))
    dr = np.asarray(sections.width, float) * radial
    r = np.asarray(sections.radius, float)
    return float(np.min(r - 0.5 * dr)), float(np.max(r + 0.5 * dr)), dr


def sections_induction(sections: AeroSections, rotor: RotorGeometry, wind_speed: float, omega: float,
                       n_blades: int | None = None, pitch: float = 0.0, air_density: float = 1.225,
                       cone: bool = False, warn: bool = True, **kw) -> BEMResult:
    """:func:`bem_induction` for the strips of a built model (every strip of every blade).

    Parameters
    ----------
    sections : the model's strips; ``rotor`` : its geometry.  wind_speed (m/s), omega (rad/s).
    n_blades : blades of the rotor (None: the blades present in ``sections``; give it for a
        one-blade model of a B-bladed rotor).  pitch : extra pitch on top of ``e_chord`` (rad).
    air_density : kg/m^3.  kw : passed to :func:`bem_induction` (corrections, tolerance).
    cone : each strip sees the normal wind projected on its own plane, ``V cos gamma_j`` with the
        local cone angle ``sin gamma_j = e_span . shaft`` (``normal_factor`` of
        :func:`bem_induction`; the coned BEM of a deflected blade); False (default): ``V``.
    warn : warn when the result leaves momentum theory (:func:`warn_outside_momentum_theory`) or its
        fastest strip the incompressible range (:func:`~windflutter.aero.compressibility.warn_compressible`);
        False for a caller that warns when it uses the result (a cache).

    The wind component normal to the rotor plane, ``V |wind . shaft|``, drives the momentum
    balance (shaft tilt); radii, radial widths and tip/hub radius come from the strip geometry
    (:func:`rotor_extent`), ``theta`` from :func:`theta_from_geometry`.  The totals count each
    blade present once, scaled to ``n_blades``.
    """
    if rotor is None:
        raise InputError("rotor", None, "a RotorGeometry for the BEM induction")
    present = int(np.unique(np.asarray(sections.blade)).size)
    B = present if n_blades is None else n_blades
    if not (isinstance(B, (int, np.integer)) and B >= 1):
        raise InputError("n_blades", n_blades, "a positive number of blades")
    if not (np.isfinite(wind_speed) and wind_speed >= 0):
        raise InputError("wind_speed", float(wind_speed), "a non-negative speed (m/s)")
    wind = np.asarray(rotor.wind_direction, float)
    axis = np.asarray(rotor.shaft_axis, float)
    vn = float(wind_speed) * abs(float(wind @ axis) / (np.linalg.norm(wind) * np.linalg.norm(axis)))
    r_hub, r_tip, dr = rotor_extent(sections, rotor)
    theta = theta_from_geometry(sections, rotor, pitch)
    if not sections.polars:
        raise InputError("sections.polars", "[]", "airfoil polars for the BEM induction")
    if cone:
        span = np.asarray(sections.e_span, float)
        sg = (span @ axis) / (np.linalg.norm(span, axis=1) * np.linalg.norm(axis))
        kw["normal_factor"] = np.sqrt(np.maximum(1.0 - sg**2, 1e-12))
    res = bem_induction(sections.radius, sections.chord, theta, sections.polars, sections.airfoil, vn, omega,
                        int(B), r_tip, r_hub, dr=dr / present, air_density=air_density, **kw)
    if warn:
        warn_outside_momentum_theory(res, float(wind_speed), float(omega))
        warn_compressible(res.W, float(wind_speed), float(omega))
    return res


#: limits of the momentum balance: the axial induction of Buhl's turbulent-wake relation ends at 1
#: (C_T = 2); a tangential induction below -0.1 is a strip driving the flow (propeller state)
MOMENTUM_LIMITS = {"a": 0.99, "ap": -0.1}


def warn_outside_momentum_theory(res: BEMResult, wind_speed: float, omega: float = float("nan")) -> None:
    """One :class:`~windflutter.errors.ValidityWarning` per wind speed when a converged strip of
    ``res`` lies outside momentum theory (:data:`MOMENTUM_LIMITS`): at fixed pitch far above the
    operating tip-speed ratio the rotor enters the propeller-brake state, where the BEM induction,
    and every result built on it, is not physics but the model's extrapolation.  The warning
    carries the wind speed, the rotor speed and its kind (the text without the wind speed), so a
    command prints one line for all its wind speeds."""
    ok = np.asarray(res.converged, bool)
    if not ok.any():
        return
    a, ap = np.asarray(res.a, float)[ok], np.asarray(res.ap, float)[ok]
    # the tangential limit on lifting strips only: a drag-dominated strip (|cl| < cd: the root cylinder,
    # cl = 0, cd ~ 0.5) swirls the flow against the rotation at any rotor speed, by its drag, which is
    # not the propeller state (the innermost of the NREL 5 MW shell's 100 strips, r = 1.9 m: a' = -0.19 at
    # the operating 12.1 RPM, 10-25 m/s)
    lifting = np.abs(np.asarray(res.cl, float)[ok]) >= np.asarray(res.cd, float)[ok]
    ap = np.where(lifting, ap, 0.0)
    # (C_P < 0 alone is not a limit: a drag-dominated rotor at high tip-speed ratio, or one pitched
    # towards feather, takes power with a small, valid induction -- the NREL 5 MW at 25 m/s and 2 x
    # rated speed)
    if np.nanmax(a) < MOMENTUM_LIMITS["a"] and np.nanmin(ap) > MOMENTUM_LIMITS["ap"]:
        return
    # the text names the wind speed only (one line per wind speed); the rotor speed goes with the object
    kind = ("the BEM induction leaves momentum theory at high rotor speed (axial induction reaches 1 or tangential "
            f"induction falls below {MOMENTUM_LIMITS['ap']}: the propeller-brake state); onsets in that range depend "
            "on the induction model (compare with solver.induction: false)")
    warnings.warn(ValidityWarning(f"at V = {wind_speed:.1f} m/s {kind}", rotor_speed_rpm=omega * 30.0 / np.pi,
                                  wind_speed=float(wind_speed), kind=kind), stacklevel=3)
