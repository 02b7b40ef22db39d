"""The fixed-interface basis of a rotating blade at an operating point.

The basis (:class:`BladeBasis`) is the lowest modes of the hub-clamped blade with its rotating-frame
stiffness and steady stress (``K_r + K_sigma - Omega^2 K_r1``), plus, with ``corrections``, the
static responses to the strip loads those modes generate (modal truncation augmentation, Dickens et
al. 1997).  Beam blades (up to :data:`DENSE_BASIS_LIMIT` DOFs) take a dense eigen-solve; shell blades
one sparse factorization and modes refined from the last point's by subspace iteration
(:func:`~windflutter.solve.symmetric.refine_modes`), or shift-invert Lanczos from scratch for the
first point and whenever the refinement does not converge.  Every pitch of a blade has the same
reduced coordinates (:mod:`windflutter.system.pitch`), so the last modes are a start whatever the
pitch.  Measured on the NREL 5 MW shell blade (7,866 DOF): 0.05-0.2 s a point against 0.5 s from
scratch, onsets within 3e-6 RPM (docs/notes/performance_rounds.md, "Done since (2 Dec 2026, second
session): the shell map in 2 min 5 s - 2 min 25 s").
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from windflutter.solve import symmetric  # module access: tests patch symmetric.refine_modes
from windflutter.structure.modal import m_orthonormalize, symmetric_eigs

#: blade models up to this many free DOFs get their basis from a dense eigen-solve (beams: ~200);
#: above (shells: ~8000 per blade) from one sparse factorization
DENSE_BASIS_LIMIT = 1500
#: a mass matrix whose smallest eigenvalue is below this fraction of its largest is singular for
#: the dense basis (a shell's massless drilling rotations: 4e-13 on a coarse IEA 15 MW shell blade)
SINGULAR_MASS = 1e-10


def dense_pairs(K: np.ndarray, M: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``n`` lowest eigenpairs ``(w2, V)`` of a small blade (dense ``K``, ``M``).  A singular mass
    (massless DOFs: the drilling rotations of a coarse shell) takes the inverted form ``M v = mu K v``,
    whose finite roots are the blade's modes; ``eigh(K, M)`` would return round-off modes of the
    massless DOFs.  A stiffness that is not positive definite (a coarse shell's panel buckled under
    the steady stress) keeps the ordinary form."""
    m = np.linalg.eigvalsh(0.5 * (M + M.T))
    if m[0] < SINGULAR_MASS * max(m[-1], 1e-300):
        try:
            return symmetric_eigs(K, M, n, inverted=True)
        except np.linalg.LinAlgError:  # the inverted form needs K positive definite (a buckled panel
            pass                       # under steady stress is not): the ordinary form, as before
    return symmetric_eigs(K, M, n)


def dense_modes(K: np.ndarray, M: np.ndarray, n: int) -> np.ndarray:
    """The ``n`` lowest modes of a small blade (:func:`dense_pairs`)."""
    return dense_pairs(K, M, n)[1]


#: large blades: modes computed beyond the wanted ones, the guard of the next point's subspace
#: iteration, and its convergence (``refine_modes``' ``tol``: each wanted vector's residual angle;
#: its frequency to about 1e-4, the low modes far better)
GUARD_MODES = 10
MODES_TOL = 1e-2


#: blades below this many free DOFs (beams) get their clamped modes from a dense eigen-solve; above
#: (coarse shells too) a Lanczos run of 40 modes is faster (as :func:`~windflutter.solve.reduction.
#: structural_modes` does)
DENSE_CLAMPED_LIMIT = 600


def clamped_modes(struct, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``k`` lowest modes ``(w2, X)`` of an assembled blade's clamped pencil ``(Kr, Mr)`` (its
    reduced coordinates; dense below :data:`DENSE_CLAMPED_LIMIT` DOFs, above shift-invert Lanczos from a
    fixed start vector), computed once per structure and kept on it: the blade's reference modes
    (:func:`~windflutter.system.reference.blade_reference`) and a shell blade's modal damping
    (:func:`~windflutter.system.damping.shell_modal_damping`) are read from them, and every wind
    speed's first shell-blade basis is refined from them.  A larger ``k`` than kept computes them again."""
    cache = struct.__dict__.get("_clamped_modes")
    if cache is None or cache[1].shape[1] < k:
        Kr, Mr = sp.csc_matrix(struct.Kr), sp.csc_matrix(struct.Mr)
        if Kr.shape[0] < DENSE_CLAMPED_LIMIT:
            cache = dense_pairs(Kr.toarray(), Mr.toarray(), k)
        else:
            cache = symmetric_eigs(Kr, Mr, k, shift=0.0, opinv=symmetric.spd_operator(Kr), v0=np.ones(Kr.shape[0]))
        struct.__dict__["_clamped_modes"] = cache
    return cache[0][:k], cache[1][:, :k]


class BladeBasis:
    """``basis(rb, omega, ksigma, blocks, strip_P)`` -> the (nq, m) basis, None for full order.

    Parameters
    ----------
    n_modes : fixed-interface modes (None: full order).
    corrections : add the static corrections of the aerodynamic loads; ``correction_tol`` is their
        relative cut-off in the Gram spectrum of the (mass-normalised) responses.
    """

    def __init__(self, n_modes: int | None, corrections: bool = False, correction_tol: float = 1e-6):
        self.n_modes, self.corrections, self.correction_tol = n_modes, bool(corrections), float(correction_tol)
        self.start = None  # the last large-blade modes and guards (reduced coordinates)
        #: negative eigenvalues of the last call's full-order blade stiffness (the inertia of its
        #: factorization, :func:`~windflutter.solve.symmetric.factor_with_inertia`): 0 positive definite,
        #: None not known (a small blade's dense basis holds its lowest modes, negative ones included)
        self.negative: int | None = None

    def restart(self, struct=None) -> None:
        """Forget the last modes: the next large-blade basis is refined from the clamped modes of
        ``struct`` (the undeformed blade at rest, :func:`clamped_modes`: the same start whatever ran
        before), or computed from scratch without it."""
        self.start = None
        n = self.n_modes
        if struct is not None and n is not None and struct.Kr.shape[0] > DENSE_BASIS_LIMIT:
            p = min(n + GUARD_MODES, struct.Kr.shape[0] - 2)
            self.start = clamped_modes(struct, p)[1]

    def __call__(self, rb, omega: float, ksigma, blocks, strip_P):
        """The basis of the :class:`~windflutter.system.blade.RotorBlade` ``rb`` at ``omega`` (rad/s)
        with the steady stress's full-numbering geometric stiffness ``ksigma``; ``blocks`` (the strip
        state-space blocks, or None) and ``strip_P`` (the strips' motion map) for the corrections."""
        n = self.n_modes
        st = rb.struct
        self.negative = None
        if n is None or n >= st.nq:
            return None
        T = st.T
        Ks = (st.Kr + T.T @ (ksigma - omega**2 * rb.Kr1) @ T).tocsc()
        Ks = 0.5 * (Ks + Ks.T)
        if st.nq <= DENSE_BASIS_LIMIT:
            K, M = Ks.toarray(), st.Mr.toarray()
            V = dense_modes(K, M, n)
            solve = lambda F: np.linalg.solve(K, F)  # noqa: E731
        else:
            M = st.Mr.tocsc()
            solve, self.negative = symmetric.factor_with_inertia(Ks)
            V = self._sparse_modes(Ks, M, solve, n)
        if not (self.corrections and blocks is not None):
            return V
        return np.hstack([V, self._corrections(T, V, M, solve, blocks, strip_P)])

    def _sparse_modes(self, K, M, solve, n: int) -> np.ndarray:
        """The ``n`` lowest modes of a large blade; :data:`GUARD_MODES` more kept as the next start."""
        p = min(n + GUARD_MODES, K.shape[0] - 2)
        prev = self.start
        ok = prev is not None and prev.shape == (K.shape[0], p)
        out = symmetric.refine_modes(K, M, solve, prev, n, tol=MODES_TOL) if ok else None
        if out is None:
            out = symmetric_eigs(K, M, p, shift=0.0, opinv=solve, v0=np.ones(K.shape[0]))
        self.start = out[1]
        return out[1][:, :n]

    def _corrections(self, T, V, M, solve, blocks, strip_P) -> np.ndarray:
        """Static responses to the strip loads the modes ``V`` generate (the Ka and Da blocks acting on
        their section motion), orthogonal to ``V``, M-orthonormal, above the cut-off."""
        R = np.asarray(strip_P @ (T @ V))  # (3 ns, n)
        ns = blocks.n_sections
        Rs = R.reshape(ns, 3, -1)
        loads = np.concatenate([np.einsum("jab,jbk->jak", blocks.Ka, Rs), np.einsum("jab,jbk->jak", blocks.Da, Rs)],
                               axis=2).reshape(3 * ns, -1)
        X = np.asarray(solve(np.asarray(T.T @ (strip_P.T @ loads))))
        X -= V @ (V.T @ (M @ X))
        return m_orthonormalize(X, M, tol=self.correction_tol, largest_first=False, gram=X.T @ M @ X)
