"""Relative flow and section kinematics of aerodynamic strips at an operating point.

For every strip ``j`` of an :class:`~windflutter.aero.sections.AeroSections` and an
:class:`OperatingPoint` (wind speed, rotor speed, extra pitch, optional steady induction):

* the relative flow: ``U_vec = V w - Omega x (x_j - hub)`` projected on the plane normal to the
  span; ``U = |U_vec|`` (equals ``sqrt(V^2 + (Omega r)^2)`` for an unconed, untilted rotor
  without induction, the seed's ch. 3.2);
* the inflow axes: ``e3`` along ``U_vec`` (drag), ``e1`` normal to it in the section plane on the
  suction side (lift), ``e2 = e1 x e3`` (nose-up pitch axis, +-span);
* the geometric angle of attack ``alpha`` (chord vs ``U_vec``, nose-up positive);
* the section motion ``q_j = (h, alpha, s)`` with ``h = e1 . u`` (plunge along lift, i.e. up),
  ``alpha = e2 . theta`` and ``s = e3 . u`` from the section's rows of ``motion_map``
  (:func:`section_map`).

Every aerodynamic operator (:mod:`windflutter.aero.operators`) starts from these.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.aero.sections import AeroSections, RotorGeometry
from windflutter.errors import InputError

__all__ = ["OperatingPoint", "SectionFlow", "section_flow", "section_map"]


@dataclass(frozen=True)
class OperatingPoint:
    """Where the rotor runs.

    Parameters
    ----------
    wind_speed : free wind V (m/s) along ``rotor.wind_direction``.
    omega : rotor speed (rad/s) about ``rotor.shaft_axis`` (0 for a fixed wing).
    air_density : rho (kg/m^3).
    rotor : rotor geometry; for a fixed wing only ``wind_direction`` is used.
    pitch : extra blade pitch (rad, positive nose-down to feather) on top of what the model's
        ``e_chord`` already holds; it only changes the reported angle of attack (the linear
        strip matrices use the inflow axes).
    induction : optional steady induction ``(a, a')`` per strip (arrays (ns,) or scalars, -),
        e.g. from :func:`windflutter.aero.induction.sections_induction`; None (default) keeps the
        thesis's uninduced inflow.  Held fixed (frozen) in the linear stability problem.
    """

    wind_speed: float
    omega: float = 0.0
    air_density: float = 1.225
    rotor: RotorGeometry | None = None
    pitch: float = 0.0
    induction: tuple | None = None


@dataclass
class SectionFlow:
    """Relative flow at each strip (arrays over sections).

    U (m/s), e1/e2/e3 (ns, 3) inflow axes, phi inflow angle from the rotor plane (rad),
    alpha geometric angle of attack (rad, chord vs U, nose-up positive).
    """

    U: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    e3: np.ndarray
    phi: np.ndarray
    alpha: np.ndarray


def unit(v: np.ndarray) -> np.ndarray:
    """Rows of ``v`` (..., 3) scaled to unit length (zero rows stay zero)."""
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0, n, 1.0)


def _induction_factors(op: OperatingPoint, ns: int):
    """``(a, a')`` of ``op.induction`` as finite (ns,) arrays."""
    try:
        a, ap = op.induction
        a = np.broadcast_to(np.asarray(a, float), (ns,))
        ap = np.broadcast_to(np.asarray(ap, float), (ns,))
    except (TypeError, ValueError):
        raise InputError("induction", type(op.induction).__name__,
                         f"a pair (a, a') of scalars or arrays of {ns} strips") from None
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(ap))):
        raise InputError("induction", "non-finite", "finite induction factors (a, a')")
    return a, ap


def _inflow_axes(vrel: np.ndarray, span: np.ndarray, chord: np.ndarray, op: OperatingPoint):
    """Relative speed U (m/s), lift/span/drag axes e1, e2, e3 and angle of attack (rad) of each
    strip from its relative wind ``vrel`` (m/s, (ns, 3)); the spanwise component is dropped."""
    vrel = vrel - np.sum(vrel * span, axis=1, keepdims=True) * span
    U = np.linalg.norm(vrel, axis=1)
    if np.any(U <= 0):
        j = int(np.argmin(U))
        raise InputError("operating point", (op.wind_speed, op.omega), f"a non-zero relative speed at section {j}")
    e3 = vrel / U[:, None]
    e1 = unit(np.cross(e3, span))
    suction = np.cross(chord, span)
    flip = np.sum(e1 * suction, axis=1) < 0
    e1[flip] *= -1.0
    e2 = np.cross(e1, e3)
    ca = np.sum(chord * e3, axis=1)
    sa = -np.sum(chord * e1, axis=1)
    alpha = np.arctan2(sa, ca) - op.pitch
    return U, e1, e2, e3, alpha


def section_flow(sections: AeroSections, op: OperatingPoint) -> SectionFlow:
    """Relative speed, inflow axes and angles at every strip (see module docstring).

    With ``op.induction = (a, a')`` the relative flow is
    ``U_vec = V w - a (V w . n) n - (1 + a') Omega n x (x_j - hub)`` (``n``: shaft axis; the wind
    direction for a fixed wing), i.e. ``U = sqrt((V (1 - a))^2 + (Omega r (1 + a'))^2)`` and
    ``phi = atan2(V (1 - a), Omega r (1 + a'))`` for an unconed, untilted rotor.
    """
    if not np.isfinite(op.wind_speed) or op.wind_speed < 0:
        raise InputError("wind_speed", op.wind_speed, "a non-negative speed (m/s)")
    if not np.isfinite(op.omega):
        raise InputError("omega", op.omega, "a finite rotor speed (rad/s)")
    if not (np.isfinite(op.air_density) and op.air_density > 0):
        raise InputError("air_density", op.air_density, "a positive density (kg/m^3)")
    ns = sections.n_sections
    # no induction: a = a' = 0, which gives the thesis's V, Omega r exactly (bit for bit)
    a, ap = (np.zeros(ns), np.zeros(ns)) if op.induction is None else _induction_factors(op, ns)
    span = unit(np.asarray(sections.e_span, float))
    chord = unit(np.asarray(sections.e_chord, float))
    wind = np.array([1.0, 0.0, 0.0]) if op.rotor is None else unit(np.asarray(op.rotor.wind_direction, float))
    axis = wind if op.rotor is None else unit(np.asarray(op.rotor.shaft_axis, float))
    w = op.wind_speed * wind
    vrel = w[None, :] - (a * float(w @ axis))[:, None] * axis[None, :]
    blade_vel = np.zeros((ns, 3))
    if op.omega != 0.0:
        if op.rotor is None:
            raise InputError("rotor", None, "a RotorGeometry when the rotor speed is not zero")
        rvec = np.asarray(sections.origin, float) - np.asarray(op.rotor.hub_center, float)
        blade_vel = op.omega * np.cross(axis, rvec)
        vrel = vrel - (1.0 + ap)[:, None] * blade_vel
    U, e1, e2, e3, alpha = _inflow_axes(vrel, span, chord, op)
    vrot = np.linalg.norm(blade_vel, axis=1)
    phi = np.arctan2(op.wind_speed * (1.0 - a), vrot * (1.0 + ap))
    return SectionFlow(U=U, e1=e1, e2=e2, e3=e3, phi=phi, alpha=alpha)


def section_map(sections: AeroSections, flow: SectionFlow) -> sp.csr_matrix:
    """Sparse (3 ns, n_dof) map from structural DOFs to ``(h, alpha, s)`` of every section."""
    ns = sections.n_sections
    rows = np.repeat(np.arange(3 * ns), 3)
    cols = np.empty((ns, 3, 3), dtype=np.int64)
    base = 6 * np.arange(ns)[:, None]
    cols[:, 0, :] = base + np.arange(3)  # e1 . u
    cols[:, 1, :] = base + 3 + np.arange(3)  # e2 . theta
    cols[:, 2, :] = base + np.arange(3)  # e3 . u
    vals = np.stack([flow.e1, flow.e2, flow.e3], axis=1)  # (ns, 3, 3)
    E = sp.csr_matrix((vals.ravel(), (rows, cols.ravel())), shape=(3 * ns, 6 * ns))
    mm = sp.csr_matrix(sections.motion_map)
    if mm.shape[0] != 6 * ns:
        raise InputError("sections.motion_map", mm.shape, f"{6 * ns} rows (6 per section)")
    return (E @ mm).tocsr()
