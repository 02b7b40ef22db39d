"""A geometrically exact reference for beams in large deflection: a discrete Kirchhoff rod.

Written for the tests of the co-rotational beam and shares nothing with windflutter's elements:
``n`` rigid links of length ``h = L / n`` (inextensible, unshearable: a Kirchhoff rod), link ``k``
turned by the rotation ``Q_k`` from the straight reference along ``t0`` with section axes ``D``
(columns ``t0, d2, d3``).  The elastic energy sits in the joints: the relative rotation of two
neighbouring links in the material frame, ``psi_j = log(D^T Q_(j-1)^T Q_j D)`` (``Q_(-1) = I``, the
clamp), carries ``1/2 (psi_j - psi0_j)^T C (psi_j - psi0_j) / h_j`` with ``C = diag(GJ, EI_2,
EI_3)``, ``h_j = h`` (``h/2`` at the clamp, which holds only half a link), ``psi0`` a stress-free
curvature.  Mass ``m h`` at each link centre and the section's rotary inertia ``h Q D diag(J) D^T
Q^T`` per link.  Loads: a dead force at the tip, optionally through a rigid arm fixed to the last
link.  Discretization error O(h^2) (midpoint links, half clamp joint).

Equilibrium by Newton on the total potential in the links' spatial spins ``Q_k -> expm(S theta_k)
Q_k``; the linearized stiffness is the Hessian there (the elastic part by central second
differences over each joint's six spins, the load part in closed form); the frequencies solve
``K v = omega^2 M v``.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy.spatial.transform import Rotation


def _exp(v):
    return Rotation.from_rotvec(np.asarray(v, float).reshape(-1, 3)).as_matrix().reshape(np.shape(v)[:-1] + (3, 3))


def _log(Q):
    return Rotation.from_matrix(np.asarray(Q, float).reshape(-1, 3, 3)).as_rotvec().reshape(np.shape(Q)[:-2] + (3,))


def _S(v):
    v = np.asarray(v, float)
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2], out[..., 1, 2] = -v[..., 2], v[..., 1], -v[..., 0]
    out[..., 1, 0], out[..., 2, 0], out[..., 2, 1] = v[..., 2], -v[..., 1], v[..., 0]
    return out


def _dead_load_hessian(P, r):
    """Hessian in theta of ``P . expm(S theta) r`` at theta = 0."""
    return 0.5 * (np.outer(P, r) + np.outer(r, P)) - (P @ r) * np.eye(3)


class Chain:
    """Discrete Kirchhoff rod cantilevered at the origin (module docstring)."""

    def __init__(self, L, n, C, m, J, D=np.eye(3)):
        self.L, self.n, self.h = float(L), int(n), float(L) / int(n)
        self.C, self.m, self.J = np.asarray(C, float), float(m), np.asarray(J, float)
        self.D = np.asarray(D, float)
        self.t0 = self.D[:, 0]
        self.hj = np.full(self.n, self.h)
        self.hj[0] = 0.5 * self.h
        self.Q = np.broadcast_to(np.eye(3), (self.n, 3, 3)).copy()
        self.psi0 = np.zeros((self.n, 3))
        self.P = np.zeros(3)
        self.arm = np.zeros(3)

    # -- geometry ------------------------------------------------------------------------------
    def tangents(self, Q=None):
        return (self.Q if Q is None else Q) @ self.t0

    def tip(self):
        return self.h * self.tangents().sum(axis=0) + self.Q[-1] @ self.arm

    def tip_rotation(self):
        return self.Q[-1]

    def psi(self, Qprev, Q):
        return _log(np.swapaxes(self.D, -1, -2) @ np.swapaxes(Qprev, -1, -2) @ Q @ self.D)

    # -- energy derivatives --------------------------------------------------------------------
    def _joint_energy(self, Qprev, Q):
        e = self.psi(Qprev, Q) - self.psi0
        return 0.5 * np.einsum("...k,k,...k->...", e, self.C, e) / self.hj

    def _elastic(self, step=1e-4):
        """Gradient (3n) and Hessian (3n, 3n) of the joint energies by central differences."""
        n = self.n
        Qprev = np.concatenate([np.eye(3)[None], self.Q[:-1]])
        eye = np.eye(6)
        pairs = [(i, j) for i in range(6) for j in range(i + 1, 6)]
        pert = [np.zeros(6)] + [eye[i] for i in range(6)] + [-eye[i] for i in range(6)]
        pert += [a * eye[i] + b * eye[j] for a, b in ((1, 1), (1, -1), (-1, 1), (-1, -1)) for i, j in pairs]
        pert = np.array(pert) * step
        Ea = _exp(np.broadcast_to(pert[:, None, :3], (len(pert), n, 3))) @ Qprev[None]
        Eb = _exp(np.broadcast_to(pert[:, None, 3:], (len(pert), n, 3))) @ self.Q[None]
        W = self._joint_energy(Ea, Eb)  # (npert, n)
        g6 = (W[1:7] - W[7:13]) / (2 * step)  # (6, n)
        H6 = np.zeros((n, 6, 6))
        for i in range(6):
            H6[:, i, i] = (W[1 + i] - 2 * W[0] + W[7 + i]) / step**2
        m = W[13:].reshape(4, len(pairs), n)
        for p, (i, j) in enumerate(pairs):
            H6[:, i, j] = H6[:, j, i] = (m[0, p] - m[1, p] - m[2, p] + m[3, p]) / (4 * step**2)
        # joint j couples link j-1 (not for the clamp, j = 0) and link j
        g = g6[3:].T.reshape(-1).copy()
        g[:-3] += g6[:3, 1:].T.reshape(-1)
        H4 = np.zeros((n, 3, n, 3))
        j = np.arange(n)
        H4[j, :, j, :] = H6[:, 3:, 3:]
        H4[j[:-1], :, j[:-1], :] += H6[1:, :3, :3]
        H4[j[:-1], :, j[1:], :] = H6[1:, :3, 3:]
        H4[j[1:], :, j[:-1], :] = H6[1:, 3:, :3]
        return g, H4.reshape(3 * n, 3 * n)

    def _load(self, P):
        """Gradient and Hessian of the dead-load potential ``-P . tip``."""
        n = self.n
        t = self.tangents()
        g = -np.cross(self.h * t, P).reshape(-1)
        r = self.h * t
        blocks = 0.5 * (P[None, :, None] * r[:, None, :] + r[:, :, None] * P[None, None, :]) \
            - (r @ P)[:, None, None] * np.eye(3)
        H4 = np.zeros((n, 3, n, 3))
        H4[np.arange(n), :, np.arange(n), :] = -blocks
        H = H4.reshape(3 * n, 3 * n)
        b = self.Q[-1] @ self.arm
        g[-3:] += -np.cross(b, P)
        H[-3:, -3:] += -_dead_load_hessian(P, b)
        return g, H

    def gradient_hessian(self):
        ge, He = self._elastic()
        gl, Hl = self._load(self.P)
        return ge + gl, 0.5 * ((He + Hl) + (He + Hl).T)

    # -- solution ------------------------------------------------------------------------------
    def solve(self, P, arm=(0.0, 0.0, 0.0), steps=10, tol=1e-11, max_iterations=30):
        """Equilibrium under the tip dead force ``P`` (through ``arm``, reference axes), load-stepped."""
        self.arm = np.asarray(arm, float)
        P = np.asarray(P, float)
        for s in range(1, steps + 1):
            self.P = P * s / steps
            for _ in range(max_iterations):
                g, H = self.gradient_hessian()
                d = -np.linalg.solve(H, g)
                self.Q = _exp(d.reshape(-1, 3)) @ self.Q
                if np.abs(d).max() < tol:
                    break
            else:
                raise RuntimeError("chain equilibrium did not converge")
        return self

    def freeze_shape(self):
        """Make the current shape stress-free (a rod manufactured bent) and remove the load."""
        Qprev = np.concatenate([np.eye(3)[None], self.Q[:-1]])
        self.psi0 = self.psi(Qprev, self.Q)
        self.P = np.zeros(3)
        return self

    def mass(self):
        """Mass matrix in the links' spins: link centres ``c_k = sum_(j<k) h t_j + h t_k / 2`` move by
        ``sum_j w_kj theta_j x h t_j`` (``w`` 1 below the diagonal, 1/2 on it), plus rotary inertia."""
        n, h = self.n, self.h
        S = _S(h * self.tangents())
        W = np.tril(np.ones((n, n)), -1) + 0.5 * np.eye(n)
        M = self.m * h * np.einsum("jl,jba,lbc->jalc", W.T @ W, S, S).reshape(3 * n, 3 * n)
        FD = self.Q @ self.D
        Jr = np.einsum("kab,b,kcb->kac", FD, self.J, FD) * h
        idx = np.arange(n)
        M4 = M.reshape(n, 3, n, 3)
        M4[idx, :, idx, :] += Jr
        return M

    def frequencies(self, k=8):
        """The ``k`` lowest natural frequencies (Hz) about the current equilibrium."""
        _, H = self.gradient_hessian()
        w2 = sla.eigh(H, self.mass(), eigvals_only=True, subset_by_index=[0, k - 1])
        return np.sign(w2) * np.sqrt(np.abs(w2)) / (2 * np.pi)
