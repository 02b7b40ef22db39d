"""Strip aerodynamics in first-order (state-space) form, its projection and the coupled system.

Per strip ``j`` (arrays over strips), section motion ``q_j = (h, alpha, s)`` (plunge along the
lift axis e1, nose-up pitch about e2, edgewise along the relative wind e3; m, rad, m) and
aerodynamic states ``z_j`` (``nz`` per strip)::

    f_j  = Ma_j q_j'' + Da_j q_j' + Ka_j q_j + Cz_j z_j          (lift N/m, moment N m/m, drag N/m
    z_j' = Az_j z_j + Bq_j q_j + Bv_j q_j'                          times the strip width: N, N m, N)

:class:`StripStateSpace` holds these arrays; the operators of :mod:`windflutter.aero.unsteady`
build them.  With the section motion of a structural basis, ``q = R x`` (``R`` (3 ns, m)),
:func:`project` gives the generalized aerodynamic terms (:class:`ProjectedStateSpace`)::

    f_x = M_a x'' + D_a x' + K_a x + F_z z,      z' = A_z z + B_q x + B_v x'

and :meth:`ProjectedStateSpace.pencil` the first-order system of the structure ``M x'' + D x' +
K x = f_x`` with the state ``X = [x, x', z]``: ``E X' = A X``.  Its eigenvalues are the damped
aeroelastic modes at any damping.  At harmonic motion ``exp(i omega t)`` the states can be
eliminated, which gives the frequency-domain ``(Ma, Da, Ka)(omega)`` of p-k
(:meth:`StripStateSpace.frequency_blocks`, :meth:`ProjectedStateSpace.__call__`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from windflutter.errors import InputError

__all__ = ["StripStateSpace", "ProjectedStateSpace", "project", "block_diagonal"]


def block_diagonal(blocks: np.ndarray) -> sp.csr_matrix:
    """Sparse block-diagonal matrix of ``blocks`` (n, r, c)."""
    n, r, c = blocks.shape
    rows = (r * np.arange(n)[:, None, None] + np.arange(r)[None, :, None]) * np.ones((1, 1, c), np.int64)
    cols = (c * np.arange(n)[:, None, None] + np.arange(c)[None, None, :]) * np.ones((1, r, 1), np.int64)
    return sp.csr_matrix((blocks.ravel(), (rows.ravel(), cols.ravel())), shape=(n * r, n * c))


def _lag_terms(Az: np.ndarray, Cz: np.ndarray, Bs: tuple, s: complex):
    """``Cz (s I - Az)^-1 B`` for each ``B`` of ``Bs``, batched over the leading axis."""
    nz = Az.shape[-1]
    if nz == 0:
        return tuple(np.zeros(Cz.shape[:-1] + B.shape[-1:], complex) for B in Bs)
    S = s * np.eye(nz) - Az
    X = np.linalg.solve(S, np.concatenate(Bs, axis=-1).astype(complex))
    out = np.matmul(Cz, X)
    widths = np.cumsum([B.shape[-1] for B in Bs])[:-1]
    return tuple(np.split(out, widths, axis=-1))


@dataclass(frozen=True)
class StripStateSpace:
    """First-order aerodynamics of ``ns`` strips (see the module docstring), real arrays.

    Units: forces (N/m per unit span, or N after :meth:`scaled` by the strip widths) per m, rad
    and m of ``q`` (and per s, s^2 of its derivatives); ``Az`` in 1/s.
    """

    Ma: np.ndarray
    """(ns, 3, 3) apparent mass (of q'')."""
    Da: np.ndarray
    """(ns, 3, 3) damping (of q'): instantaneous circulatory, mean-load and apparent-mass terms."""
    Ka: np.ndarray
    """(ns, 3, 3) stiffness (of q)."""
    Cz: np.ndarray
    """(ns, 3, nz) forces of the aerodynamic states."""
    Az: np.ndarray
    """(ns, nz, nz) state dynamics."""
    Bq: np.ndarray
    """(ns, nz, 3) states driven by q."""
    Bv: np.ndarray
    """(ns, nz, 3) states driven by q'."""

    @property
    def n_sections(self) -> int:
        return int(self.Ma.shape[0])

    @property
    def n_states(self) -> int:
        """Aerodynamic states per strip (``nz``)."""
        return int(self.Az.shape[-1])

    def scaled(self, width: np.ndarray) -> "StripStateSpace":
        """The forces times ``width`` (ns,) (m): per-unit-span arrays -> strip forces."""
        w = np.asarray(width, float)[:, None, None]
        return StripStateSpace(self.Ma * w, self.Da * w, self.Ka * w, self.Cz * w, self.Az, self.Bq, self.Bv)

    def take(self, idx) -> "StripStateSpace":
        """The strips ``idx`` (e.g. a parent map: the sub-strips of the skin distribution)."""
        return StripStateSpace(*(np.asarray(getattr(self, n))[idx] for n in
                                 ("Ma", "Da", "Ka", "Cz", "Az", "Bq", "Bv")))

    def transfer(self, s: complex) -> np.ndarray:
        """``H_j(s)`` (ns, 3, 3) complex with ``f_j = H_j(s) q_j`` for ``q ~ exp(s t)``."""
        lq, lv = _lag_terms(self.Az, self.Cz, (self.Bq, self.Bv), s)
        return s * s * self.Ma + s * self.Da + self.Ka + lq + s * lv

    def frequency_blocks(self, omega: float):
        """Frequency-domain ``(Ma, Da, Ka)`` (ns, 3, 3) complex at ``omega`` (rad/s), the states
        eliminated at ``s = i omega`` as p-k does with C(k): the lag response of ``Bq q`` goes to
        ``Ka``, that of ``Bv q'`` to ``Da``, so ``-omega^2 Ma + i omega Da + Ka = H(i omega)``."""
        lq, lv = _lag_terms(self.Az, self.Cz, (self.Bq, self.Bv), 1j * abs(float(omega)))
        return self.Ma.astype(complex), self.Da + lv, self.Ka + lq


@dataclass(frozen=True)
class ProjectedStateSpace:
    """Generalized aerodynamic terms on a basis of ``m`` coordinates (see the module docstring);
    ``N`` = total number of aerodynamic states."""

    Ma: np.ndarray
    """(m, m) generalized apparent mass."""
    Da: np.ndarray
    """(m, m) generalized damping."""
    Ka: np.ndarray
    """(m, m) generalized stiffness."""
    Fz: np.ndarray
    """(m, N) generalized forces of the states."""
    Az: sp.csr_matrix
    """(N, N) sparse block-diagonal state dynamics."""
    Bq: np.ndarray
    """(N, m) states driven by x."""
    Bv: np.ndarray
    """(N, m) states driven by x'."""
    blocks: np.ndarray
    """(nb, r, r) the diagonal blocks of ``Az`` (fast harmonic evaluation)."""

    @property
    def n_states(self) -> int:
        return int(self.Fz.shape[1])

    def __call__(self, omega: float):
        """Frequency-domain ``(Ma, Da, Ka)`` (m, m) complex at ``omega`` (rad/s): the drop-in of
        :class:`~windflutter.aero.strip.ProjectedAero` for p-k searches (states eliminated at
        ``s = i omega``)."""
        m = self.Ma.shape[0]
        nb, r, _ = self.blocks.shape
        if r == 0:
            return self.Ma.astype(complex), self.Da.astype(complex), self.Ka.astype(complex)
        S = 1j * abs(float(omega)) * np.eye(r) - self.blocks
        B = np.concatenate([self.Bv, self.Bq], axis=1).reshape(nb, r, 2 * m)
        X = np.linalg.solve(S, B.astype(complex)).reshape(nb * r, 2 * m)
        L = self.Fz @ X.real + 1j * (self.Fz @ X.imag)
        return self.Ma.astype(complex), self.Da + L[:, :m], self.Ka + L[:, m:]

    def pencil(self, M, D, K):
        """First-order pencil ``E X' = A X``, ``X = [x, x', z]``, of ``M x'' + D x' + K x = f_x``.

        ``M, D, K`` : structural (m, m) (mass, damping incl. gyroscopic, stiffness incl. rotor
        terms), dense or sparse.  Returns dense ``E, A`` (2 m + N square)::

            E = diag(I, M - M_a, I),   A = [[0, I, 0], [-(K - K_a), -(D - D_a), F_z], [B_q, B_v, A_z]]
        """
        M, D, K = (np.asarray(X.toarray() if sp.issparse(X) else X, float) for X in (M, D, K))
        m = self.Ma.shape[0]
        if M.shape != (m, m) or D.shape != (m, m) or K.shape != (m, m):
            raise InputError("M, D, K", (M.shape, D.shape, K.shape), f"structural matrices of the basis ({m}, {m})")
        N = self.n_states
        n = 2 * m + N
        E = np.eye(n)
        E[m:2 * m, m:2 * m] = M - self.Ma
        A = np.zeros((n, n))
        A[:m, m:2 * m] = np.eye(m)
        A[m:2 * m, :m] = -(K - self.Ka)
        A[m:2 * m, m:2 * m] = -(D - self.Da)
        A[m:2 * m, 2 * m:] = self.Fz
        A[2 * m:, :m] = self.Bq
        A[2 * m:, m:2 * m] = self.Bv
        A[2 * m:, 2 * m:] = self.Az.toarray()
        return E, A

    def state_matrix(self, M, D, K) -> np.ndarray:
        """``E^-1 A`` of :meth:`pencil` (only the structural block row needs a solve)."""
        E, A = self.pencil(M, D, K)
        m = self.Ma.shape[0]
        A[m:2 * m] = sla.solve(E[m:2 * m, m:2 * m], A[m:2 * m])
        return A

    def compress(self, group: np.ndarray, rtol: float = 1e-12) -> "ProjectedStateSpace":
        """Fewer states, same transfer function: merge the states of strips that share their lag
        dynamics (``group`` (nb,): one label per strip, e.g. the skin sub-strips' parent strip).

        Within a group every strip has the same ``Az`` block, so per eigenvalue ``mu`` of the
        block the group's lag response is ``(F_G B_G) / (s - mu)`` with ``F_G B_G`` of rank at
        most ``m``; it is realised with ``rank`` states from its SVD (singular values below
        ``rtol`` times the largest dropped).  Exact for ``rtol -> 0``.  Groups whose block has
        complex or repeated eigenvalues are kept as they are.
        """
        nb, r, _ = self.blocks.shape
        group = np.asarray(group)
        if group.shape != (nb,):
            raise InputError("group", group.shape, f"one label per strip ({nb},)")
        if r == 0:
            return self
        m = self.Ma.shape[0]
        F = self.Fz.reshape(m, nb, r)
        B = np.concatenate([self.Bq, self.Bv], axis=1).reshape(nb, r, 2 * m)
        outs, ins, lams = [], [], []
        for g in np.unique(group):
            js = np.where(group == g)[0]
            blk = self.blocks[js[0]]
            lam, V = np.linalg.eig(blk)
            if (not np.allclose(self.blocks[js], blk, rtol=1e-12, atol=0) or np.any(np.abs(lam.imag) > 0)
                    or np.unique(lam.real).size < r):
                for j in js:  # keep as is (block in its own coordinates)
                    outs.append(F[:, j, :])
                    ins.append(B[j])
                    lams.append(blk)
                continue
            V, Vi = V.real, np.linalg.inv(V.real)
            Fg = np.einsum("mjr,rp->pmj", F[:, js, :], V)      # (r, m, G)
            Bg = np.einsum("pr,jrk->pjk", Vi, B[js])           # (r, G, 2m)
            for p in range(r):
                U, sv, Wt = np.linalg.svd(Fg[p] @ Bg[p], full_matrices=False)
                keep = sv > rtol * sv[0] if sv.size and sv[0] > 0 else np.zeros(0, bool)
                k = int(keep.sum())
                if k:
                    outs.append(U[:, :k] * sv[:k])
                    ins.append(Wt[:k])
                    lams.append(np.diag(np.full(k, lam[p].real)))
        Fz = np.hstack(outs)
        Bn = np.vstack(ins)
        Az = sp.block_diag(lams, format="csr")
        blocks = _diagonal_blocks(lams)
        return ProjectedStateSpace(self.Ma, self.Da, self.Ka, Fz, Az, Bn[:, :m], Bn[:, m:], blocks)


def _diagonal_blocks(mats: list) -> np.ndarray:
    """(nb, r, r) blocks for :meth:`ProjectedStateSpace.__call__` from a list of square blocks:
    equal sizes are stacked; otherwise one (1, N, N) dense block."""
    sizes = {a.shape[0] for a in mats}
    if len(sizes) == 1:
        return np.stack(mats)
    return sla.block_diag(*mats)[None]


def project(ss: StripStateSpace, R) -> ProjectedStateSpace:
    """Project strip state-space aerodynamics (forces already times the strip widths) on a basis.

    Parameters
    ----------
    ss : :class:`StripStateSpace` of ``ns`` strips.
    R : (3 ns, m) real (dense or sparse): ``q = R x``, rows ``3 j + (0, 1, 2)`` the
        ``(h, alpha, s)`` of strip ``j`` (e.g. ``section_map @ basis``).

    Returns
    -------
    :class:`ProjectedStateSpace` by consistent virtual work: ``M_a = sum_j R_j^T Ma_j R_j``,
    ``F_z = [R_j^T Cz_j]``, ``B_q = [Bq_j R_j]`` (batched matrix products, no loop over strips).
    """
    R = R.toarray() if sp.issparse(R) else np.asarray(R, float)
    ns, nz = ss.n_sections, ss.n_states
    if R.ndim != 2 or R.shape[0] != 3 * ns:
        raise InputError("R", R.shape, f"(3 x {ns} strips, m) section motions of the basis")
    m = R.shape[1]
    R3 = R.reshape(ns, 3, m)

    def sym(blk):
        return R.T @ np.matmul(blk, R3).reshape(3 * ns, m)

    Fz = np.einsum("jam,jak->mjk", R3, ss.Cz).reshape(m, ns * nz)
    Bq = np.matmul(ss.Bq, R3).reshape(ns * nz, m)
    Bv = np.matmul(ss.Bv, R3).reshape(ns * nz, m)
    return ProjectedStateSpace(sym(ss.Ma), sym(ss.Da), sym(ss.Ka), Fz, block_diagonal(ss.Az), Bq, Bv,
                               np.asarray(ss.Az, float))
