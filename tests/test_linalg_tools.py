"""The shared helpers of windflutter.linalg_tools against NumPy's own operations."""

import numpy as np
import pytest

from windflutter.linalg_tools import mac, mac_matrix, skew


def test_skew_is_the_cross_product():
    rng = np.random.default_rng(0)
    v, b = rng.standard_normal((5, 4, 3)), rng.standard_normal((5, 4, 3))
    np.testing.assert_allclose(np.einsum("...ij,...j->...i", skew(v), b), np.cross(v, b), rtol=0, atol=1e-15)
    S = skew([1.0, 2.0, 3.0])
    assert S.shape == (3, 3) and np.array_equal(S, -S.T)


def test_mac_of_vectors_and_matrices():
    rng = np.random.default_rng(1)
    A = rng.standard_normal((8, 3)) + 1j * rng.standard_normal((8, 3))
    B = rng.standard_normal((8, 2)) + 1j * rng.standard_normal((8, 2))
    # invariant to a complex factor of either shape; 1 for parallel, 0 for orthogonal shapes
    assert mac(A[:, 0], (2 - 3j) * A[:, 0]) == pytest.approx(1.0, abs=1e-15)
    e = np.eye(4)
    assert mac(e[0], e[1]) == 0.0 and mac(e[0], np.zeros(4)) == 0.0
    # the matrix form is the vector form for every pair (rows: columns of A)
    M = mac_matrix(A, B)
    assert M.shape == (3, 2)
    for i in range(3):
        for j in range(2):
            assert M[i, j] == pytest.approx(mac(A[:, i], B[:, j]), rel=1e-12)
    assert np.array_equal(mac_matrix(np.zeros((4, 1)), e[:, :2]), np.zeros((1, 2)))
