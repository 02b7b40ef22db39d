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

The end rings restrain the warping and the in-plane deformation of the sections, which in a thin-walled
box decays slowly along the span (a 2 x 1 m box: torsion -3.8 %, shear centre 3.5 % of the width off
between rings 4 m from the ends).  ``section_properties(..., ends="periodic")`` removes that: the cell
between the two measuring rings with periodic ends (:func:`periodic_compliance`, the Saint-Venant
state of a prismatic beam) gives the axial, torsion and bending columns and, by the compliance's
symmetry, every coupling and the shear centre; only the transverse shear block keeps the rigid
ends' value.

Units: SI (m, N, N m, N m^2).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.errors import InputError
from windflutter.structure.assembly import assemble, assemble_matrices
from windflutter.structure.fem import FEModel, RigidLink
from windflutter.structure.prestress import static_solve

__all__ = ["SegmentStiffness", "SectionProperties", "periodic_compliance", "ring_rigid_motion", "section_properties",
           "segment_stiffness"]


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
                       refs: tuple[np.ndarray, np.ndarray], axis, e2=None, ends: str = "rigid") -> SectionProperties:
    """The full beam section of the shell segment ``fe`` (module docstring; arguments as
    :func:`segment_stiffness`).  ``ends``: ``"rigid"`` (the unit loads through the clamped root and the
    tied tip ring) or ``"periodic"`` (the axial, torsion and bending columns -- with the shear centre
    and every coupling -- from the cell between the two measuring rings with periodic ends,
    :func:`periodic_compliance`; only the transverse shear block from the rigid ends).  Periodic ends
    need a prismatic cell: the rings' nodes in the same order, the second ring the first one moved
    along the axis."""
    if ends not in ("rigid", "periodic"):
        raise InputError("ends", ends, "'rigid' or 'periodic'")
    E, refs, length, X, x_load, fe2 = _loaded_segment(fe, root, tip, refs, axis, e2)
    load_node = fe.n_nodes
    S, asym = _section_compliance(fe2, load_node, E, X, rings, refs, length, x_load)
    if ends == "periodic":
        P = periodic_compliance(fe, rings, refs, E)
        shear = S[1:3, 1:3].copy()
        S = P
        S[1:3, 1:3] = shear
    # tension centre: N at (y, z) gives M2 = z N, M3 = -y N and no curvature
    A = np.array([[-S[4, 5], S[4, 4]], [-S[5, 5], S[5, 4]]])
    tc = np.linalg.solve(A, -S[[4, 5], 0])
    # shear centre: V2 at (y, z) gives T = -z V2, V3 gives T = y V3, and no twist
    sc = np.array([-S[3, 2] / S[3, 3], S[3, 1] / S[3, 3]])
    M, cm = _segment_mass(fe, E, refs, length)
    return SectionProperties(stiffness=np.linalg.inv(S), compliance=S, mass=M, axes=E, length=length,
                             tension_centre=tc, shear_centre=sc, mass_centre=cm, asymmetry=asym)


def _cell(fe: FEModel, rings, refs, e1: np.ndarray) -> tuple[FEModel, np.ndarray, np.ndarray]:
    """The shell elements between the two measuring rings (centroids between their planes) as a model
    of their own: ``(cell, a, b)`` with the rings' nodes renumbered."""
    X = np.asarray(fe.nodes, float)
    s = (X[np.asarray(fe.shell_conn)].mean(axis=1) - refs[0]) @ e1
    cell, new = fe.shell_part((s > 0) & (s < (refs[1] - refs[0]) @ e1))
    a, b = (new[np.asarray(r, dtype=np.int64)] for r in rings)
    if np.any(a < 0) or np.any(b < 0):
        raise InputError("rings", "nodes outside the cell", "two rings bounding the shell elements between them")
    return cell, a, b


def periodic_compliance(fe: FEModel, rings, refs, E: np.ndarray) -> np.ndarray:
    """(6, 6) section compliance (the :class:`SectionProperties` order) from the cell between the two
    measuring rings with periodic ends; its transverse shear block ``[1:3, 1:3]`` is left zero.

    Every node ``i`` of the second ring follows its partner on the first ring up to the relative
    rigid motion ``q = (du, dth)`` of the two sections (about their reference points):
    ``u_b = u_a + du + dth x r_i``, ``theta_b = theta_a + dth`` -- the Saint-Venant state of a prismatic
    beam under constant section forces, in which warping and the sections' in-plane deformation repeat
    from section to section and no end restrains them.  The section force ``N``, the torque and the two
    bending moments act as the forces conjugate to ``q``; six single DOFs of the first ring (statically
    determinate) remove the rigid motion.  The strains follow from ``q`` as in
    :func:`section_properties` (``dth = L kappa``, ``du = L (eps e1 + gamma) + L^2/2 kappa x e1``): the
    columns of ``N, T, M2, M3`` -- and by the compliance's symmetry the rows of the transverse forces,
    so the shear centre (the torque's lateral motion of the reference point) and every coupling.  The
    shear block needs a moment varying along the beam, which periodic ends cannot carry."""
    refs = [np.asarray(r, float) for r in refs]
    e1 = E[0]
    length = float((refs[1] - refs[0]) @ e1)
    cell, a, b = _cell(fe, rings, refs, e1)
    Xc = np.asarray(cell.nodes, float)
    r = Xc[a] - refs[0]
    if np.max(np.abs(Xc[b] - refs[1] - r)) > 1e-6 * max(length, 1.0):
        raise InputError("rings", "not a prismatic cell", "the second ring the first one moved along the axis")
    _, K = assemble_matrices(cell)
    n = cell.n_dof
    keep = np.setdiff1d(np.arange(n), (6 * b[:, None] + np.arange(6)).ravel())
    # T: reduced (the DOFs off the second ring, then q) -> full
    col = {int(d): k for k, d in enumerate(keep)}
    rows, cols, vals = list(keep), list(range(len(keep))), [1.0] * len(keep)
    nq0 = len(keep)
    for i in range(len(b)):
        for c in range(6):
            rows.append(6 * b[i] + c), cols.append(col[6 * a[i] + c]), vals.append(1.0)
        G = np.zeros((6, 6))
        G[:3, :3] = np.eye(3)
        G[:3, 3:] = -np.array([[0, -r[i, 2], r[i, 1]], [r[i, 2], 0, -r[i, 0]], [-r[i, 1], r[i, 0], 0]])
        G[3:, 3:] = np.eye(3)
        rr, cc = np.nonzero(G)
        rows += list(6 * b[i] + rr)
        cols += list(nq0 + cc)
        vals += list(G[rr, cc])
    T = sp.csr_matrix((vals, (rows, cols)), shape=(n, nq0 + 6))
    Z = _supports(r, e1, [[col[6 * int(node) + c] for c in range(3)] for node in a], nq0 + 6)
    Kf = (Z.T @ (T.T @ K @ T) @ Z).tocsc()
    F = np.zeros((nq0 + 6, 4))
    F[nq0:nq0 + 3, 0] = e1  # N
    for k in range(3):  # T, M2, M3
        F[nq0 + 3:, 1 + k] = E[k]
    W = Z @ spla.splu(Kf).solve(np.asarray(Z.T @ F))
    Q, U = W[nq0:], T @ W  # the relative rigid motions, the cell's displacements
    kappa = E @ Q[3:] / length
    J = np.array([[0.0, 0, 0], [0, 0, 1], [0, -1, 0]])  # J k = k x e1 in the section axes
    strain = E @ Q[:3] / length - J @ (kappa * length / 2 + _first_ring_rotation(K, U, a, r, E))
    S = np.zeros((6, 6))
    S[:, [0, 3, 4, 5]] = np.vstack([strain, kappa])
    S[[0, 3, 4, 5], 1:3] = S[1:3, [0, 3, 4, 5]].T
    return S


def _first_ring_rotation(K, U: np.ndarray, a: np.ndarray, r: np.ndarray, E: np.ndarray) -> np.ndarray:
    """(3, 4) rotation of the first ring's section (section axes ``E``) in each of the four cases
    (columns N, T, M2, M3),
    as the generalized displacement conjugate to the moments: the work of the bending cases' (and
    the torque case's) nodal forces across the first ring on the case's displacements, normalized
    by their moment (a rigid rotation of the ring gives its angle).  This is the rotation the
    section forces do work on -- Trefftz's definition, which makes the torque's lateral motion the
    shear centre's -- where a least-squares fit of the ring's warped shape would weight the nodes
    by their number, not by the walls' stiffness."""
    dofs = (6 * a[:, None] + np.arange(6)).ravel()
    Fc = np.asarray(K @ U)[dofs]  # (6 n_a, 4) forces across the first ring
    Ua = U[dofs]
    out = np.zeros((3, 4))
    for k, case in enumerate((1, 2, 3)):  # the torque, M2 and M3 cases' forces
        f = Fc[:, case].reshape(-1, 6)
        moment = np.sum(np.cross(r, f[:, :3]) + f[:, 3:], axis=0)
        out[k] = f.reshape(-1) @ Ua / (moment @ E[k])
    return out


def _supports(r: np.ndarray, e1: np.ndarray, dofs: list, n: int):
    """(n, n - 6) sparse map removing the rigid motion of the periodic cell by six single supports on
    its first ring (``r`` its nodes' positions from the reference point, ``dofs[i]`` the reduced
    indices of node ``i``'s three translations): all three translations of node 0, the axial and
    the in-plane tangential (about the axis) translation of the node farthest from it, the axial one
    of the node farthest from their line.  Statically determinate: no reaction under the
    self-equilibrated cell loads."""
    d1 = np.linalg.norm(r - r[0], axis=1)
    p1 = int(np.argmax(d1))
    line = (r[p1] - r[0]) / d1[p1]
    off = r - r[0] - np.outer((r - r[0]) @ line, line)
    p2 = int(np.argmax(np.linalg.norm(off, axis=1)))
    B = sp.lil_matrix((n, n))
    B.setdiag(1.0)
    drop = list(dofs[0])
    for node, v in ((p1, e1), (p1, np.cross(e1, line)), (p2, e1)):
        k = dofs[node]
        j = max((c for c in range(3) if k[c] not in drop), key=lambda c: abs(v[c]))
        for c in range(3):  # v . u = 0 solved for the component j
            if c != j:
                B[k[j], k[c]] = -v[c] / v[j]
        drop.append(k[j])
    return sp.csr_matrix(B)[:, np.setdiff1d(np.arange(n), drop)]
