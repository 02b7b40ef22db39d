"""Label placement (no overprinting) and the damping-axis split of the figures."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize

from windflutter.post.figstyle import damping_split, spread_labels


def _qp(y, gap, lo, hi):
    """Second implementation: the same constrained least squares by SLSQP (sorted order)."""
    order = np.argsort(y, kind="stable")
    d = np.asarray(y, float)[order]
    n = d.size
    cons = [{"type": "ineq", "fun": (lambda p, k=k: p[k + 1] - p[k] - gap)} for k in range(n - 1)]
    res = minimize(lambda p: np.sum((p - d) ** 2), np.clip(d, lo, hi), jac=lambda p: 2 * (p - d),
                   constraints=cons, bounds=[(lo, hi)] * n, method="SLSQP", options={"ftol": 1e-14, "maxiter": 500})
    out = np.empty(n)
    out[order] = res.x
    return out


@pytest.mark.parametrize("seed", range(6))
def test_spread_labels_is_the_constrained_least_squares_optimum(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 14))
    y = rng.uniform(0, 10, n)
    y[: n // 3] = y[0]                      # ties and clusters, the hard case
    gap, lo, hi = 0.6, -0.5, 10.5
    p = spread_labels(y, gap, lo, hi)
    q = _qp(y, gap, lo, hi)
    # both solve a strictly convex QP: the optimum is unique; SLSQP converges to ~1e-7
    np.testing.assert_allclose(p, q, atol=1e-5)


def test_spread_labels_keeps_order_gap_and_bounds():
    y = np.array([1.0, 1.0, 1.05, 5.0, 0.98, 9.9])
    p = spread_labels(y, 0.5, 0.0, 10.0)
    s = np.sort(p)
    assert np.all(np.diff(s) >= 0.5 - 1e-12)
    assert p.min() >= 0.0 and p.max() <= 10.0
    # order kept: a label never jumps over another (ties keep their input order)
    assert list(np.argsort(p, kind="stable")) == list(np.argsort(y, kind="stable"))
    assert p[3] == pytest.approx(5.0)       # an isolated label stays where it belongs
    # too many labels for the room: the gap shrinks so that all fit
    p = spread_labels(np.zeros(11), 1.0, 0.0, 5.0)
    np.testing.assert_allclose(np.sort(p), np.linspace(0, 5, 11))


def test_damping_split_scales_the_main_axis_to_the_lightly_damped_modes():
    z = np.array([[0.01, 0.02, 0.45], [0.008, 0.03, 0.35], [0.012, 0.025, 0.30]])   # edge, tower, flap
    lo, cut, top = damping_split(z)
    assert cut == pytest.approx(1.15 * 0.03)          # the largest lightly damped value + 15 %
    assert top == pytest.approx(1.06 * 0.45)          # the flap mode on the second panel
    assert lo < 0                                     # the zero line is inside the main panel
    lo, cut, top = damping_split(np.array([[0.01, -0.02]]))
    assert top is None and lo < -0.02 and cut >= 0.02  # nothing heavily damped: one panel
