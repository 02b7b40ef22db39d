"""Complex quadratic eigenproblem ``(lambda^2 M + lambda D + K) x = 0``.

Two paths, same answer:

* dense (small problems): the first-order companion pencil ``A z = lambda B z`` with
  ``z = [x, lambda x]``, ``A = [[0, I], [-K, -D]]``, ``B = [[I, 0], [0, M]]``, solved by
  :func:`scipy.linalg.eig` (LAPACK QZ);
* sparse (large problems): shift-invert Arnoldi (ARPACK through :func:`scipy.sparse.linalg.eigs`)
  on the same pencil, where the 2n x 2n operator ``(A - sigma B)^{-1} B`` is applied through a
  single sparse LU of the n x n matrix ``Q(sigma) = sigma^2 M + sigma D + K``:

  ``y1 = -Q(sigma)^{-1} (M z2 + (D + sigma M) z1)``, ``y2 = z1 + sigma y1``,

  and ``lambda = sigma + 1/nu`` for each Ritz value ``nu``.

The LU comes from :class:`windflutter.solve.linsolve.Factorizer` (``lu_backend``, default
``"auto"``, see :data:`LU_BACKEND`), with BLAS limited to one thread around the factorization
and every solve (a multi-threaded OpenBLAS on a busy machine made one SuperLU factorization 30x
slower, ``docs/performance.md``). One ``Factorizer`` per backend and thread is kept, so UMFPACK's
symbolic analysis is reused by every later solve with the same sparsity pattern (the p-k
iterations and rotor speeds of a point all share it); the numbers do not depend on that reuse.
ARPACK gets a fixed start vector, so a solve does not depend on what ran before it in the
process (serial and parallel runs give identical results).

Eigenvalues ``lambda = s + i w`` (rad/s); damping ratio ``zeta = -s/|lambda|``.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.errors import ConvergenceError, InputError, ModelError
from windflutter.solve import linsolve

#: problems with at most this many DOFs go to the dense QZ path by default
DENSE_LIMIT = 600
#: below this many eigenvalues wanted per ``2 n`` the dense path uses shift-invert Arnoldi
#: through a dense LU instead of computing the whole spectrum (``solve_qep_dense_near``)
NEAR_FRACTION = 0.25

#: LU of the shift-invert path: ``"auto"`` (:func:`windflutter.solve.linsolve.default_backend`:
#: SuperLU unless ``WINDFLUTTER_LU_BACKEND`` says otherwise), ``"superlu"`` or ``"umfpack"``.
#: Ordering as for :class:`~windflutter.solve.linsolve.Factorizer`: ``"auto"`` is SuperLU's
#: symmetric mode for structurally symmetric patterns (FE + rotor + strip-aero matrices are) and
#: COLAMD otherwise. Chosen by ``benchmarks/bench_qep.py`` on a 24,960-DOF complex system
#: (``docs/performance.md``): symmetric mode 0.56x the time of the former bare COLAMD ``splu``,
#: COLAMD through the Factorizer 1.1x, UMFPACK (kvxopt) 1.9x (its solves, with the iterative
#: refinement kvxopt always runs, dominate an Arnoldi run).
LU_BACKEND = "auto"
LU_ORDERING = "auto"

_local = threading.local()


def _factorizer(backend: str, ordering: str) -> linsolve.Factorizer:
    """One :class:`~windflutter.solve.linsolve.Factorizer` per (backend, ordering) and thread."""
    cache = getattr(_local, "factorizers", None)
    if cache is None:
        cache = _local.factorizers = {}
    backend = linsolve._check_backend(backend, "lu_backend")
    key = (backend, ordering if backend == "superlu" else "auto")  # UMFPACK orders itself
    if key not in cache:
        cache[key] = linsolve.Factorizer(*key)
    return cache[key]


def start_vector(n: int) -> np.ndarray:
    """Fixed complex ARPACK start vector of length ``n`` (seeded, so reproducible anywhere)."""
    rng = np.random.default_rng(20101)  # any fixed seed; the value has no meaning
    return rng.standard_normal(n) + 1j * rng.standard_normal(n)


@dataclass
class Eigs:
    """Eigenpairs of a quadratic eigenproblem.

    Attributes
    ----------
    values : (m,) complex eigenvalues (rad/s), sorted by distance to the shift.
    vectors : (n, m) complex mode shapes (columns), each scaled so that its largest component
        is 1 (real, positive).
    shift : complex shift used.
    """

    values: np.ndarray
    vectors: np.ndarray
    shift: complex = 0.0

    @property
    def frequency(self) -> np.ndarray:
        """Damped frequency ``Im(lambda)`` (rad/s)."""
        return self.values.imag

    @property
    def damping_ratio(self) -> np.ndarray:
        """``zeta = -Re(lambda) / |lambda|`` (-); 0/0 gives 0."""
        mod = np.abs(self.values)
        with np.errstate(invalid="ignore", divide="ignore"):
            z = np.where(mod > 0, -self.values.real / np.where(mod > 0, mod, 1.0), 0.0)
        return z


def _normalize(vecs: np.ndarray) -> np.ndarray:
    if vecs.size == 0:
        return vecs
    idx = np.argmax(np.abs(vecs), axis=0)
    piv = vecs[idx, np.arange(vecs.shape[1])]
    piv = np.where(piv == 0, 1.0, piv)
    return vecs / piv[None, :]


def _as_csc(A, n: int) -> sp.csc_matrix:
    if A is None:
        return sp.csc_matrix((n, n), dtype=complex)
    return sp.csc_matrix(A, dtype=complex)


def _dense_mdk(M, D, K):
    """``M, D, K`` as dense arrays (``D = None``: zeros)."""
    M = M.toarray() if sp.issparse(M) else np.asarray(M)
    K = K.toarray() if sp.issparse(K) else np.asarray(K)
    D = np.zeros(K.shape) if D is None else (D.toarray() if sp.issparse(D) else np.asarray(D))
    return M, D, K


def qep_pencil(M, D, K, lam: complex):
    """``T(lam) = lam^2 M + lam D + K`` and ``x -> T'(lam) x = (2 lam M + D) x``.

    Sparse when all three are sparse (full-order models), otherwise dense.
    """
    if not (sp.issparse(M) and sp.issparse(D) and sp.issparse(K)):
        M, D, K = _dense_mdk(M, D, K)
    return (lam * lam) * M + lam * D + K, lambda x: (2.0 * lam) * (M @ x) + D @ x


def qep_residual(M, D, K, lam: complex, x: np.ndarray) -> float:
    """Relative residual ``|Q(lam) x| / ((|lam|^2 |M| + |lam| |D| + |K|) |x|)`` (Frobenius norms)."""

    def nrm(A):
        return spla.norm(A) if sp.issparse(A) else np.linalg.norm(A)

    r = lam**2 * (M @ x) + lam * (D @ x) + K @ x
    scale = (abs(lam) ** 2 * nrm(M) + abs(lam) * nrm(D) + nrm(K)) * np.linalg.norm(x)
    return float(np.linalg.norm(r) / scale) if scale > 0 else float(np.linalg.norm(r))


def solve_qep_dense(M, D, K, shift: complex = 0.0, n_eig: int | None = None) -> Eigs:
    """All finite eigenpairs by QZ on the companion pencil; keep the ``n_eig`` nearest ``shift``."""
    M, D, K = _dense_mdk(M, D, K)
    n = K.shape[0]
    Z = np.zeros((n, n))
    I = np.eye(n)
    w = v = None
    # standard form with M^-1 when M is well conditioned (LAPACK geev is several times faster
    # than the QZ algorithm); otherwise the generalized pencil (infinite eigenvalues dropped)
    if np.linalg.cond(M) < 1e10:
        MiK = np.linalg.solve(M, K)
        MiD = np.linalg.solve(M, D)
        A = np.block([[Z, I], [-MiK, -MiD]]).astype(complex)
        w, v = np.linalg.eig(A)
    else:
        A = np.block([[Z, I], [-K, -D]]).astype(complex)
        B = np.block([[I, Z], [Z, M]]).astype(complex)
        w, v = sla.eig(A, B)
    ok = np.isfinite(w) & (np.abs(w) < 1e12)
    w, v = w[ok], v[:n, ok]
    order = np.argsort(np.abs(w - shift), kind="stable")
    if n_eig is not None:
        order = order[:n_eig]
    return Eigs(values=w[order], vectors=_normalize(v[:, order]), shift=complex(shift))


def solve_qep_dense_near(M, D, K, shift: complex = 0.0, n_eig: int = 20, v0: np.ndarray | None = None) -> Eigs:
    """The ``n_eig`` eigenpairs nearest ``shift`` of a small dense QEP by shift-invert Arnoldi.

    The same operator as :func:`solve_qep_sparse` (``(A - shift B)^-1 B`` of the companion
    pencil applied through one LU of ``Q(shift) = shift^2 M + shift D + K``) with a dense LAPACK
    LU: for the projected models of the p-k search (n ~ 100-200, 20 of 2n eigenvalues) it costs
    a sixth of the full QZ/geev spectrum (NREL 5 MW beam, n = 169: 15 ms vs 85 ms) and gives the
    same eigenvalues (to ~1e-13; ``tests/solver/test_qep.py``).  Falls back to
    :func:`solve_qep_dense` when ARPACK does not converge or ``Q(shift)`` is singular.
    ``v0``: ARPACK start vector as for :func:`solve_qep_sparse`.
    """
    Md, Dd, Kd = (np.asarray(A, dtype=complex) for A in _dense_mdk(M, D, K))
    n = Kd.shape[0]
    k = min(int(n_eig), 2 * n - 2)
    s = complex(shift)
    Q = (s * s) * Md + s * Dd + Kd
    with linsolve.blas_limit(1):
        lu, piv = sla.lu_factor(Q, check_finite=False)
        if not np.all(np.isfinite(lu)) or np.min(np.abs(np.diag(lu))) <= 1e-14 * np.max(np.abs(np.diag(lu))):
            return solve_qep_dense(M, D, K, shift, n_eig)
        # the shift-inverted companion operator as one dense 2n x 2n matrix (one LU solve with
        # 2n right-hand sides; then every Arnoldi step is a single matrix-vector product)
        X = sla.lu_solve((lu, piv), np.hstack([Dd + s * Md, Md]), check_finite=False)
        X1, X2 = X[:, :n], X[:, n:]
        op = np.block([[-X1, -X2], [np.eye(n) - s * X1, -s * X2]])
        try:
            nu, v = spla.eigs(op, k=k, which="LM", v0=_start(v0, n, s))
        except spla.ArpackNoConvergence:
            return solve_qep_dense(M, D, K, shift, n_eig)
    lam = s + 1.0 / nu
    order = np.argsort(np.abs(lam - s), kind="stable")
    return Eigs(values=lam[order], vectors=_normalize(v[:n, order]), shift=s)


def warm_start_vector(previous: Eigs) -> np.ndarray:
    """A companion-space start vector ``sum_j [x_j, lambda_j x_j]`` from an earlier solve."""
    x, lam = previous.vectors, previous.values
    return np.concatenate([x.sum(axis=1), (x * lam[None, :]).sum(axis=1)])


def _start(v0, n: int, shift: complex) -> np.ndarray:
    if v0 is None:
        return start_vector(2 * n)
    v0 = np.asarray(v0, dtype=complex).ravel()
    if v0.size == n:
        v0 = np.concatenate([v0, shift * v0])
    if v0.size != 2 * n or not np.all(np.isfinite(v0)) or not np.any(v0):
        raise InputError("v0", f"shape {v0.shape}", f"a finite, non-zero vector of length {n} or {2 * n}")
    return v0


def solve_qep_sparse(M, D, K, shift: complex = 0.0, n_eig: int = 20, tol: float = 0.0,
                     maxiter: int | None = None, lu_backend: str | None = None,
                     lu_ordering: str | None = None, v0: np.ndarray | None = None) -> Eigs:
    """``n_eig`` eigenpairs nearest ``shift`` by shift-invert Arnoldi through one LU of Q(shift).

    ``lu_backend`` / ``lu_ordering``: the sparse LU (default :data:`LU_BACKEND`,
    :data:`LU_ORDERING`; see :mod:`windflutter.solve.linsolve`).
    ``v0``: ARPACK start vector, ``(2n,)`` in the companion space ``[x, lambda x]`` or ``(n,)``
    (then ``[x, shift x]``); default :func:`start_vector`.  A warm start from a nearby solve,
    e.g. ``warm_start_vector(previous)``, saved 15-27 % of the operator applications (LU solves)
    on a 4,800-DOF tube for shift steps of 0.1-5 %, same eigenvalues to 1e-14
    (``docs/performance.md``).  The p-k search does not use it: its Newton refinement already
    starts every root from the previous rotor speed, and starting the remaining Arnoldi solves
    from the tracked shape saved 3 % of a full-order point (within the noise).
    """
    n = K.shape[0]
    M = _as_csc(M, n)
    D = _as_csc(D, n)
    K = _as_csc(K, n)
    s = complex(shift)
    Q = (s * s) * M + s * D + K
    fz = _factorizer(LU_BACKEND if lu_backend is None else lu_backend,
                     LU_ORDERING if lu_ordering is None else lu_ordering)
    try:
        lu = fz.factorize(Q)
    except ModelError as exc:  # exactly singular Q(shift)
        raise ConvergenceError(f"Q(shift) is singular at shift {s}: choose another shift ({exc})") from exc
    DsM = (D + s * M).tocsr()
    Mr = M.tocsr()

    def matvec(z):
        z = np.asarray(z).ravel()
        z1, z2 = z[:n], z[n:]
        y1 = -lu.solve(Mr @ z2 + DsM @ z1)
        y2 = z1 + s * y1
        return np.concatenate([y1, y2])

    op = spla.LinearOperator((2 * n, 2 * n), matvec=matvec, dtype=complex)
    k = min(n_eig, 2 * n - 2)
    try:
        with linsolve.blas_limit(1):
            nu, v = spla.eigs(op, k=k, which="LM", tol=tol, maxiter=maxiter, v0=_start(v0, n, s))
    except spla.ArpackNoConvergence as exc:
        raise ConvergenceError(f"ARPACK did not converge for {k} eigenvalues near {s}") from exc
    lam = s + 1.0 / nu
    x = v[:n, :]
    order = np.argsort(np.abs(lam - s), kind="stable")
    return Eigs(values=lam[order], vectors=_normalize(x[:, order]), shift=s)


def solve_qep(M, D, K, shift: complex = 0.0, n_eig: int = 20, method: str = "auto",
              dense_limit: int = DENSE_LIMIT, v0: np.ndarray | None = None) -> Eigs:
    """Eigenpairs of ``(lambda^2 M + lambda D + K) x = 0`` nearest ``shift``.

    Parameters
    ----------
    M, D, K : (n, n) dense or sparse, real or complex (kg, N s/m, N/m in SI DOFs).
        ``D`` may be ``None``.
    shift : complex shift (rad/s); 0 gives the eigenvalues of smallest modulus (the seed's choice).
    n_eig : number of eigenvalues wanted.
    method : ``"auto"`` (dense up to ``dense_limit`` DOFs: shift-invert Arnoldi through a dense
        LU when fewer than ``NEAR_FRACTION * 2n`` eigenvalues are wanted, else the whole
        spectrum), ``"dense"`` (whole spectrum) or ``"sparse"``.
    v0 : ARPACK start vector of the shift-invert paths (``(n,)`` shape or ``(2n,)`` companion
        vector, see :func:`solve_qep_sparse`); ignored by the whole-spectrum path.

    Returns
    -------
    Eigs
        values sorted by distance to the shift, mode shapes as columns.
    """
    if K is None or K.shape[0] != K.shape[1]:
        raise InputError("K", getattr(K, "shape", None), "a square stiffness matrix")
    n = K.shape[0]
    for name, A in (("M", M), ("D", D)):
        if A is not None and A.shape != K.shape:
            raise InputError(name, A.shape, f"the shape of K {K.shape}")
    if n_eig < 1:
        raise InputError("n_eig", n_eig, "a positive number of eigenvalues")
    if method not in ("auto", "dense", "sparse"):
        raise InputError("method", method, "'auto', 'dense' or 'sparse'")
    if method == "dense" or (method == "auto" and (n <= dense_limit or 2 * n - 2 <= n_eig)):
        if method == "auto" and n >= 40 and n_eig < NEAR_FRACTION * 2 * n:
            return solve_qep_dense_near(M, D, K, shift, n_eig, v0=v0)
        return solve_qep_dense(M, D, K, shift, n_eig)
    return solve_qep_sparse(M, D, K, shift, n_eig, v0=v0)
