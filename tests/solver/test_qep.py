"""QEP solver: sparse shift-invert Arnoldi vs dense QZ on the companion pencil (scipy.linalg.eig)."""

import numpy as np
import scipy.sparse as sp

from windflutter.solve.qep import qep_residual, solve_qep, solve_qep_dense, solve_qep_dense_near


def _random_system(n, seed=0):
    rng = np.random.default_rng(seed)
    # banded SPD stiffness/mass plus complex non-symmetric "aero" parts (local coupling)
    main = 2.0 + rng.random(n)
    K = sp.diags([-np.ones(n - 1), main * 1e3, -np.ones(n - 1)], [-1, 0, 1]) * 1.0
    M = sp.diags([1.0 + rng.random(n)], [0])
    A = sp.random(n, n, density=3.0 / n, random_state=seed) + 1j * sp.random(n, n, density=3.0 / n, random_state=seed + 1)
    D = sp.diags([0.5 * np.ones(n)], [0]) + 0.3 * A
    return M.tocsr(), D.tocsr().astype(complex), (K + 10 * A).tocsr()


def test_sparse_matches_dense():
    M, D, K = _random_system(120)
    shift = 5.0 + 30.0j
    d = solve_qep(M, D, K, shift=shift, n_eig=12, method="dense")
    s = solve_qep(M, D, K, shift=shift, n_eig=12, method="sparse")
    # same 12 eigenvalues nearest the shift; 1e-8 relative: both are backward-stable solvers on
    # a well-conditioned problem, so only round-off separates them
    assert np.allclose(np.sort_complex(d.values), np.sort_complex(s.values), rtol=1e-8, atol=1e-8)
    for lam, x in zip(s.values, s.vectors.T):
        assert qep_residual(M, D, K, lam, x) < 1e-10


def test_dense_near_matches_whole_spectrum():
    # the p-k search's small projected systems: shift-invert Arnoldi through a dense LU must
    # return the same n_eig eigenvalues nearest the shift as the whole QZ/geev spectrum (1e-9:
    # both backward stable on a well-conditioned problem) and be what "auto" picks for them
    M, D, K = _random_system(150, seed=3)
    M, D, K = (A.toarray() for A in (M, D, K))
    for shift in (0.0, 40.0j, 3.0 + 25.0j):
        full = solve_qep_dense(M, D, K, shift=shift, n_eig=20)
        near = solve_qep_dense_near(M, D, K, shift=shift, n_eig=20)
        auto = solve_qep(M, D, K, shift=shift, n_eig=20)
        assert np.allclose(np.sort_complex(near.values), np.sort_complex(full.values), rtol=1e-9, atol=1e-9)
        assert np.array_equal(auto.values, near.values)
        for lam, x in zip(near.values, near.vectors.T):
            assert qep_residual(M, D, K, lam, x) < 1e-10


def test_single_dof_analytic():
    # m l^2 + c l + k = 0 -> l = (-c +- sqrt(c^2 - 4 m k)) / 2m
    m, c, k = 2.0, 0.3, 50.0
    e = solve_qep(np.array([[m]]), np.array([[c]]), np.array([[k]]), n_eig=2)
    exact = np.roots([m, c, k])
    assert np.allclose(np.sort_complex(e.values), np.sort_complex(exact), rtol=1e-12)
    assert np.all(e.damping_ratio > 0)


def test_no_wind_no_rotation_gives_structural_modes():
    # coupled wing system with (almost) no air: eigenvalues -> +-i omega of the structural
    # pencil (K, M).  The air must go too, not only the wind: the apparent mass pi rho b^2
    # (3.2 kg/m here, 9 % of the wing's 35.7 kg/m) does not vanish as U -> 0.  1e-4 relative:
    # rho = 1e-9 kg/m^3 and U = 1e-3 m/s leave perturbations of O(1e-10).
    import scipy.linalg as sla

    from windflutter.frozen.wing import WingConfig, wing_model

    cfg = WingConfig(span=6.096, chord=1.8288, elastic_axis=0.33, mass_axis=0.43, bending_stiffness=9.77e6,
                     torsion_stiffness=0.987e6, mass=35.71, inertia=8.64, n_elements=8, n_modes=6,
                     air_density=1e-9)
    m = wing_model(cfg)
    w_struct = np.sqrt(sla.eigh(m.Kr0, m.Mr, eigvals_only=True))
    s = m.at(1e-3, 0.0)
    e = solve_qep(*s.matrices(0.0), n_eig=12)
    w = np.sort(e.values.imag[e.values.imag > 0])
    assert np.allclose(w, np.sort(w_struct), rtol=1e-4)
