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

The shear stiffness and the mass are not extracted (yet): the 6 x 6 of
:class:`~windflutter.structure.fem.BeamSection` has them, so a full blade-station table needs
transverse-load cases with the bending part removed.

Units: SI (m, N, N m, N m^2).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.assembly import assemble
from windflutter.structure.fem import FEModel, RigidLink
from windflutter.structure.prestress import static_solve

__all__ = ["SegmentStiffness", "ring_rigid_motion", "segment_stiffness"]


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
    E = _axes(axis, e2)
    refs = [np.asarray(r, float) for r in refs]
    length = float((refs[1] - refs[0]) @ E[0])
    if not length > 0:
        raise InputError("refs", refs, "two reference points along the axis, root side first")
    X = np.asarray(fe.nodes, float)
    tip = np.asarray(tip, dtype=np.int64)
    dref = (refs[1] - refs[0]) / np.linalg.norm(refs[1] - refs[0])
    c = refs[0] + ((X[tip].mean(axis=0) - refs[0]) @ dref) * dref  # the loads act on the reference axis
    load_node = fe.n_nodes
    spc = {int(n): (0, 1, 2, 3, 4, 5) for n in np.asarray(root, dtype=np.int64)}
    fe2 = replace(fe, nodes=np.vstack([X, c]), spc={**fe.spc, **spc},
                  rigid_links=list(fe.rigid_links) + [RigidLink(independent=load_node, dependent=tip)])
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
