"""Steady aerodynamic strip loads, rotor totals and the second-order (deformed-configuration) moments.

Strip loads (per strip, global axes, at the strip's elastic-axis point): with the induced inflow
of :func:`windflutter.aero.strip.section_flow` (speed ``U``, lift axis ``e1``, nose-up axis
``e2``, drag axis ``e3``, angle of attack ``alpha``) and the static polar at ``alpha``
(:func:`windflutter.aero.strip.mean_coefficients`),

    ``f = q c (Cl e1 + Cd e3)``,   ``m = q c^2 Cm e2 + (x_qc - x_ea) x f``,   ``q = rho U^2 / 2``,

per unit span, times the strip width; the lift and drag act at the quarter chord
``x_qc - x_ea = -(a + 1/2) b e_chord`` (``a``: elastic axis aft of mid-chord in semi-chords,
``b`` the semi-chord) and ``Cm`` is about the quarter chord.  They enter the structure through
``motion_map^T`` (consistent virtual work), so beam and shell models are treated alike.

Second-order moments.  The structure is linear: it balances the loads with the moment arms of
the undeformed blade and resolves its section moments in undeformed axes.  The deflected blade
balances them with the deformed arms, and its sections (whose curvatures the 6x6 or the shell
laminates relate to the moments) are turned.  For a blade cantilevered at its root, the section
moment at the inner edge ``c_k`` of strip ``k`` is, with the loads ``(F_j, M_j)`` of the strips
``j >= k`` outboard of it at their deformed points ``p'_j``,

    ``M'(k) = sum_j [M_j + (p'_j - c'_k) x F_j]``   (deformed),  local: ``M*(k) = R_k^T M'(k)``

(``R_k`` the finite rotation of the section at ``c_k``) against the linear
``M(k) = sum_j [M_j + (p_j - c_k) x F_j]``.  Pure strip moments ``h_k = dM(k) - dM(k+1)``,
``dM = M* - M``, make the linear structure carry ``M*`` at every cut.  This holds the couplings a
geometrically linear model misses: the edgewise force acting through the flapwise deflection and
the lift through the edgewise deflection twist the blade (the ``(EI_flap - EI_edge) v'' w''``
torsion of Hodges and Dowell's moderate-rotation beam equations), and the flapwise moment seen in
the elastically twisted section.  Left out: the rotation of the section *force* (it turns shear
into axial force and back: the axial-force part is the geometric stiffness ``K_sigma`` of the
centrifugal tension that the static solve holds; the rest changes the axial force by the shear
times a rotation, negligible against the centrifugal tension); the centrifugal loads' own
second-order moments other than ``K_sigma`` and spin softening.

Units: SI (N, N m, m, rad, W).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.sections import AeroSections, RotorGeometry
from windflutter.aero.strip import OperatingPoint, SectionFlow, mean_coefficients, section_flow
from windflutter.steady.geometry import Deflection, blade_strips

__all__ = ["StripLoads", "strip_loads", "nodal_loads", "rotor_totals", "second_order_moments"]


@dataclass(frozen=True)
class StripLoads:
    """Aerodynamic loads of every strip and the flow they come from.

    Attributes
    ----------
    loads : (ns, 6) force (N) and moment (N m) of each strip at its elastic-axis point, global.
    flow : the induced section flow (:class:`~windflutter.aero.strip.SectionFlow`).
    cl, cd, cm : (ns,) static polar coefficients at ``flow.alpha`` (-).
    """

    loads: np.ndarray
    flow: SectionFlow
    cl: np.ndarray
    cd: np.ndarray
    cm: np.ndarray


def strip_loads(sections: AeroSections, op: OperatingPoint) -> StripLoads:
    """Steady lift, drag and pitching moment of every strip at the operating point ``op`` (with its
    induction), see the module docstring."""
    flow = section_flow(sections, op)
    cl, cd, cm = mean_coefficients(sections, flow.alpha)
    chord = np.asarray(sections.chord, float)
    qc = 0.5 * op.air_density * flow.U**2 * chord
    f = qc[:, None] * (cl[:, None] * flow.e1 + cd[:, None] * flow.e3)
    e_chord = np.asarray(sections.e_chord, float)
    e_chord = e_chord / np.linalg.norm(e_chord, axis=1, keepdims=True)
    arm = (-(np.asarray(sections.elastic_axis, float) + 0.5) * 0.5 * chord)[:, None] * e_chord
    m = (qc * chord * cm)[:, None] * flow.e2 + np.cross(arm, f)
    w = np.asarray(sections.width, float)[:, None]
    return StripLoads(loads=np.hstack([f, m]) * w, flow=flow, cl=cl, cd=cd, cm=cm)


def nodal_loads(sections: AeroSections, loads: np.ndarray) -> np.ndarray:
    """Full-numbering nodal loads ``motion_map^T loads`` (N, N m) of (ns, 6) strip loads."""
    return sections.motion_map.T @ np.asarray(loads, float).reshape(-1)


def rotor_totals(sections: AeroSections, rotor: RotorGeometry, loads: np.ndarray, omega: float,
                 n_blades: int) -> tuple[float, float, float]:
    """``(thrust N, torque N m, power W)`` of ``n_blades`` blades from the strip loads.

    Thrust is the force along the shaft axis; torque the moment about it (about the hub centre,
    strip moments included) in the sense of rotation, so that a driving rotor has positive torque
    and power ``|Omega| torque``.  The blades present in ``sections`` are scaled to ``n_blades``.
    """
    loads = np.asarray(loads, float)
    axis = np.asarray(rotor.shaft_axis, float)
    axis = axis / np.linalg.norm(axis)
    rel = np.asarray(sections.origin, float) - np.asarray(rotor.hub_center, float)
    scale = n_blades / int(np.unique(np.asarray(sections.blade)).size)
    thrust = scale * float(np.sum(loads[:, :3] @ axis))
    moment = scale * float(np.sum((np.cross(rel, loads[:, :3]) + loads[:, 3:]) @ axis))
    torque = moment * (np.sign(omega) if omega != 0 else 1.0)
    return thrust, torque, abs(float(omega)) * torque


def _rev_cumsum(a: np.ndarray) -> np.ndarray:
    return np.cumsum(a[::-1], axis=0)[::-1]


def second_order_moments(sections: AeroSections, defl: Deflection, loads: np.ndarray) -> np.ndarray:
    """(ns, 6) pure strip moments (zero forces) that make the linear structure carry the
    deformed-configuration section moments of the strip loads (module docstring).

    Parameters
    ----------
    sections : the undeformed strips (those of the linear structure).
    defl : their deflection (:func:`~windflutter.steady.geometry.deflection`).
    loads : (ns, 6) strip loads (N, N m), global axes, at the deflected strip points.
    """
    loads = np.asarray(loads, float)
    out = np.zeros_like(loads)
    p0 = np.asarray(sections.origin, float)
    for idx in blade_strips(sections):
        F, M = loads[idx, :3], loads[idx, 3:]
        Fk = _rev_cumsum(F)
        m_def = _rev_cumsum(M + np.cross(defl.origin[idx], F)) - np.cross(defl.cut[idx], Fk)
        m_lin = _rev_cumsum(M + np.cross(p0[idx], F)) - np.cross(defl.cut0[idx], Fk)
        dM = np.einsum("kba,kb->ka", defl.R_cut[idx], m_def) - m_lin
        h = dM.copy()
        h[:-1] -= dM[1:]
        out[idx, 3:] = h
    return out
