"""The eigenvalue perturbation formula on small systems, against eigenvalues re-solved after a change
(numpy's eigvals of the changed state matrix: nothing of the formula), and the veering flag."""

from __future__ import annotations

import numpy as np
import pytest

from windflutter.sensitivity.eigen import (frequency_damping, mode_vectors, pair_ratio, pair_vectors,
                                           system_derivative)
from windflutter.sensitivity.point import PAIR_LIMIT
from windflutter.system.multiblade import MultiBladeSystem


def _system(rng, n=5, nz=3, **changes) -> MultiBladeSystem:
    A = rng.standard_normal((n, n))
    M = A @ A.T + n * np.eye(n)
    B = rng.standard_normal((n, n))
    K = B @ B.T + 2 * n * np.eye(n)
    C = 0.1 * (rng.standard_normal((n, n)) + 2 * np.eye(n))
    F = 0.3 * rng.standard_normal((n, nz))
    Az = -np.diag(rng.uniform(0.5, 2.0, nz)) + 0.1 * rng.standard_normal((nz, nz))
    Bq, Bv = 0.3 * rng.standard_normal((nz, n)), 0.3 * rng.standard_normal((nz, n))
    parts = dict(M=M, C=C, K=K, F=F, A=Az, Bq=Bq, Bv=Bv)
    for k, d in changes.items():
        parts[k] = parts[k] + d
    return MultiBladeSystem(**parts, n_fixed=n, n_eta=0, n_blades=3)


def _eig_near(sys_, lam):
    ev = np.linalg.eigvals(sys_.state_matrix())
    return ev[np.argmin(np.abs(ev - lam))]


@pytest.mark.parametrize("part", ["M", "C", "K", "F", "A", "Bq", "Bv"])
def test_eigenvalue_derivative_of_every_block(part):
    """dlambda = y^H dS x / y^H x written with the blocks of the second-order system with states
    (the pencil of method p's point), for a random change of each block: within 1e-6 of central
    differences of the re-solved eigenvalues (the differences' own error is ~1e-9 at h = 1e-5)."""
    rng = np.random.default_rng(3)
    base = _system(np.random.default_rng(3))
    shape = getattr(base, part).shape
    D = rng.standard_normal(shape)
    if part in ("M", "K"):
        D = D + D.T
    h = 1e-5
    plus = _system(np.random.default_rng(3), **{part: h * D})
    minus = _system(np.random.default_rng(3), **{part: -h * D})
    lams = np.linalg.eigvals(base.state_matrix())
    lams = lams[lams.imag > 0][:4]
    mvs = mode_vectors(base, lams)
    for mv in mvs:
        fd = (_eig_near(plus, mv.lam) - _eig_near(minus, mv.lam)) / (2 * h)
        got = system_derivative(mv, **{"d" + part: D})
        assert abs(got - fd) <= 1e-6 * max(abs(fd), 1.0), (part, got, fd)


def test_frequency_and_damping_derivatives():
    """d|lambda|/2pi and d(-Re lambda/|lambda|) of a complex change, against the functions evaluated."""
    lam, d = complex(-0.3, 5.0), complex(0.02, -0.07)
    h = 1e-6
    f = lambda x: (abs(x) / (2 * np.pi), -x.real / abs(x))  # noqa: E731
    fp, fm = f(lam + h * d), f(lam - h * d)
    df, dz = frequency_damping(lam, d)
    assert df == pytest.approx((fp[0] - fm[0]) / (2 * h), rel=1e-7)
    assert dz == pytest.approx((fp[1] - fm[1]) / (2 * h), rel=1e-7)


def _pair(g: float, p: float = 0.0) -> MultiBladeSystem:
    """Two undamped oscillators coupled by ``g``, detuned by ``p``: K = [[1+p, g], [g, 1-p]] --
    frequencies^2 = 1 +- sqrt(g^2 + p^2): a veering of half-width g at p = 0."""
    K = np.array([[1.0 + p, g], [g, 1.0 - p]])
    z = np.zeros((2, 0))
    return MultiBladeSystem(M=np.eye(2), C=np.zeros((2, 2)), K=K, F=z, A=np.zeros((0, 0)), Bq=z.T, Bv=z.T,
                            n_fixed=2, n_eta=0, n_blades=3)


@pytest.mark.parametrize("g, flagged", [(1e-3, True), (0.3, False)])
def test_veering_flag(g, flagged):
    """Detuning one oscillator (dK = diag(1, 0)): at a veering (g = 1e-3) a 1 % change moves the pair
    by ``sqrt(g^2 + p^2/4)`` -- not linearly: the first-order prediction misses most of it, and the
    pair ratio is far above PAIR_LIMIT (flagged).  Well separated (g = 0.3) the ratio is below the
    limit and the derivative predicts the 1 % change to within 5 %."""
    dK = np.diag([1.0, 0.0])
    base = _pair(g)
    lams = np.linalg.eigvals(base.state_matrix())
    mv = mode_vectors(base, [lams[lams.imag > 0].max()])[0]
    ji, ij = pair_vectors(mv)
    ratio = pair_ratio(mv, system_derivative(ji, None, None, dK), system_derivative(ij, None, None, dK), 0.01)
    assert (ratio >= PAIR_LIMIT) == flagged
    predicted = system_derivative(mv, None, None, dK) * 0.01
    assert abs(predicted) > 0
    K = np.array([[1.01, g], [g, 1.0]])
    z = np.zeros((2, 0))
    changed = MultiBladeSystem(M=np.eye(2), C=np.zeros((2, 2)), K=K, F=z, A=np.zeros((0, 0)), Bq=z.T, Bv=z.T,
                               n_fixed=2, n_eta=0, n_blades=3)
    error = abs(_eig_near(changed, mv.lam) - mv.lam - predicted) / abs(predicted)
    assert (error > 0.3) if flagged else (error < 0.05)
