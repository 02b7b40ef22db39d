"""Sparse LU factorization behind one small interface, with interchangeable backends.

The eigen-solvers of windflutter spend most of their time factorizing and back-substituting
the complex, non-symmetric n x n matrix ``Q(s) = s^2 M + s D + K`` (shift-invert Arnoldi).
This module hides *which* sparse LU does that:

``"superlu"``
    SciPy's SuperLU (:func:`scipy.sparse.linalg.splu`), always available. The column ordering
    defaults to ``COLAMD``; ``MMD_AT_PLUS_A`` was measured to be orders of magnitude slower on
    the 26k-DOF shell model (issue 5), so it is not the default.
``"umfpack"``
    SuiteSparse UMFPACK through `kvxopt <https://pypi.org/project/kvxopt/>`_ (``kvxopt.umfpack``
    with ``'d'`` or ``'z'`` sparse matrices), an optional dependency (``pip install
    windflutter[fast]``). Its symbolic analysis (ordering, elimination tree) depends only on the
    sparsity pattern and can be reused across shifts, reduced frequencies and rotor speeds: see
    :class:`Factorizer`.

Two measured facts decide the defaults (``benchmarks/bench_linsolve.py``, ``docs/performance.md``,
complex 25k-DOF shell-like system, 2 cores shared with other jobs):

* **BLAS threads.** SciPy's SuperLU calls the multi-threaded OpenBLAS that NumPy/SciPy bundle.
  When the cores are busy (other jobs, or our own parallel sweep) its spinning threads contend
  and one factorization took 70-90 s instead of 1.3-2.5 s. Factorizations and solves therefore
  run with BLAS limited to ``blas_threads=1`` (via ``threadpoolctl`` when installed). kvxopt
  ships a single-threaded OpenBLAS and is unaffected.
* **Ordering.** FE matrices (and the element- or section-local aero coupling) are structurally
  symmetric. For such patterns SuperLU runs in "symmetric mode" (minimum degree on ``A^T + A``,
  ``SymmetricMode=True``, diagonal pivoting preferred with threshold 0.1): 38 % less fill than
  COLAMD and about half the factorization time. Unsymmetric patterns use COLAMD. (Minimum degree
  *without* symmetric mode and with full partial pivoting is the slow combination reported in
  issue 5.)

With these settings SuperLU factorizes as fast as kvxopt's UMFPACK and solves 4-5x faster
(kvxopt always runs UMFPACK's iterative refinement), so ``backend="auto"`` is SuperLU; UMFPACK
stays available (``backend="umfpack"``) as an independent second implementation and for
unsymmetric patterns. Force a backend without touching code with the environment variable
``WINDFLUTTER_LU_BACKEND``.

Examples
--------
>>> import scipy.sparse as sp, numpy as np
>>> A = sp.diags([1.0 + 1j, 2.0, 3.0]).tocsc()
>>> f = factorize(A)
>>> np.allclose(A @ f.solve(np.ones(3)), 1.0)
True
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.errors import InputError, ModelError
from windflutter.fastlib import import_kvxopt
from windflutter.threads import blas_limit  # noqa: F401  (re-exported: used here and by callers)

__all__ = [
    "BACKENDS",
    "Factor",
    "Factorizer",
    "available_backends",
    "default_backend",
    "factorize",
    "as_operator",
    "blas_limit",
    "is_structurally_symmetric",
]

#: Backend names, fastest first as measured by ``bench_linsolve.py``.
BACKENDS: tuple[str, ...] = ("superlu", "umfpack")

#: SuperLU options for structurally symmetric matrices (see the module docstring).
SUPERLU_SYMMETRIC = dict(permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.1,
                         options=dict(SymmetricMode=True))
#: SuperLU options otherwise (SciPy's default ordering).
SUPERLU_GENERAL = dict(permc_spec="COLAMD")

_ENV_VAR = "WINDFLUTTER_LU_BACKEND"


def available_backends() -> list[str]:
    """Names of the LU backends usable in this environment, fastest first."""
    out = []
    for name in BACKENDS:
        if name == "umfpack" and import_kvxopt() is None:
            continue
        out.append(name)
    return out


def default_backend() -> str:
    """The backend :func:`factorize` uses for ``backend="auto"`` (SuperLU, see module doc).

    ``WINDFLUTTER_LU_BACKEND`` (``superlu`` or ``umfpack``) overrides the automatic choice.
    """
    forced = os.environ.get(_ENV_VAR, "").strip().lower()
    if forced and forced != "auto":
        return _check_backend(forced, field_name=_ENV_VAR)
    return available_backends()[0]


def is_structurally_symmetric(A: sp.csc_matrix) -> bool:
    """True if the sparsity pattern of the square CSC matrix ``A`` equals that of ``A^T``."""
    P = sp.csc_matrix((np.ones(A.nnz, dtype=np.int8), A.indices, A.indptr), shape=A.shape)
    return (P != P.T).nnz == 0


def _check_backend(name: str, field_name: str = "backend") -> str:
    name = str(name).strip().lower()
    if name == "auto":
        return default_backend()
    if name not in BACKENDS:
        raise InputError(field_name, name, f"one of {('auto',) + BACKENDS}")
    if name not in available_backends():
        raise InputError(
            field_name, name,
            "an installed backend: 'umfpack' needs kvxopt (pip install windflutter[fast]); "
            f"available here: {available_backends()}",
        )
    return name


def _as_square_csc(A: Any) -> sp.csc_matrix:
    """Validate ``A`` and return it as a canonical CSC matrix (float64 or complex128)."""
    if not (sp.issparse(A) or isinstance(A, np.ndarray)):
        raise InputError("A", type(A).__name__, "a SciPy sparse matrix or a 2-D NumPy array")
    if A.ndim != 2 or A.shape[0] != A.shape[1] or A.shape[0] == 0:
        raise InputError("A.shape", A.shape, "a non-empty square matrix (n, n)")
    dtype = np.complex128 if np.iscomplexobj(A) else np.float64
    A = sp.csc_matrix(A, dtype=dtype)
    A.sum_duplicates()
    A.sort_indices()
    if not np.all(np.isfinite(A.data)):
        raise InputError("A", "non-finite entries", "a matrix with finite entries (no NaN/inf)")
    return A


@dataclass
class Factor:
    """An LU factorization of a square sparse matrix ``A``.

    Attributes
    ----------
    backend
        ``"superlu"`` or ``"umfpack"``.
    shape
        ``(n, n)``.
    dtype
        ``float64`` or ``complex128`` (the dtype of ``A``).
    """

    backend: str
    shape: tuple[int, int]
    dtype: np.dtype
    _lu: Any = field(repr=False)
    _A_kvx: Any = field(default=None, repr=False)  # the kvxopt matrix (UMFPACK needs A at solve)
    blas_threads: int | None = 1
    ordering: str = ""

    @property
    def n(self) -> int:
        return self.shape[0]

    def solve(self, b: np.ndarray, trans: str = "N") -> np.ndarray:
        """Solve ``A x = b`` (``trans="N"``), ``A^T x = b`` (``"T"``) or ``A^H x = b`` (``"H"``).

        Parameters
        ----------
        b
            Right-hand side(s), shape ``(n,)`` or ``(n, k)``. Real or complex; a complex ``b``
            with a real ``A`` is solved as two real systems.

        Returns
        -------
        numpy.ndarray
            ``x`` with the shape of ``b`` and dtype ``result_type(A, b)``.
        """
        trans = str(trans).upper()
        if trans not in ("N", "T", "H"):
            raise InputError("trans", trans, "'N', 'T' or 'H'")
        b = np.asarray(b)
        if b.ndim not in (1, 2) or b.shape[0] != self.n:
            raise InputError("b.shape", b.shape, f"({self.n},) or ({self.n}, k)")
        if self.dtype == np.float64 and np.iscomplexobj(b):
            # A real factor solves real and imaginary parts separately (A^H = A^T for real A).
            return self._solve(np.ascontiguousarray(b.real, dtype=np.float64), trans) + 1j * self._solve(
                np.ascontiguousarray(b.imag, dtype=np.float64), trans
            )
        return self._solve(np.asarray(b, dtype=self.dtype), trans)

    __call__ = solve

    def _solve(self, b: np.ndarray, trans: str) -> np.ndarray:
        if self.backend == "superlu":
            with blas_limit(self.blas_threads):
                return self._lu.solve(b, trans=trans)
        from kvxopt import matrix, umfpack

        # kvxopt dense matrices are column-major; Fortran-order copy keeps the columns intact.
        B = matrix(np.asfortranarray(b.reshape(self.n, -1)).copy(order="F"))
        umfpack.solve(self._A_kvx, self._lu, B, trans={"N": "N", "T": "T", "H": "C"}[trans])
        return np.array(B, copy=True).reshape(b.shape)


def _to_kvxopt(A: sp.csc_matrix):
    """Convert a canonical CSC matrix to a kvxopt ``spmatrix`` ('d' or 'z')."""
    from kvxopt import matrix, spmatrix

    coo = A.tocoo()
    tc = "z" if A.dtype == np.complex128 else "d"
    # int64 index arrays become kvxopt 'i' matrices; one copy, no Python loop.
    return spmatrix(
        matrix(np.ascontiguousarray(coo.data)),
        matrix(coo.row.astype(np.int64)),
        matrix(coo.col.astype(np.int64)),
        A.shape,
        tc=tc,
    )


def _singular(A_shape, backend: str, err: Exception) -> ModelError:
    return ModelError(
        f"the {A_shape[0]}x{A_shape[1]} matrix is singular to working precision ({backend}: {err}); "
        "typical causes: an unconstrained structure (rigid-body modes) or an eigen-shift that "
        "coincides with an eigenvalue"
    )


def factorize(
    A: Any, backend: str = "auto", *, ordering: str = "auto", blas_threads: int | None = 1
) -> Factor:
    """LU-factorize a square sparse matrix.

    Parameters
    ----------
    A
        Square SciPy sparse matrix (any format) or dense array, real or complex.
    backend
        ``"auto"`` (fastest installed, see :func:`default_backend`), ``"superlu"`` or
        ``"umfpack"``.
    ordering
        SuperLU only: ``"auto"`` (symmetric mode for structurally symmetric patterns, else
        COLAMD), ``"symmetric"``, or a SciPy ``permc_spec`` (``"COLAMD"``, ``"MMD_ATA"``,
        ``"MMD_AT_PLUS_A"``, ``"NATURAL"``) with SciPy's default pivoting. UMFPACK chooses its own.
    blas_threads
        BLAS threads during factorization and solves (``None``: leave as is). 1 is fastest on
        busy machines and in parallel sweeps (see module doc).

    Returns
    -------
    Factor
        Object with ``.solve(b, trans="N")``.

    Raises
    ------
    InputError
        Bad matrix or unknown/unavailable backend.
    ModelError
        ``A`` is singular.
    """
    return Factorizer(backend=backend, ordering=ordering, blas_threads=blas_threads).factorize(A)


class Factorizer:
    """Factorize a sequence of matrices, reusing the symbolic analysis when the pattern repeats.

    In a stability sweep the matrix ``Q(s) = s^2 M + s D + K`` changes value with the shift, the
    reduced frequency and the rotor speed, but never its sparsity pattern. UMFPACK's symbolic
    step (fill-reducing ordering and elimination tree) is then done once; each further
    :meth:`factorize` only runs the numeric factorization. SuperLU (SciPy) offers no such split,
    so with ``backend="superlu"`` every call is a full factorization.

    Parameters
    ----------
    backend, ordering, blas_threads
        As for :func:`factorize`.
    """

    _ORDERINGS = ("auto", "symmetric", "COLAMD", "MMD_ATA", "MMD_AT_PLUS_A", "NATURAL")

    def __init__(self, backend: str = "auto", ordering: str = "auto", blas_threads: int | None = 1):
        self.backend = _check_backend(backend)
        if ordering not in self._ORDERINGS:
            raise InputError("ordering", ordering, f"one of {self._ORDERINGS}")
        self.ordering = ordering
        self.blas_threads = blas_threads
        self._pattern: tuple[tuple[int, int], str, np.ndarray, np.ndarray] | None = None
        self._symbolic: Any = None
        self.n_symbolic = 0  #: number of symbolic analyses done (diagnostics)
        self.n_numeric = 0  #: number of numeric factorizations done

    def factorize(self, A: Any) -> Factor:
        """Factorize ``A``; see :func:`factorize`."""
        A = _as_square_csc(A)
        if self.backend == "superlu":
            ordering = self.ordering
            if ordering == "auto":
                ordering = "symmetric" if is_structurally_symmetric(A) else "COLAMD"
            opts = SUPERLU_SYMMETRIC if ordering == "symmetric" else dict(permc_spec=ordering)
            try:
                with blas_limit(self.blas_threads):
                    lu = spla.splu(A, **opts)
            except RuntimeError as err:  # "Factor is exactly singular"
                raise _singular(A.shape, "superlu", err) from err
            self.n_numeric += 1
            return Factor("superlu", A.shape, A.dtype, lu, None, self.blas_threads, ordering)

        from kvxopt import umfpack

        Ak = _to_kvxopt(A)
        tc = Ak.typecode
        same = (
            self._pattern is not None
            and self._pattern[0] == A.shape
            and self._pattern[1] == tc
            and np.array_equal(self._pattern[2], A.indptr)
            and np.array_equal(self._pattern[3], A.indices)
        )
        try:
            if not same:
                self._symbolic = umfpack.symbolic(Ak)
                self._pattern = (A.shape, tc, A.indptr.copy(), A.indices.copy())
                self.n_symbolic += 1
            num = umfpack.numeric(Ak, self._symbolic)
        except ArithmeticError as err:
            raise _singular(A.shape, "umfpack", err) from err
        self.n_numeric += 1
        return Factor("umfpack", A.shape, A.dtype, num, Ak, self.blas_threads, "umfpack")


def as_operator(factor: Factor) -> spla.LinearOperator:
    """``A^{-1}`` as a SciPy :class:`~scipy.sparse.linalg.LinearOperator` (e.g. for ARPACK's
    ``OPinv``)."""
    return spla.LinearOperator(
        factor.shape,
        matvec=factor.solve,
        rmatvec=lambda b: factor.solve(b, trans="H"),
        matmat=factor.solve,
        dtype=factor.dtype,
    )
