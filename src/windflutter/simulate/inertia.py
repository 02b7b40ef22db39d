"""Inertial loads of a beam model spinning at a constant rate, from its current configuration.

A second route to the rotating-frame terms: no Coriolis, spin-softening or geometric-stiffness
matrix is formed.  The centrifugal and Coriolis loads are evaluated on the current (finitely
deformed) configuration, so that centrifugal stiffening, spin softening and the Coriolis
coupling all arise from the kinematics when the loads enter the nonlinear equations.

Mass model (from the section mass matrices and the lumped masses, the model's input data):

* translational mass of each beam element ``m_e = m l0`` spread with the linear-interpolation
  (consistent) weights: node ``a`` carries ``m_e (2 x_a + x_b) / 6`` of the position field;
* the section's first moment ``m c`` and second moment ``Q = int s s^T dm = tr(J)/2 I - J``
  about the reference axis (section frame turned to global), half of each element on each
  node, turned with the node's rotation ``R``; lumped masses as rigid bodies on their nodes.

For a material point at ``r = x + s`` (``s = R s0``) of a body moving at ``x'`` and spinning at
``omega`` (relative to the frame) in a frame spinning at ``Omega`` about an axis through the apex,
the fictitious accelerations ``2 Omega x r' + Omega x (Omega x r)`` give per body, with
``P = S(Omega)^T S(Omega)`` (``P r`` the centrifugal acceleration)::

    F = P (m x + m c) - 2 Omega x (m x' + omega x m c)
    M = m c x (P x - 2 Omega x x') + 2 omega x (Q Omega) + eps : (P Q)

(the moment about the node; ``eps : (P Q)_i = eps_ijk P_kl Q_jl``).  The relative accelerations
enter through the model's constant mass matrix; ``omega x J omega`` (second order in the motion)
is left out.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.linalg_tools import skew
from windflutter.structure.beam import beam_frames
from windflutter.structure.fem import FEModel

__all__ = ["SpinningMass", "cross"]

_EPS = np.zeros((3, 3, 3))
_EPS[0, 1, 2] = _EPS[1, 2, 0] = _EPS[2, 0, 1] = 1.0
_EPS[0, 2, 1] = _EPS[2, 1, 0] = _EPS[1, 0, 2] = -1.0


def cross(a, b) -> np.ndarray:
    """``np.cross`` of (..., 3) arrays (broadcast), without its axis handling (the time domain
    calls it tens of thousands of times)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1], a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


class SpinningMass:
    """Inertial loads of the nodes ``nodes`` of ``fe`` spinning at ``omega`` (rad/s) about the unit
    ``axis`` through ``apex`` (module docstring)."""

    def __init__(self, fe: FEModel, nodes, omega: float, axis, apex):
        axis = np.asarray(axis, float)
        if not np.isclose(np.linalg.norm(axis), 1.0, atol=1e-6):
            raise InputError("axis", axis.tolist(), "a unit vector")
        if not np.isfinite(omega):
            raise InputError("omega", omega, "a finite rotor speed (rad/s)")
        n = fe.n_nodes
        self.apex = np.asarray(apex, float)
        self.Omega = float(omega) * axis
        S = skew(self.Omega)
        self.P = S.T @ S
        spin = np.zeros(n, bool)
        spin[np.asarray(nodes, dtype=np.int64)] = True
        self.spin = spin
        conn = np.asarray(fe.beam_conn, dtype=np.int64)
        keep = spin[conn].all(axis=1) if len(conn) else np.zeros(0, bool)
        conn = conn[keep]
        self.mc0 = np.zeros((n, 3))
        self.Q0 = np.zeros((n, 3, 3))
        rows, cols, vals = [], [], []
        if len(conn):
            L, R = beam_frames(fe)
            L, R = L[keep], R[keep]
            Ms = np.array([np.asarray(s.mass, float) for s in fe.beam_sections])[np.asarray(fe.beam_section)[keep]]
            m = Ms[:, 0, 0] * L
            Smc = 0.5 * (Ms[:, 3:, :3] - np.swapaxes(Ms[:, 3:, :3], 1, 2))
            mc = np.stack([Smc[:, 2, 1], Smc[:, 0, 2], Smc[:, 1, 0]], axis=1) * L[:, None]
            J = 0.5 * (Ms[:, 3:, 3:] + np.swapaxes(Ms[:, 3:, 3:], 1, 2)) * L[:, None, None]
            Rt = np.swapaxes(R, 1, 2)  # local -> global
            mc_g = np.einsum("eij,ej->ei", Rt, mc)
            J_g = Rt @ J @ R
            Q = 0.5 * np.trace(J_g, axis1=1, axis2=2)[:, None, None] * np.eye(3) - J_g
            for k in (0, 1):
                np.add.at(self.mc0, conn[:, k], 0.5 * mc_g)
                np.add.at(self.Q0, conn[:, k], 0.5 * Q)
            a, b = conn[:, 0], conn[:, 1]
            for r, c, w in ((a, a, 2), (b, b, 2), (a, b, 1), (b, a, 1)):
                rows.append(r), cols.append(c), vals.append(w * m / 6.0)
        for lm in fe.masses:
            if not spin[lm.node]:
                continue
            off = np.asarray(lm.offset, float)
            Icm = np.asarray(lm.inertia, float)
            rows.append([lm.node]), cols.append([lm.node]), vals.append([float(lm.mass)])
            self.mc0[lm.node] += lm.mass * off
            self.Q0[lm.node] += 0.5 * np.trace(Icm) * np.eye(3) - Icm + lm.mass * np.outer(off, off)
        if rows:
            self.Mlin = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                                      shape=(n, n)).tocsr()
        else:
            self.Mlin = sp.csr_matrix((n, n))

    @property
    def total_mass(self) -> float:
        return float(self.Mlin.sum())

    def loads(self, x: np.ndarray, R: np.ndarray, xdot: np.ndarray | None = None,
              omega: np.ndarray | None = None, frame_spin: np.ndarray | None = None,
              frame_alpha: np.ndarray | None = None) -> np.ndarray:
        """(n_nodes, 6) inertial loads (N, N m; global axes) at positions ``x`` (n, 3), rotations
        ``R`` (n, 3, 3) (reference -> current), velocities ``xdot`` and angular velocities
        ``omega`` (n, 3) relative to the spinning frame (None: at rest).

        ``frame_spin`` (3,): the frame's angular velocity now, in place of the constant
        ``omega axis`` (a frame carried by a moving hub); ``frame_alpha`` (3,): an angular
        acceleration of the frame whose Euler loads ``-alpha x r dm`` are added (with ``J alpha``
        on the rotational inertia)."""
        X = np.asarray(x, float) - self.apex
        mc = np.einsum("nij,nj->ni", R, self.mc0)
        Q = R @ self.Q0 @ np.swapaxes(R, 1, 2)
        P, Om = self.P, self.Omega
        if frame_spin is not None:
            Om = np.asarray(frame_spin, float)
            S = skew(Om)
            P = S.T @ S
        F = (self.Mlin @ X) @ P.T + mc @ P.T
        acc = X @ P.T  # P x per node (the body's reference point)
        Mo = cross(mc, acc) + np.einsum("ijk,kl,njl->ni", _EPS, P, Q)
        if frame_alpha is not None:
            al = np.asarray(frame_alpha, float)
            F -= cross(al, self.Mlin @ X + mc)
            Mo -= cross(mc, cross(al, X))
            Mo -= np.trace(Q, axis1=1, axis2=2)[:, None] * al - Q @ al
        if xdot is not None:
            V = self.Mlin @ np.asarray(xdot, float)
            w = np.zeros_like(X) if omega is None else np.asarray(omega, float)
            F -= 2.0 * cross(Om, V + cross(w, mc))
            Mo -= 2.0 * cross(mc, cross(Om, xdot))
            Mo += 2.0 * cross(w, Q @ Om)
        out = np.zeros((X.shape[0], 6))
        out[self.spin, :3] = F[self.spin]
        out[self.spin, 3:] = Mo[self.spin]
        return out
