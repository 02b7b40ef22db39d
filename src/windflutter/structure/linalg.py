"""Symmetric positive-definite sparse factorisation for the structural solvers.

CHOLMOD supernodal Cholesky (SuiteSparse, through the optional ``kvxopt`` package, extra
``windflutter[fast]``) with an AMD ordering computed here so that every pivot can be traced back to
its DOF; fallback: SciPy SuperLU with diagonal pivoting (COLAMD ordering, symmetric mode).  Measured
on the 30k-DOF tube of ``benchmarks/bench_structure.py``: CHOLMOD 1.2 s vs SuperLU 5-9 s.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.fastlib import cholmod_block_solve, import_kvxopt


class NotPositiveDefinite(Exception):
    """The matrix has a zero or negative pivot."""


@dataclass
class _Analysis:
    """CHOLMOD's symbolic analysis of one pattern (size, the lower triangle's triplet rows and columns):
    the AMD ordering, the symbolic factor (into which each ``numeric`` writes), the factor that
    holds it now (a weak reference) and kvxopt's matrix of the pattern (None when kvxopt stores the
    triplets in another order)."""

    n: int
    rows: np.ndarray
    cols: np.ndarray
    ordering: object
    factor: object
    owner: weakref.ref | None = None
    matrix: object = None


#: the last symbolic analyses (:class:`_Analysis`), newest first
_SYMBOLIC: list = []
_SYMBOLIC_CACHE = 4


class SPDFactor:
    """Cholesky (or diagonal-pivot LU) factor of a symmetric matrix ``A``.

    Attributes
    ----------
    pivots : (n,) pivots (``L_kk^2`` or ``U_kk``) in elimination order.
    pivot_dofs : (n,) row/column of ``A`` eliminated at each step.
    backend : "cholmod" or "superlu".
    """

    def __init__(self, A: sp.spmatrix, backend: str = "auto"):
        A = sp.csc_matrix(A)
        self.n = A.shape[0]
        self.backend = self.backend_asked = backend
        if backend in ("auto", "cholmod"):
            if import_kvxopt() is not None:
                self.backend = "cholmod"
            elif backend == "cholmod":
                raise ImportError("the CHOLMOD backend needs kvxopt (pip install windflutter[fast])")
            else:
                self.backend = "superlu"
        if self.backend == "cholmod":
            self._cholmod(A)
        else:
            self._superlu(A)

    def _cholmod(self, A: sp.csc_matrix) -> None:
        """CHOLMOD's factor of ``A``.  Its symbolic analysis (AMD ordering, symbolic factor: 35 ms of
        0.2 s on a 26k-DOF shell blade) and kvxopt's matrix of that pattern (whose numbers are rewritten:
        25 ms saved) are shared with the last factor of the same pattern (:data:`_SYMBOLIC`; the
        structural operators of a sweep's points have one pattern): kvxopt's ``numeric`` writes into the
        factor it is given, so the factor that had it is marked stale and, should it solve again,
        factorizes its matrix anew (:meth:`_own_factor`) -- never a wrong solve."""
        from kvxopt import cholmod, matrix, sparse

        if not A.has_sorted_indices:  # the lower triangle's triplets in column-major order, as kvxopt
            A = A.sorted_indices()    # stores them
        L = sp.tril(A, format="coo")
        self._L = L  # for a new factorization of its own, should it be stale
        entry = _symbolic_entry(L)
        Ak = entry.matrix
        if Ak is None:  # an order kvxopt does not keep: a matrix of its own
            Ak = _kvxopt_lower(L, A.shape)
        else:  # the pattern's matrix with these numbers (kvxopt: "an efficient way of changing the values")
            Ak.V = matrix(np.ascontiguousarray(L.data, dtype=float))
        self._p = entry.ordering
        owner = entry.owner() if entry.owner is not None else None
        if owner is not None and owner is not self:
            owner._F = None  # stale: its numbers are being overwritten
        entry.owner = weakref.ref(self)
        self._F = entry.factor
        try:
            cholmod.numeric(Ak, self._F)
        except ArithmeticError as exc:
            self._F = None
            raise NotPositiveDefinite(str(exc)) from None
        try:
            self.pivots = np.array(cholmod.diag(self._F)).ravel() ** 2
        except ValueError:  # singular (or not supernodal): let SuperLU decide and report, unless
            if self.backend_asked == "cholmod":  # CHOLMOD alone was asked for (the caller has its own
                raise NotPositiveDefinite("CHOLMOD: not positive definite") from None  # fallback)
            self.backend = "superlu"
            self._superlu(A)
            return
        self.pivot_dofs = np.array(self._p, dtype=np.int64).ravel()
        self._matrix, self._sparse = matrix, sparse
        self._cm = cholmod

    def _superlu(self, A: sp.csc_matrix) -> None:
        try:
            self._lu = spla.splu(A, permc_spec="COLAMD", diag_pivot_thresh=0.0, options=dict(SymmetricMode=True))
        except RuntimeError as exc:
            raise NotPositiveDefinite(str(exc)) from None
        self.pivots = self._lu.U.diagonal()
        self.pivot_dofs = self._lu.perm_c
        if np.any(self.pivots <= 0):
            raise NotPositiveDefinite("non-positive pivot")

    def _own_factor(self) -> None:
        """A stale factor (its shared symbolic factor reused by a later one) factorizes its matrix anew,
        into a symbolic factor of its own."""
        from kvxopt import cholmod

        Ak = _kvxopt_lower(self._L, self._L.shape)
        self._F = cholmod.symbolic(Ak, p=self._p)
        cholmod.numeric(Ak, self._F)

    def solve(self, b: np.ndarray) -> np.ndarray:
        """Solve ``A x = b`` for (n,) or (n, k) real b."""
        b = np.asarray(b, dtype=float)
        if self.backend == "superlu":
            return self._lu.solve(b)
        if self._F is None:
            self._own_factor()
        if b.ndim == 2 and b.shape[1] > 1:  # a block: CHOLMOD's supernodal solve on all its columns at once
            X = cholmod_block_solve(self._F, b)  # (level-3 BLAS: 40 columns of the NREL 5 MW shell blade
            if X is not None:                    # 0.07 s against 0.26 s through kvxopt, the same numbers)
                return X
        B = self._matrix(np.asfortranarray(b.reshape(self.n, -1)))
        if B.size[1] > 1:  # a block: CHOLMOD's sparse right-hand-side solve works on blocks of columns, where
            # kvxopt's dense solve loops over them one by one (40 columns of the IEA 22 MW shell blade,
            # 26,658 DOF: 0.29 s against 0.66 s, the same numbers to 1e-14)
            return np.array(self._matrix(self._cm.spsolve(self._F, self._sparse(B)))).reshape(b.shape)
        self._cm.solve(self._F, B)
        return np.array(B).reshape(b.shape)

    def operator(self) -> spla.LinearOperator:
        return spla.LinearOperator((self.n, self.n), matvec=self.solve, matmat=self.solve, dtype=float)


def _kvxopt_lower(C: sp.coo_matrix, shape) -> object:
    """kvxopt's ``spmatrix`` of the lower triangle ``C`` (COO)."""
    from kvxopt import matrix, spmatrix

    try:  # the index arrays through the buffer protocol: 3x faster than lists (0.36 -> 0.11 s at 1.5 M nonzeros)
        return spmatrix(matrix(np.ascontiguousarray(C.data, dtype=float)),
                        matrix(np.ascontiguousarray(C.row, dtype=np.int64)),
                        matrix(np.ascontiguousarray(C.col, dtype=np.int64)), size=shape)
    except (TypeError, ValueError):  # a kvxopt whose integer type is not 64-bit
        return spmatrix(C.data.astype(float), C.row.astype(int).tolist(), C.col.astype(int).tolist(), size=shape)


def _symbolic_entry(L: sp.coo_matrix) -> _Analysis:
    """The :data:`_SYMBOLIC` entry of the pattern of ``L`` (its triplets' rows and columns in their
    order, compared in full: equal arrays are the same pattern), analysed and added if new; its
    kvxopt matrix is kept when kvxopt stores the triplets in their order (then new numbers are
    written into it), else None."""
    from kvxopt import amd, cholmod

    n = L.shape[0]
    for entry in _SYMBOLIC:
        if entry.n == n and np.array_equal(entry.rows, L.row) and np.array_equal(entry.cols, L.col):
            return entry
    Ak = _kvxopt_lower(L, L.shape)
    colptr = np.concatenate([[0], np.cumsum(np.bincount(L.col, minlength=n))])
    same_order = (np.array_equal(np.asarray(Ak.CCS[0]).ravel(), colptr)
                  and np.array_equal(np.asarray(Ak.CCS[1]).ravel(), L.row))
    p = amd.order(Ak)
    entry = _Analysis(n, L.row.copy(), L.col.copy(), p, cholmod.symbolic(Ak, p=p), matrix=Ak if same_order else None)
    _SYMBOLIC.insert(0, entry)
    del _SYMBOLIC[_SYMBOLIC_CACHE:]
    return entry
