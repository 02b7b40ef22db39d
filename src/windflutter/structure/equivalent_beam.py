"""Equivalent beam section stiffness of a shell segment by unit loads (issue 33 item 3, first part).

A prismatic (or slowly varying) shell segment between a root ring and a tip ring: the root ring
clamped, the tip ring tied to a new node on the reference axis (the line through the measuring rings'
reference points; rigid link), and four unit loads
at that node -- axial force, torque and the two bending moments, each with resultants constant
along the segment.  The rigid motion of two interior rings (least-squares fit of their nodes'
translations about their reference points, as the strips' motion map does) gives the relative
rotation and stretch of the segment between them, away from the end rings' restraint of warping
and Poisson contraction; divided by their distance, the generalized strains (axial strain, twist
rate, two curvatures) per unit resultant.  The inverse of that 4 x 4 compliance is the section
stiffness -- EA, GJ, EI_2, EI_3 and their couplings -- about the reference axis, in the section
axes ``(e1 along the axis, e2, e3)``.

:func:`section_properties` adds the two transverse unit forces at the loaded node.  Their
resultants are not constant along the segment (the moment grows from the tip), so the relative
rigid motion of the rings is the integral of the generalized strains over the distance between them:
with the section forces ``F(x) = F0 + F1 x`` (x from the first ring) and the section compliance
``S`` (strains ``(eps, gamma2, gamma3, kappa1, kappa2, kappa3)`` from ``(N, V2, V3, T, M2, M3)``)

    d_theta = S_k (F0 l + F1 l^2 / 2)
    d_u - theta_a x e1 l = S_e (F0 l + F1 l^2 / 2) + J S_k (F0 l^2 / 2 + F1 l^3 / 6),  J k = k x e1

in the section axes; the six load cases give the 6 x 6 ``S`` by two linear solves (rotations first).
From it, about the reference axis: the tension centre (an axial force there gives no curvature), the
shear centre (a transverse force there gives no twist) and the 6 x 6 stiffness ``S^-1``; from the
elements between the rings, the mass per length, the mass centre and the mass moments of inertia
(element masses lumped at their centroids: the walls' own rotary inertia through their thickness is
left out).

Units: SI (m, N, N m, N m^2).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.assembly import assemble
from windflutter.structure.fem import FEModel, RigidLink
from windflutter.structure.prestress import static_solve

__all__ = ["SegmentStiffness", "SectionProperties", "ring_rigid_motion", "section_properties", "segment_stiffness"]


@dataclass(frozen=True)
class SegmentStiffness:
    """Section stiffness of a shell segment (module docstring).

    ``stiffness`` (4, 4): generalized forces ``(N, T, M2, M3)`` from strains ``(eps, twist rate,
    kappa2, kappa3)`` (N, N m^2); ``compliance`` its inverse; ``axes`` (3, 3) rows ``e1, e2, e3``;
    ``length`` the distance between the two measuring rings (m).
    """

    stiffness: np.ndarray
    compliance: np.ndarray
    axes: np.ndarray
    length: float

    @property
    def EA(self) -> float:
        return float(self.stiffness[0, 0])

    @property
    def GJ(self) -> float:
        return float(self.stiffness[1, 1])

    @property
    def EI2(self) -> float:
        return float(self.stiffness[2, 2])

    @property
    def EI3(self) -> float:
        return float(self.stiffness[3, 3])


def ring_rigid_motion(points: np.ndarray, u: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """``(u0, theta)`` (6,) of the rigid motion ``u0 + theta x (x - ref)`` nearest (least squares) to
    the translations ``u`` (n, 3) of the ``points`` (n, 3)."""
    d = np.asarray(points, float) - np.asarray(ref, float)
    n = len(d)
    A = np.zeros((3 * n, 6))
    A[:, :3] = np.tile(np.eye(3), (n, 1))
    S = np.zeros((n, 3, 3))  # -skew(d): theta x d = -d x theta
    S[:, 0, 1], S[:, 0, 2], S[:, 1, 2] = d[:, 2], -d[:, 1], d[:, 0]
    S[:, 1, 0], S[:, 2, 0], S[:, 2, 1] = -d[:, 2], d[:, 1], -d[:, 0]
    A[:, 3:] = S.reshape(3 * n, 3)
    return np.linalg.lstsq(A, np.asarray(u, float).reshape(-1), rcond=None)[0]


def _axes(axis, e2) -> np.ndarray:
    e1 = np.asarray(axis, float)
    e1 = e1 / np.linalg.norm(e1)
    v = np.asarray(e2, float) if e2 is not None else (np.eye(3)[int(np.argmin(np.abs(e1)))])
    v = v - (v @ e1) * e1
    if np.linalg.norm(v) < 1e-12:
        raise InputError("e2", e2, "a direction not along the segment axis")
    v /= np.linalg.norm(v)
    return np.stack([e1, v, np.cross(e1, v)])


def _loaded_segment(fe: FEModel, root, tip, refs, axis, e2):
    """The segment prepared for its unit loads: ``(E, refs, length, X, x_load, fe2)`` -- its axes, the
    measuring rings' reference points, their distance along the axis, the nodes, the loaded node's
    distance from the first reference point and the model with the root clamped and the tip ring tied
    to a load node on the reference axis (node ``fe.n_nodes``)."""
    E = _axes(axis, e2)
    refs = [np.asarray(r, float) for r in refs]
    length = float((refs[1] - refs[0]) @ E[0])
    if not length > 0:
        raise InputError("refs", refs, "two reference points along the axis, root side first")
    X = np.asarray(fe.nodes, float)
    tip = np.asarray(tip, dtype=np.int64)
    dref = (refs[1] - refs[0]) / np.linalg.norm(refs[1] - refs[0])
    x_load = float((X[tip].mean(axis=0) - refs[0]) @ dref)
    c = refs[0] + x_load * dref  # the loads act on the reference axis
    spc = {int(n): (0, 1, 2, 3, 4, 5) for n in np.asarray(root, dtype=np.int64)}
    fe2 = replace(fe, nodes=np.vstack([X, c]), spc={**fe.spc, **spc},
                  rigid_links=list(fe.rigid_links) + [RigidLink(independent=fe.n_nodes, dependent=tip)])
    return E, refs, length, X, x_load, fe2


def segment_stiffness(fe: FEModel, root: np.ndarray, tip: np.ndarray, rings: tuple[np.ndarray, np.ndarray],
                      refs: tuple[np.ndarray, np.ndarray], axis, e2=None) -> SegmentStiffness:
    """Section stiffness of the shell segment ``fe`` (module docstring).

    Parameters
    ----------
    fe : the segment's shell model (no constraints of its own).
    root, tip : node indices of the end rings (root clamped, tip tied to the loaded node).
    rings : node indices of the two measuring rings, root side first.
    refs : their reference-axis points (m).
    axis : the segment axis (root to tip); ``e2`` the first section axis (default: a global axis).
    """
    E, refs, length, X, x_load, fe2 = _loaded_segment(fe, root, tip, refs, axis, e2)
    load_node = fe.n_nodes
    st = assemble(fe2)
    F = np.zeros((fe2.n_dof, 4))
    F[6 * load_node: 6 * load_node + 3, 0] = E[0]  # axial force
    for k in range(3):  # torque, moment about e2, moment about e3
        F[6 * load_node + 3: 6 * load_node + 6, 1 + k] = E[k]
    U = static_solve(st, F)
    C = np.zeros((4, 4))
    for j in range(4):
        u = U[:, j].reshape(-1, 6)[:, :3]
        ma = ring_rigid_motion(X[rings[0]], u[rings[0]], refs[0])
        mb = ring_rigid_motion(X[rings[1]], u[rings[1]], refs[1])
        du = mb[:3] - ma[:3] - np.cross(ma[3:], refs[1] - refs[0])  # stretch (the rigid rotation removed)
        dth = mb[3:] - ma[3:]
        C[:, j] = np.r_[du @ E[0], E @ dth] / length
    C = 0.5 * (C + C.T)
    return SegmentStiffness(stiffness=np.linalg.inv(C), compliance=C, axes=E, length=length)


@dataclass(frozen=True)
class SectionProperties:
    """Beam section of a shell segment about its reference axis (module docstring), in the
    :class:`~windflutter.structure.fem.BeamSection` order and the section axes ``axes`` (rows e1 along
    the axis, e2, e3).

    ``stiffness`` / ``compliance`` (6, 6): ``(N, V2, V3, T, M2, M3)`` from ``(eps, gamma2, gamma3,
    kappa1, kappa2, kappa3)``; ``mass`` (6, 6) per length (kg/m, kg, kg m) for ``(u, theta)`` of the
    reference point; ``tension_centre``, ``shear_centre``, ``mass_centre`` (2,) their (e2, e3)
    offsets from the reference axis (m); ``asymmetry``: the measured compliance's relative
    asymmetry (a check of the extraction, ~1e-3 and below).
    """

    stiffness: np.ndarray
    compliance: np.ndarray
    mass: np.ndarray
    axes: np.ndarray
    length: float
    tension_centre: np.ndarray
    shear_centre: np.ndarray
    mass_centre: np.ndarray
    asymmetry: float


def _section_compliance(fe2, load_node: int, E: np.ndarray, X: np.ndarray, rings, refs, length: float,
                        x_load: float) -> tuple[np.ndarray, float]:
    """The 6 x 6 section compliance from six unit loads at ``load_node`` (module docstring)."""
    st = assemble(fe2)
    F = np.zeros((fe2.n_dof, 6))
    for k in range(3):
        F[6 * load_node: 6 * load_node + 3, k] = E[k]  # forces along e1, e2, e3
        F[6 * load_node + 3: 6 * load_node + 6, 3 + k] = E[k]  # moments about e1, e2, e3
    U = static_solve(st, F)
    # section forces F(x) = F0 + F1 x of each case (x from the first ring; the load at x_load on the axis)
    F0, F1 = np.eye(6), np.zeros((6, 6))
    F0[5, 1], F1[5, 1] = x_load, -1.0  # a force along e2 at distance d ahead: M3 = d
    F0[4, 2], F1[4, 2] = -x_load, 1.0  # a force along e3: M2 = -d
    G = F0 * length + F1 * length**2 / 2
    H = F0 * length**2 / 2 + F1 * length**3 / 6
    dth, du = np.zeros((3, 6)), np.zeros((3, 6))
    for j in range(6):
        u = U[:, j].reshape(-1, 6)[:, :3]
        ma = ring_rigid_motion(X[rings[0]], u[rings[0]], refs[0])
        mb = ring_rigid_motion(X[rings[1]], u[rings[1]], refs[1])
        du[:, j] = E @ (mb[:3] - ma[:3] - np.cross(ma[3:], refs[1] - refs[0]))
        dth[:, j] = E @ (mb[3:] - ma[3:])
    Sk = np.linalg.solve(G.T, dth.T).T
    J = np.array([[0.0, 0, 0], [0, 0, 1], [0, -1, 0]])
    Se = np.linalg.solve(G.T, (du - J @ Sk @ H).T).T
    S = np.vstack([Se, Sk])
    asym = float(
        np.max(np.abs(S - S.T) / np.sqrt(np.outer(np.abs(np.diag(S)), np.abs(np.diag(S))))))
    return 0.5 * (S + S.T), asym


def _segment_mass(fe: FEModel, E: np.ndarray, refs, length: float) -> tuple[np.ndarray, np.ndarray]:
    """(6 x 6 mass per length about the reference axis, (e2, e3) mass centre) of the elements whose
    centroids lie between the two measuring rings (lumped at the centroids)."""
    X = np.asarray(fe.nodes, float)
    conn = np.asarray(fe.shell_conn)
    p = X[conn]
    area = 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]), axis=1)
    mpa = np.array([pr.mass_per_area for pr in fe.shell_properties])[np.asarray(fe.shell_prop)]
    c = p.mean(axis=1)
    axial = (refs[1] - refs[0]) / np.linalg.norm(refs[1] - refs[0])
    s = (c - refs[0]) @ axial
    keep = (s >= 0) & (s < np.linalg.norm(refs[1] - refs[0]))
    m = area[keep] * mpa[keep]
    r = c[keep] - (refs[0] + s[keep, None] * axial)  # from the reference axis at the same station
    r = r @ E.T
    r[:, 0] = 0.0
    mt = float(m.sum())
    cm = (m[:, None] * r).sum(axis=0) / mt
    Jm = np.eye(3) * np.sum(m * np.sum(r * r, axis=1)) - (m[:, None] * r).T @ r
    Sk = np.array([[0.0, -cm[2], cm[1]], [cm[2], 0, -cm[0]], [-cm[1], cm[0], 0]])
    M = np.zeros((6, 6))
    M[:3, :3] = mt * np.eye(3)
    M[:3, 3:] = -mt * Sk
    M[3:, :3] = mt * Sk
    M[3:, 3:] = Jm
    return M / length, cm[1:]


def section_properties(fe: FEModel, root: np.ndarray, tip: np.ndarray, rings: tuple[np.ndarray, np.ndarray],
                       refs: tuple[np.ndarray, np.ndarray], axis, e2=None) -> SectionProperties:
    """The full beam section of the shell segment ``fe`` (module docstring; arguments as
    :func:`segment_stiffness`)."""
    E, refs, length, X, x_load, fe2 = _loaded_segment(fe, root, tip, refs, axis, e2)
    load_node = fe.n_nodes
    S, asym = _section_compliance(fe2, load_node, E, X, rings, refs, length, x_load)
    # tension centre: N at (y, z) gives M2 = z N, M3 = -y N and no curvature
    A = np.array([[-S[4, 5], S[4, 4]], [-S[5, 5], S[5, 4]]])
    tc = np.linalg.solve(A, -S[[4, 5], 0])
    # shear centre: V2 at (y, z) gives T = -z V2, V3 gives T = y V3, and no twist
    sc = np.array([-S[3, 2] / S[3, 3], S[3, 1] / S[3, 3]])
    M, cm = _segment_mass(fe, E, refs, length)
    return SectionProperties(stiffness=np.linalg.inv(S), compliance=S, mass=M, axes=E, length=length,
                             tension_centre=tc, shear_centre=sc, mass_centre=cm, asymmetry=asym)
