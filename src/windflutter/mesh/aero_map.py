"""Aerodynamic strips of a built model and their sparse motion map (shell: rigid least-squares fit
of the section's skin nodes, RBE3-like; beam: rigid transfer from the element's end nodes).

Elastic-axis choice: the strip's reference point is the blade **pitch axis** (windIO reference
axis) at the strip centre, so ``a = 2 * pitch_axis - 1`` (pitch axis aft of the LE as a chord
fraction).  For the beam model this is the point the 6x6 properties refer to; the true elastic
centre offsets live in the 6x6 coupling terms, and the aero matrices act on the rigid motion of
this point, so the choice only moves where the motion is sampled, not the physics.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from windflutter.aero_types import Polar
from windflutter.linalg_tools import skew
from windflutter.mesh.loft import stack_weights


def blend_polar(p0: Polar, p1: Polar, w: float, name: str) -> Polar:
    """Linear blend ``(1-w) p0 + w p1`` on the union of the two alpha grids."""
    if w <= 1e-9:
        return p0
    if w >= 1 - 1e-9:
        return p1
    al = p0.alpha if (len(p0.alpha) == len(p1.alpha) and np.allclose(p0.alpha, p1.alpha)) else np.union1d(p0.alpha, p1.alpha)

    def f(p, key):
        return np.interp(al, p.alpha, getattr(p, key))

    return Polar(
        alpha=al,
        cl=(1 - w) * f(p0, "cl") + w * f(p1, "cl"),
        cd=(1 - w) * f(p0, "cd") + w * f(p1, "cd"),
        cm=(1 - w) * f(p0, "cm") + w * f(p1, "cm"),
        name=name,
        relative_thickness=(1 - w) * p0.relative_thickness + w * p1.relative_thickness,
    )


def strip_polars(blade, airfoils: dict, eta: np.ndarray) -> list[Polar]:
    """One polar per strip, blended between the neighbouring airfoils of the stack with the same
    thickness-matching weights as the shape (:func:`windflutter.mesh.loft.stack_weights`)."""
    pos = np.asarray(blade.airfoil_positions, dtype=float)
    names = blade.airfoil_names
    tc = [airfoils[n].relative_thickness for n in names]
    jj, ww = stack_weights(pos, tc, eta, blade.at("relative_thickness", eta))
    polars = {n: airfoils[n].polar for n in set(names) if airfoils[n].polars}  # each airfoil's once
    out = []
    for j, w in zip(jj, ww):
        j, w = int(j), float(w)
        n0, n1 = names[j], names[j + 1]
        if n0 not in polars or n1 not in polars:
            out.append(Polar(np.array([-np.pi, np.pi]), np.zeros(2), np.zeros(2), np.zeros(2), name="none"))
            continue
        out.append(blend_polar(polars[n0], polars[n1], w, f"{n0}|{n1}@{w:.3f}"))
    return out


def rigid_fit_rows(points: np.ndarray, nodes: np.ndarray, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Least-squares rigid motion of point ``ref`` from the translations of ``nodes``.

    Solves ``min sum |u0 + theta x (x_n - ref) - u_n|^2``.

    Returns
    -------
    cols : (3 N,) global DOF numbers (translations of the nodes).
    W : (6, 3 N) weights: ``(u0, theta) = W @ u[cols]``.
    """
    d = points - ref[None, :]
    A = np.zeros((3 * len(nodes), 6))
    for k in range(len(nodes)):
        A[3 * k : 3 * k + 3, :3] = np.eye(3)
        A[3 * k : 3 * k + 3, 3:] = -skew(d[k])
    W = np.linalg.solve(A.T @ A, A.T)
    cols = (6 * np.asarray(nodes)[:, None] + np.arange(3)[None, :]).ravel()
    return cols, W


def rigid_transfer_rows(node_xyz: np.ndarray, nodes: np.ndarray, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rigid transfer of nodes' 6 DOFs to points ``ref``: ``u_p = u_n + theta x (p - x_n)``, for
    (k, 3) node coordinates, (k,) node numbers and (k, 3) points: (k, 6) DOF numbers and (k, 6, 6)
    weights."""
    W = np.broadcast_to(np.eye(6), (len(nodes), 6, 6)).copy()
    W[:, :3, 3:] = -skew(np.asarray(ref, float) - np.asarray(node_xyz, float))
    return 6 * np.asarray(nodes)[:, None] + np.arange(6)[None, :], W


def assemble_motion_map(blocks: list[tuple[np.ndarray, np.ndarray]], n_dof: int) -> sp.csr_matrix:
    """Stack per-strip (cols, W) blocks into a sparse (6 ns, n_dof) matrix."""
    rows, cols, vals = [], [], []
    for j, (c, W) in enumerate(blocks):
        r = 6 * j + np.repeat(np.arange(6), len(c))
        rows.append(r)
        cols.append(np.tile(c, 6))
        vals.append(W.ravel())
    return sp.coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(6 * len(blocks), n_dof)
    ).tocsr()
