"""Theodorsen's function, R.T. Jones' approximation and the Roger RFA."""

import numpy as np
import pytest
from scipy import special

from windflutter.aero.theodorsen import (
    fit_roger,
    jones,
    jones_rfa,
    roger_poles,
    theodorsen,
    theodorsen_F_G,
    theodorsen_rfa,
)
from windflutter.errors import InputError

# F(k), G(k) as tabulated to 4 decimals in Bisplinghoff, Ashley & Halfman, "Aeroelasticity"
# (1955), Table 5-1 (from Theodorsen, NACA Report 496, 1935).
TABLE = [
    (0.1, 0.8319, -0.1723),
    (0.2, 0.7276, -0.1886),
    (0.3, 0.6650, -0.1793),
    (0.5, 0.5979, -0.1507),
    (1.0, 0.5394, -0.1003),
]


@pytest.mark.parametrize("k,F,G", TABLE)
def test_against_published_table(k, F, G):
    f, g = theodorsen_F_G(k)
    # 4-decimal table: rounding error <= 5e-5; 1e-4 leaves margin but catches any real error
    assert abs(f - F) < 1e-4
    assert abs(g - G) < 1e-4


def test_against_modified_bessel_form():
    # independent closed form: C = K1(ik) / (K0(ik) + K1(ik)) (Laplace-domain form of the same
    # function, evaluated with scipy's modified Bessel K of complex argument)
    k = np.geomspace(1e-4, 50, 200)
    s = 1j * k
    ref = special.kv(1, s) / (special.kv(0, s) + special.kv(1, s))
    assert np.max(np.abs(theodorsen(k) - ref)) < 1e-12


def test_limits_and_switch_continuity():
    assert theodorsen(0.0) == 1.0  # exact quasi-steady limit
    assert abs(theodorsen(1e-14) - 1.0) < 1e-12
    # k -> inf: C -> 1/2 with G ~ -1/(8k)
    c = complex(theodorsen(1e9))
    assert abs(c.real - 0.5) < 1e-12 and abs(c.imag + 1 / 8e9) < 1e-15
    # the series used below 1e-12 / above 1e8 must join the Hankel evaluation smoothly
    for k0 in (1e-12, 1e8):
        lo, hi = theodorsen([k0 * (1 - 1e-9), k0 * (1 + 1e-9)])
        assert abs(lo - hi) < 1e-13 + 1e-9 * abs(lo)
    # monotone approach: F decreases from 1 to 1/2
    F, _ = theodorsen_F_G(np.geomspace(1e-6, 1e4, 500))
    assert np.all(np.diff(F) < 0) and F[0] < 1 and F[-1] > 0.5


def test_vectorised_shape_and_symmetry():
    k = np.linspace(-2, 2, 12).reshape(3, 4)
    c = theodorsen(k)
    assert c.shape == (3, 4)
    assert np.allclose(theodorsen(-k), np.conj(c))
    with pytest.raises(InputError):
        theodorsen([0.1, np.nan])


def test_jones_approximation():
    k = np.linspace(0, 3, 301)
    assert jones(0.0) == 1.0
    assert abs(jones(1e12) - 0.5) < 1e-9
    # R.T. Jones' fit is known to be within about 1.5e-2 of C(k) (NACA Rep. 681)
    assert np.max(np.abs(jones(k) - theodorsen(k))) < 0.02
    assert np.allclose(jones_rfa()(k), jones(k), atol=1e-14)


def test_fit_roger_recovers_exact_rational_function():
    # a matrix-valued function that IS of Roger form must be recovered exactly
    poles = np.array([0.2, 0.9])
    A0 = np.array([[1.0, -2.0], [0.5, 3.0]])
    A1 = np.array([[0.1, 0.0], [-0.3, 0.2]])
    A2 = np.array([[0.05, 0.01], [0.0, -0.02]])
    L = np.array([[[0.4, -0.1], [0.2, 0.0]], [[-0.7, 0.3], [0.1, 0.6]]])
    k = np.linspace(0, 3, 40)
    s = (1j * k)[:, None, None]
    Q = A0 + A1 * s + A2 * s**2 + L[0] * s / (s + poles[0]) + L[1] * s / (s + poles[1])
    r = fit_roger(k, Q, poles, n_poly=3)
    assert np.allclose(r.A0, A0, atol=1e-10) and np.allclose(r.A1, A1, atol=1e-10)
    assert np.allclose(r.A2, A2, atol=1e-10) and np.allclose(r.lags, L, atol=1e-10)
    assert r.rms_error < 1e-10


def test_theodorsen_rfa_accuracy():
    r = theodorsen_rfa(n_lag=4)
    k = np.linspace(0, 2, 401)
    err = np.abs(r(k) - theodorsen(k))
    assert r(0.0) == pytest.approx(1.0, abs=1e-14)  # static value exact (divergence unaffected)
    # 4 optimised poles: max error ~2e-3 on the fitted range (Jones' 2 poles: 1.5e-2)
    assert err.max() < 3e-3
    assert np.all(r.poles > 0)
    # with the heuristic (non-optimised) poles the fit still converges with more poles
    e4 = np.abs(theodorsen_rfa(4, optimize_poles=False)(k) - theodorsen(k)).max()
    e8 = np.abs(theodorsen_rfa(8, optimize_poles=False)(k) - theodorsen(k)).max()
    assert e8 < e4


def test_rfa_bad_input():
    with pytest.raises(InputError):
        roger_poles(0, 1.0)
    with pytest.raises(InputError):
        fit_roger([0, 1], [1, 1], [-0.1])
