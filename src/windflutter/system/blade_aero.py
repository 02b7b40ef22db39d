"""Strip aerodynamics of one blade in its substructure coordinates ``y = (h, eta)``.

The aerodynamic operator gives, per strip ``j`` (forces times strip width, section motion
``q_j = (h, alpha, s)``)::

    f_j = Ma_j q_j'' + Da_j v_j + Ka_j q_j + Cz_j z_j,   z_j' = Az_j z_j + Bq_j q_j + Bv_j v_j

where ``v_j`` is the section velocity relative to the air's steady frame.  In the rotating frame a
displacement ``w`` of a blade spinning at ``Omega`` about ``n`` adds the transport velocity
``Omega n x w`` to its translations, so with ``q = R y`` and ``Rt = P S_t B``
(:func:`windflutter.system.blade.axis_skew_translations`) ``v = R y' + Omega Rt y``.  Projected by
virtual work (``R^T``), the blade's equations get ``-R^T Ma R`` (mass), ``-R^T Da R`` (damping),
``-R^T (Ka R + Omega Da Rt)`` (stiffness) and the state coupling.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.aero.statespace import StripStateSpace
from windflutter.errors import InputError
from windflutter.structure.modal import symmetric_eigs
from windflutter.system.multiblade import BladeSystem


#: the per-strip pieces are the operator's :class:`~windflutter.aero.statespace.StripStateSpace`
#: (forces times the strip widths; ``nz = 0`` for operators without states)
StripBlocks = StripStateSpace


def _dense(A) -> np.ndarray:
    return A.toarray() if sp.issparse(A) else np.asarray(A)


def project_blade_aero(blocks: StripBlocks, R, Rt, omega: float):
    """``(Ma, Da, Ka, F, Az, Bq, Bv)`` of the strips in the coordinates ``y`` with ``q = R y``.

    ``R``, ``Rt`` (3 ns, ny): section motion and transport map (see module docstring).  Returns
    dense arrays: Ma, Da, Ka (ny, ny) to be SUBTRACTED from the structure's M, C, K; F (ny, ns nz);
    Az (ns nz, ns nz) block diagonal; Bq, Bv (ns nz, ny).
    """
    ns = blocks.n_sections
    Ry = _dense(R).reshape(ns, 3, -1)
    Rty = _dense(Rt).reshape(ns, 3, -1)

    def sym(blk, left, right):
        return np.einsum("jai,jab,jbk->ik", left, blk, right, optimize=True)

    Ma = sym(blocks.Ma, Ry, Ry)
    Da = sym(blocks.Da, Ry, Ry)
    Ka = sym(blocks.Ka, Ry, Ry) + omega * sym(blocks.Da, Ry, Rty)
    nz = blocks.n_states
    ny = Ry.shape[2]
    if nz == 0:
        return Ma, Da, Ka, np.zeros((ny, 0)), np.zeros((0, 0)), np.zeros((0, ny)), np.zeros((0, ny))
    F = np.einsum("jai,jaz->ijz", Ry, blocks.Cz).reshape(ny, ns * nz)
    Az = np.zeros((ns * nz, ns * nz))
    for j in range(ns):  # block diagonal (ns small blocks)
        Az[j * nz:(j + 1) * nz, j * nz:(j + 1) * nz] = blocks.Az[j]
    Bv = np.einsum("jza,jak->jzk", blocks.Bv, Ry).reshape(ns * nz, ny)
    Bq = (np.einsum("jza,jak->jzk", blocks.Bq, Ry) + omega * np.einsum("jza,jak->jzk", blocks.Bv, Rty)
          ).reshape(ns * nz, ny)
    return Ma, Da, Ka, F, Az, Bq, Bv


def blade_system(M, C, K, aero=None) -> BladeSystem:
    """The blade's :class:`BladeSystem` from its structural ``(M, C, K)`` and projected aero."""
    if aero is None:
        return BladeSystem(M=M, C=C, K=K)
    Ma, Da, Ka, F, Az, Bq, Bv = aero
    if F.shape[1] == 0:
        return BladeSystem(M=M - Ma, C=C - Da, K=K - Ka)
    return BladeSystem(M=M - Ma, C=C - Da, K=K - Ka, F=F, Az=Az, Bq=Bq, Bv=Bv)


def quasi_steady_blocks(strip) -> StripBlocks:
    """Provisional operator: today's Theodorsen strips (:class:`~windflutter.aero.strip.StripAero`)
    with ``C = 1`` (quasi-steady, no states), mean-load terms as the strip was configured."""
    pt = strip.parts()
    ns = strip.sections.n_sections
    Ma, Da, Ka = pt.matrices(np.ones(ns))
    w = strip.width[:, None, None]
    z0 = np.zeros((ns, 3, 0))
    return StripStateSpace(Ma=np.real(Ma) * w, Da=np.real(Da) * w, Ka=np.real(Ka) * w, Cz=z0,
                           Az=np.zeros((ns, 0, 0)), Bq=np.zeros((ns, 0, 3)), Bv=np.zeros((ns, 0, 3)))


# -- the aerodynamic states reduced (balanced truncation) ---------------------------------------

#: velocity inputs ``y'`` weighted as displacement inputs at this angular frequency (rad/s) in the
#: balanced truncation's Gramians: 1 rad/s, the low end of a rotor's modes (0.2-3 Hz)
VELOCITY_WEIGHT = 1.0


@dataclass(frozen=True)
class AeroStateProjection:
    """A blade's aerodynamic states ``z = W zr`` (``zr`` the reduced ones), equations projected on
    ``Wl`` (``Wl^T W = I``): the balanced truncation of :func:`balanced_projection`.

    W, Wl : (nz, r).  hsv : (nz,) every Hankel singular value of the blade's aerodynamic subsystem,
    largest first (the kept ones are the first ``r``)."""

    W: np.ndarray
    Wl: np.ndarray
    hsv: np.ndarray

    @property
    def n_states(self) -> int:
        return int(self.W.shape[1])


def _gramian_factor(X: np.ndarray) -> np.ndarray:
    """``L`` with ``L L^T = X`` of a symmetric positive semi-definite Gramian (round-off negatives cut)."""
    w, U = symmetric_eigs(X, np.eye(X.shape[0]))
    return U * np.sqrt(np.clip(w, 0.0, None))


def balanced_projection(bs: BladeSystem, tol: float) -> AeroStateProjection:
    """The balanced truncation of the blade's aerodynamic subsystem ``z' = Az z + Bq y + Bv y'``,
    ``f = F z`` (inputs ``y`` and ``y'``, the latter weighted by :data:`VELOCITY_WEIGHT`): the states
    whose Hankel singular values are at least ``tol`` times the largest (Moore 1981; square-root
    method, Laub et al. 1987).  The error of the transfer function ``F (sI - Az)^-1 (Bq + s Bv)`` is
    at most twice the sum of the dropped values at every frequency (Glover 1984).

    The lag states of the strips are stable (``Az``'s eigenvalues ``-beta_k U_j / b_j``), so both
    Gramians exist; per blade they are ``nz`` square (200 on a 100-strip shell blade: a few ms)."""
    if not (np.isfinite(tol) and 0.0 < tol < 1.0):
        raise InputError("solver.aero_state_tol", tol, "a relative cut-off in (0, 1), or null (every state)")
    import scipy.linalg as sla

    A = np.asarray(bs.Az, float)
    B = np.hstack([bs.Bq, VELOCITY_WEIGHT * bs.Bv])
    Lp = _gramian_factor(sla.solve_continuous_lyapunov(A, -B @ B.T))
    Lq = _gramian_factor(sla.solve_continuous_lyapunov(A.T, -bs.F.T @ bs.F))
    U, s, Vt = np.linalg.svd(Lq.T @ Lp)
    r = int(np.count_nonzero(s > tol * s[0])) if s.size and s[0] > 0 else 0
    scale = 1.0 / np.sqrt(s[:r])
    return AeroStateProjection(W=(Lp @ Vt[:r].T) * scale, Wl=(Lq @ U[:, :r]) * scale, hsv=s)


def static_state_stiffness(bs: BladeSystem) -> np.ndarray:
    """``F Az^-1 Bq``: what the aerodynamic states at their static values (``z = -Az^-1 Bq y``) add to
    ``K`` (the blade's static aerodynamic stiffness with its sign in ``M y'' + C y' + K y = F z``)."""
    return bs.F @ np.linalg.solve(bs.Az, bs.Bq) if bs.n_states else np.zeros_like(bs.K)


def reduced_blade_system(bs: BladeSystem, proj: AeroStateProjection) -> BladeSystem:
    """``bs`` with its aerodynamic states projected by ``proj``; the dropped states' static part is
    added to the stiffness, so the static aerodynamic stiffness ``-F Az^-1 Bq`` is the full
    subsystem's (divergence margins unchanged; the error moves to the frequencies between)."""
    W, Wl = proj.W, proj.Wl
    F, Az, Bq, Bv = bs.F @ W, Wl.T @ bs.Az @ W, Wl.T @ bs.Bq, Wl.T @ bs.Bv
    red = BladeSystem(M=bs.M, C=bs.C, K=bs.K, F=F, Az=Az, Bq=Bq, Bv=Bv)
    red.K = bs.K + (static_state_stiffness(bs) - static_state_stiffness(red))
    return red
