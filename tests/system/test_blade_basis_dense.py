"""The dense basis of a small blade with massless DOFs (a coarse shell's drilling rotations): its
modes are those of the pencil with the massless DOFs condensed out, computed here independently
(exact static condensation, then the ordinary symmetric eigenproblem)."""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from windflutter.system.blade_basis import dense_modes


def chain(n_mass: int = 8, n_free: int = 5, seed: int = 3):
    """A fixed-free spring chain with random springs; every other node massless, plus ``n_free``
    massless DOFs tied to the chain by springs only (a singular, not just small, mass)."""
    rng = np.random.default_rng(seed)
    n = 2 * n_mass + n_free
    K = np.zeros((n, n))
    k = rng.uniform(1.0, 3.0, 2 * n_mass)
    for i in range(2 * n_mass):  # node i tied to node i-1 (the root to ground)
        K[i, i] += k[i]
        if i > 0:
            K[i - 1, i - 1] += k[i]
            K[i, i - 1] -= k[i]
            K[i - 1, i] -= k[i]
    for j in range(n_free):  # massless DOF j on chain node 2j+1
        a, b = 2 * n_mass + j, 2 * j + 1
        c = rng.uniform(0.5, 2.0)
        K[a, a] += c
        K[b, b] += c
        K[a, b] -= c
        K[b, a] -= c
    M = np.zeros((n, n))
    M[np.arange(0, 2 * n_mass, 2), np.arange(0, 2 * n_mass, 2)] = rng.uniform(0.5, 1.5, n_mass)
    return K, M


def test_dense_modes_of_a_pencil_with_massless_dofs_equal_the_condensed_ones():
    K, M = chain()
    n = 4
    V = dense_modes(K, M, n)
    m = np.diag(M) > 0
    Kc = K[np.ix_(m, m)] - K[np.ix_(m, ~m)] @ np.linalg.solve(K[np.ix_(~m, ~m)], K[np.ix_(~m, m)])
    w2_ref = sla.eigh(Kc, M[np.ix_(m, m)], eigvals_only=True)[:n]
    w2 = np.einsum("ij,ik,kj->j", V, K, V) / np.einsum("ij,ik,kj->j", V, M, V)
    assert np.allclose(w2, w2_ref, rtol=1e-9)  # round-off of a 21-DOF pencil
    # the check can fail: the ordinary form on the same singular pencil gives other (round-off) roots
    w2_plain = sla.eigh(K, M + 1e-14 * np.eye(len(K)), eigvals_only=True)[:n]
    assert not np.allclose(w2_plain, w2_ref, rtol=1e-3)


def test_dense_modes_of_a_regular_pencil_are_the_ordinary_ones():
    K, M = chain()
    M = M + np.diag(np.where(np.diag(M) > 0, 0.0, 0.3))
    V = dense_modes(K, M, 3)
    w2 = np.einsum("ij,ik,kj->j", V, K, V) / np.einsum("ij,ik,kj->j", V, M, V)
    assert np.allclose(w2, sla.eigh(K, M, eigvals_only=True)[:3], rtol=1e-10)


def test_dense_modes_with_an_indefinite_stiffness_keep_the_ordinary_form():
    """A buckled panel (K not positive definite) cannot take the inverted form: the ordinary one, as
    before, with its negative root first (the structure's instability stays visible)."""
    K, M = chain()
    M = M + np.diag(np.where(np.diag(M) > 0, 0.0, 1e-14))  # numerically positive, singular in effect
    K[0, 0] -= 10.0  # the root spring negative: one negative root
    V = dense_modes(K, M, 2)
    w2 = np.einsum("ij,ik,kj->j", V, K, V) / np.einsum("ij,ik,kj->j", V, M, V)
    assert w2[0] < 0
