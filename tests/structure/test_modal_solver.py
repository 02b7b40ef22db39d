"""The one structural eigen-solver (:func:`windflutter.structure.modal.symmetric_eigs`) and the one
M-orthonormalisation (:func:`~windflutter.structure.modal.m_orthonormalize`).

Reference: a fixed-free chain of ``N`` equal masses ``m`` and springs ``k``, whose eigenvalues are
known in closed form, ``w2_j = 4 k/m sin^2((2j - 1) pi / (2 (2N + 1)))`` (e.g. Meirovitch,
*Fundamentals of Vibrations*, the lumped string) -- shared with nothing in the package.  Dense,
inverted (massless DOFs) and Lanczos paths must all give it to 1e-10 relative (rounding of a
well-conditioned 40 x 40 problem).  A source scan keeps the inline ``eigh``/``eigsh`` calls
from coming back outside the solver.
"""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.structure.modal import mass_normalize, m_orthonormalize, symmetric_eigs

SRC = Path(__file__).resolve().parents[2] / "src" / "windflutter"
N, K_SPRING, MASS = 40, 3.0e4, 2.0


def chain(n=N):
    K = sp.diags([2 * K_SPRING * np.ones(n), -K_SPRING * np.ones(n - 1), -K_SPRING * np.ones(n - 1)], [0, 1, -1]).tolil()
    K[n - 1, n - 1] = K_SPRING  # free end
    return K.tocsr(), sp.identity(n, format="csr") * MASS


def exact(n=N):
    j = np.arange(1, n + 1)
    return 4 * K_SPRING / MASS * np.sin((2 * j - 1) * np.pi / (2 * (2 * n + 1))) ** 2


def test_dense_sparse_and_inverted_paths_give_the_analytic_chain():
    K, M = chain()
    ref = exact()
    w_full, V_full = symmetric_eigs(K.toarray(), M.toarray())
    np.testing.assert_allclose(w_full, ref, rtol=1e-10)
    w6, V6 = symmetric_eigs(K.toarray(), M.toarray(), 6)
    np.testing.assert_allclose(w6, ref[:6], rtol=1e-10)
    ws, Vs = symmetric_eigs(K, M, 6, shift=0.0, v0=np.ones(N))
    np.testing.assert_allclose(ws, ref[:6], rtol=1e-10)
    wv, none = symmetric_eigs(K, M, 1, shift=-1.0, vectors=False)
    assert none is None and wv[0] == pytest.approx(ref[0], rel=1e-10)
    wi, Vi = symmetric_eigs(K.toarray(), M.toarray(), 6, shift=-1.0, inverted=True)
    np.testing.assert_allclose(wi, ref[:6], rtol=1e-10)
    for V in (V6, Vs, Vi):  # the same modes up to sign, unit modal mass after normalisation
        U = mass_normalize(V, M)
        np.testing.assert_allclose(U.T @ (M @ U), np.eye(6), atol=1e-10)
        np.testing.assert_allclose(np.abs(U.T @ (M @ V_full[:, :6])), np.eye(6), atol=1e-8)


def test_inverted_path_takes_a_singular_mass():
    """A massless DOF (a spring in series at the root, no mass at its inner node): the inverted form
    gives the chain with the two root springs in series, K_root = k/2."""
    K, M = chain(N + 1)
    M = M.tolil()
    M[0, 0] = 0.0  # the inner node of two springs k in series
    w, _ = symmetric_eigs(K.toarray(), M.toarray(), 4, shift=-1.0, inverted=True)
    # condensed: the first spring of the chain becomes k/2 -- solve that reference densely
    Kc, Mc = chain(N)
    Kc = Kc.toarray()
    Kc[0, 0] = K_SPRING / 2 + K_SPRING
    ref = np.linalg.eigvalsh(Kc / MASS)[:4]
    np.testing.assert_allclose(w, ref, rtol=1e-9)


def test_m_orthonormalize_spans_drops_dependent_directions_and_orders():
    _, M = chain()
    rng = np.random.default_rng(3)
    A = rng.standard_normal((N, 4))
    V = np.hstack([A, A[:, :1] + A[:, 1:2]])  # a dependent fifth column
    for first in (True, False):
        Q = m_orthonormalize(V, M, largest_first=first)
        assert Q.shape == (N, 4)
        np.testing.assert_allclose(Q.T @ (M @ Q), np.eye(4), atol=1e-12)
        P = Q @ (Q.T @ (M @ A))  # the M-projection onto span(Q) reproduces A
        np.testing.assert_allclose(P, A, atol=1e-10)
    G = V.T @ (M @ V)
    np.testing.assert_array_equal(m_orthonormalize(V, M, gram=G), m_orthonormalize(V, M))  # the same Gram


#: inline eigen-solves of symmetric pencils left outside structure/modal.py, each with its reason
ALLOWED_EIGEN_CALLS = {
    "structure/prestress.py": "buckling pencil (-Kg, K), largest algebraic: not a modal problem",
}


def test_no_inline_symmetric_eigen_solve_outside_the_solver():
    found = {}
    for path in SRC.rglob("*.py"):
        rel = path.relative_to(SRC).as_posix()
        if rel == "structure/modal.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call):
                f = node.func
                name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
                # G = V^T M V Gram matrices (np.linalg.eigh of one matrix) belong to m_orthonormalize too
                if name in ("eigh", "eigsh"):
                    found.setdefault(rel, []).append(node.lineno)
    assert set(found) == set(ALLOWED_EIGEN_CALLS), found
