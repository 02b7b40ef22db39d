"""The fast p-k tracking: the Newton refinement of a tracked root and the clusters of
near-repeated roots (the copies of a blade mode on a 3-bladed rotor).

References: the dense QZ solve of the companion pencil (``solve_qep_dense``) for the Newton
root, and analytic damping crossings of uncoupled oscillators for the onset logic.
"""

import numpy as np
import pytest

from windflutter.solve.qep import qep_pencil, solve_qep_dense
from windflutter.frozen.pk_roots import PencilSystem, newton_mode, pk_mode
from windflutter.frozen.search import _clusters, _relabel, _similarity, _subspace_mac, pk_search


class _FreqSystem:
    """A random 6-DOF system whose damping and stiffness depend on the frequency (like aero)."""

    def __init__(self, seed=1):
        rng = np.random.default_rng(seed)
        A = rng.standard_normal((6, 6))
        self.M = A @ A.T / 6 + np.eye(6)
        B = rng.standard_normal((6, 6))
        self.Ks = B @ B.T * 20 + 5 * np.eye(6)
        self.D0 = 0.05 * (rng.standard_normal((6, 6)) + 1j * rng.standard_normal((6, 6)))
        self.K1 = 0.2 * rng.standard_normal((6, 6))
        self.eig_cache, self.size = {}, 6

    def matrices(self, w):
        return self.M, self.D0 * (1 + 0.1 * np.sin(w)), self.Ks + self.K1 * np.cos(0.3 * w)

    def newton_pencil(self, lam, w):
        return qep_pencil(*self.matrices(w), lam)

    def structural_pencil(self):
        return self.Ks, self.M


def test_newton_root_is_the_pk_fixed_point_of_the_dense_solve():
    # The Newton root must be an eigenvalue of the frozen-frequency problem at w = Im(lambda)
    # (the p-k fixed point): it equals the QZ eigenvalue nearest it to 1e-8 relative (the
    # Newton stopping tolerance), and its frequency is the one the matrices were frozen at.
    s = _FreqSystem()
    e0 = solve_qep_dense(*s.matrices(0.0))
    for lam0, x0 in zip(e0.values[e0.values.imag > 0][:3], e0.vectors[:, e0.values.imag > 0][:, :3].T):
        lam, x, ok = newton_mode(s, lam0, x0)
        assert ok
        ref = solve_qep_dense(*s.matrices(lam.imag), shift=lam, n_eig=1).values[0]
        assert abs(lam - ref) <= 1e-8 * abs(lam)
        # and the same root as the plain p-k iteration of frozen-frequency eigen-solves
        lam_pk, _ = pk_mode(s, lam0.imag, x0, tol=1e-12, n_eig=12)
        assert abs(lam - lam_pk) <= 1e-8 * abs(lam)


def _blades(p, split=0.0, cross=(8.0, 8.0, 8.0)):
    """Three identical 2-DOF 'blades' mixed by one rotation of all 6 DOFs (an OperatingSystem
    stand-in).  Blade j: 2 rad/s (damped) and 3 (1 + split j) rad/s with Re(lambda) =
    -0.15 (cross_j - p): its second mode flutters exactly at p = cross_j."""
    Q = np.linalg.qr(np.random.default_rng(5).standard_normal((6, 6)))[0]
    k = np.concatenate([[4.0, 9.0 * (1 + split * j) ** 2] for j in range(3)])
    d = np.concatenate([[1.0, 0.3 * (c - p)] for c in cross])
    K = Q @ np.diag(k) @ Q.T
    D = Q @ np.diag(d) @ Q.T
    return PencilSystem(lambda w: (np.eye(6), D, K), K, np.eye(6))


@pytest.mark.parametrize("split", [0.0, 1e-3, 1e-2])
def test_onset_of_repeated_blade_modes(split):
    # Exactly repeated (split 0) and near-repeated roots: shapes are arbitrary inside the
    # cluster, the onset is still the analytic p = 7.7 of the least stable copy, at 3 (1 + split j)
    # rad/s; root-finding tolerance 1e-8, so 1e-6 is a failure of the logic, not of accuracy.
    on = pk_search(lambda p: _blades(p, split, cross=(8.2, 7.7, 8.9)), np.arange(0.5, 12.0, 1.0), n_track=6, n_eig=6,
                   xtol=1e-8, divergence=False, stop_at_onset=False)
    assert on.flutter == pytest.approx(7.7, abs=1e-6)
    assert on.flutter_frequency == pytest.approx(3.0 * (1 + split), rel=1e-6)
    # every grid point has the three copies of |lambda| = 3 (1 + split j) rad/s once each (none
    # lost, none duplicated): lambda^2 + d lambda + k = 0 has |lambda|^2 = k while it oscillates
    # (1e-7: the Newton steps stop at 1e-8 relative)
    # from p = 3.5 on: below, the damping ratio exceeds 0.3 and such roots are refined only
    # 4 steps (not onset candidates, by design)
    mods = np.sort(np.abs(on.eigenvalues[on.params >= 3.5]), axis=1)
    assert np.allclose(mods[:, 3:], 3.0 * (1 + split * np.arange(3)), rtol=1e-7)


def test_cluster_subspace_and_relabel():
    # two modes with the same root: a rotation inside their plane keeps the subspace (MAC 1)
    # while the individual MACs drop; relabel puts each shape back on the mode it matches
    rng = np.random.default_rng(0)
    X = np.linalg.qr(rng.standard_normal((8, 3)))[0].astype(complex)
    c, s_ = np.cos(0.7), np.sin(0.7)
    Y = X.copy()
    Y[:, 0], Y[:, 1] = c * X[:, 0] + s_ * X[:, 1], -s_ * X[:, 0] + c * X[:, 1]
    a = [(-0.1 + 10j, X[:, 0]), (-0.1 + 10.01j, X[:, 1]), (-0.1 + 20j, X[:, 2])]
    b = [(-0.1 + 10.01j, Y[:, 0]), (-0.1 + 10j, Y[:, 1]), (-0.1 + 20j, X[:, 2])]
    groups = _clusters(a, b)
    assert sorted(map(sorted, groups)) == [[0, 1], [2]]
    assert _subspace_mac(X[:, :2], Y[:, :2]) == pytest.approx(1.0, abs=1e-12)
    assert _similarity(a, b, groups) == pytest.approx(1.0, abs=1e-12)
    swapped = [b[1], b[0], b[2]]
    assert [r[0] for r in _relabel(a, swapped, groups)] == [b[0][0], b[1][0], b[2][0]]


def test_newton_sparse_path_equals_dense():
    # full-order models hand sparse matrices to the Newton iteration (sparse LU per step)
    import scipy.sparse as sp

    s = _FreqSystem(seed=3)
    sparse = PencilSystem(lambda w: tuple(sp.csr_matrix(A) for A in s.matrices(w)), sp.csr_matrix(s.Ks),
                          sp.csr_matrix(s.M))
    e0 = solve_qep_dense(*s.matrices(0.0))
    i = int(np.argmax(e0.values.imag > 0))
    a = newton_mode(s, e0.values[i], e0.vectors[:, i])
    b = newton_mode(sparse, e0.values[i], e0.vectors[:, i])
    assert a[2] and b[2]
    assert abs(a[0] - b[0]) <= 1e-12 * abs(a[0])


def test_static_distance_lu_path_equals_the_spectrum():
    # above STATIC_DENSE_LIMIT DOFs the signed distance from static singularity comes from one
    # LU (sign of det) and Arnoldi (min |mu|); below, from the whole spectrum.  Same value (to
    # the 1e-8 of ARPACK's convergence) on both sides of a zero crossing: K = K0 - p diag(e_0)
    # becomes singular at p = K0[0, 0] - (coupling) for this diagonally dominant K0.
    import windflutter.frozen.pk_roots as search  # the module whose limit static_min_eig reads

    rng = np.random.default_rng(2)
    n = 320
    A = rng.standard_normal((n, n)) * 0.01
    K0 = np.diag(np.linspace(1.0, 50.0, n)) + A
    M = np.eye(n) + 0.001 * (A + A.T)
    vals = []
    for p in (0.5, 1.5):
        K = K0.copy()
        K[0, 0] -= p
        sysp = type("S", (), {"matrices": lambda self, w, K=K: (M, None, K)})()
        old = search.STATIC_DENSE_LIMIT
        try:
            search.STATIC_DENSE_LIMIT = 10 * n
            dense = search.static_min_eig(sysp)
            search.STATIC_DENSE_LIMIT = n - 1
            lu = search.static_min_eig(sysp)
        finally:
            search.STATIC_DENSE_LIMIT = old
        assert lu == pytest.approx(dense, rel=1e-8)
        vals.append(lu)
    assert vals[0] > 0 > vals[1]  # the crossing is seen by both


def test_newton_pencil_equals_the_matrices():
    # OperatingSystem.newton_pencil forms T(lam) and T'(lam) x of a projected model from the
    # rank-one circulatory factors; it must equal lam^2 Mt + lam Dt + Kt of matrices() (1e-12)
    from windflutter.model import load_turbine
    from windflutter.frozen.turbine import TurbineOptions, TurbineStability

    ts = TurbineStability(load_turbine("nrel5mw"), TurbineOptions(mesh={"n_span": 6, "part": "rotor"}, basis_modes=8))
    _, _, am = ts.model(0.0)
    sysx = am.at(10.0, 1.5)
    x = np.random.default_rng(1).standard_normal(am.size) + 0j
    for lam, w in ((-0.3 + 12.0j, 12.2), (-2.0 + 0.5j, 0.0)):
        T, Tp = sysx.newton_pencil(lam, w)
        M, D, K = sysx.matrices(w)
        ref = lam**2 * M + lam * D + K
        assert np.abs(T - ref).max() <= 1e-12 * np.abs(ref).max()
        r = (2 * lam) * (M @ x) + D @ x
        assert np.abs(Tp(x) - r).max() <= 1e-12 * np.abs(r).max()
