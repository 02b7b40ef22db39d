"""Theodorsen's circulation function and its rational approximations.

Theodorsen's function (Theodorsen 1935, NACA Report 496)::

    C(k) = H1(k) / (H1(k) + i H0(k)),     Hn = Hankel function of the 2nd kind, order n

with the reduced frequency ``k = omega b / U`` (b: semi-chord).  ``C(0) = 1`` (quasi-steady),
``C(k) -> 1/2`` as ``k -> inf``.  For a harmonic motion ``exp(i omega t)`` the circulatory lift is
``C(k)`` times the quasi-steady lift.

Also provided:

* :func:`jones` -- R.T. Jones' two-pole approximation (NACA Report 681, 1940), the classic
  ``1 - 0.165 s/(s+0.0455) - 0.335 s/(s+0.3)`` with ``s = i k``;
* :func:`fit_roger` -- least-squares Roger rational-function approximation (Roger 1977, AGARD
  CP-228) of a (matrix-valued) function of ``i k`` with chosen lag poles, returning real
  coefficient matrices usable in a state-space (p-method) model; :func:`theodorsen_rfa` fits
  C(k) itself.

All functions are vectorised over ``k``.  Negative ``k`` is allowed: ``C(-k) = conj(C(k))``
(the response to a real signal).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike
from scipy import special

from windflutter.errors import InputError

__all__ = [
    "theodorsen",
    "theodorsen_F_G",
    "jones",
    "RogerRFA",
    "fit_roger",
    "roger_poles",
    "theodorsen_rfa",
]

_EULER_GAMMA = 0.5772156649015329
#: Below this |k| the 2-term small-k expansion is used (its error is O(k^2 ln^2 k) < 1e-20).
_K_SMALL = 1e-12
#: Above this |k| the large-k expansion C = 1/2 + i/(8k) ... is used (error O(1/k^2) < 1e-16).
_K_LARGE = 1e8


def theodorsen(k: ArrayLike) -> np.ndarray:
    """Theodorsen's function C(k) (complex), vectorised.

    Parameters
    ----------
    k
        Reduced frequency ``omega b / U`` (dimensionless), scalar or array, any sign.

    Returns
    -------
    numpy.ndarray
        Complex array of the shape of ``k`` (0-d array for a scalar).  ``C(0) = 1`` exactly.

    Notes
    -----
    Evaluated from scipy's Hankel functions of the second kind.  For ``|k| < 1e-12`` the expansion
    ``C = 1 - pi k/2 + i k (ln(k/2) + gamma)`` and for ``|k| > 1e8`` the expansion
    ``C = 1/2 - i/(8k)`` are used, avoiding overflow of ``Y1`` and loss of precision.
    """
    k = np.asarray(k, dtype=float)
    if np.any(~np.isfinite(k)):
        raise InputError("k", k, "finite reduced frequencies")
    ka = np.abs(k)
    out = np.empty(ka.shape, dtype=complex)
    small = ka < _K_SMALL
    large = ka > _K_LARGE
    mid = ~(small | large)
    if np.any(mid):
        km = ka[mid]
        h1 = special.hankel2(1, km)
        h0 = special.hankel2(0, km)
        out[mid] = h1 / (h1 + 1j * h0)
    if np.any(small):
        ks = ka[small]
        with np.errstate(divide="ignore", invalid="ignore"):
            log_term = np.where(ks > 0, ks * (np.log(ks / 2.0) + _EULER_GAMMA), 0.0)
        out[small] = 1.0 - np.pi * ks / 2.0 + 1j * log_term
    if np.any(large):
        kl = ka[large]
        out[large] = 0.5 - 1j / (8.0 * kl)
    neg = k < 0
    out[neg] = np.conj(out[neg])
    return out


def theodorsen_F_G(k: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Real and imaginary parts ``F(k), G(k)`` of Theodorsen's function (tabulated form)."""
    c = theodorsen(k)
    return c.real, c.imag


def jones(k: ArrayLike) -> np.ndarray:
    """R.T. Jones' approximation of C(k) (NACA Report 681).

    ``C(k) ~ 1 - 0.165 s/(s + 0.0455) - 0.335 s/(s + 0.3)`` with ``s = i k``.  Exact at
    ``k = 0`` (1) and ``k -> inf`` (1/2); error a few 1e-3 in between.
    """
    s = 1j * np.asarray(k, dtype=float)
    return 1.0 - 0.165 * s / (s + 0.0455) - 0.335 * s / (s + 0.3)


#: Jones' approximation as a Roger RFA (used in tests / as an option).
def jones_rfa() -> "RogerRFA":
    """R.T. Jones' approximation expressed as a :class:`RogerRFA` of the scalar C."""
    return RogerRFA(
        poles=np.array([0.0455, 0.3]),
        A0=np.array(1.0),
        A1=np.array(0.0),
        A2=np.array(0.0),
        lags=np.array([-0.165, -0.335]),
        k_fit=np.array([]),
        rms_error=float("nan"),
    )


@dataclass(frozen=True)
class RogerRFA:
    """Roger rational-function approximation of ``Q(s)``, ``s = i k`` (reduced Laplace variable).

    ``Q(s) ~ A0 + A1 s + A2 s^2 + sum_j lags[j] s / (s + poles[j])``

    Attributes
    ----------
    poles
        Lag poles ``beta_j > 0`` (reduced-frequency units; the dimensional pole is
        ``beta_j U / b``).
    A0, A1, A2
        Real coefficient arrays with the shape of ``Q`` (scalars for C(k)).
    lags
        Real array ``(n_lag, *Q.shape)`` of lag coefficients.
    k_fit
        Reduced frequencies used in the fit.
    rms_error
        Root-mean-square of ``|Q_fit - Q|`` over the fit points.
    """

    poles: np.ndarray
    A0: np.ndarray
    A1: np.ndarray
    A2: np.ndarray
    lags: np.ndarray
    k_fit: np.ndarray = field(repr=False)
    rms_error: float

    def __call__(self, k: ArrayLike) -> np.ndarray:
        """Evaluate the approximation at reduced frequencies ``k`` (shape ``k.shape + Q.shape``)."""
        s = 1j * np.asarray(k, dtype=float)
        qshape = np.shape(self.A0)
        s_ = s.reshape(s.shape + (1,) * len(qshape))
        out = self.A0 + self.A1 * s_ + self.A2 * s_**2
        for beta, a in zip(self.poles, self.lags):
            out = out + a * s_ / (s_ + beta)
        return out

    def evaluate_s(self, s: complex) -> np.ndarray:
        """Evaluate at a complex reduced Laplace variable ``s = p b / U``."""
        out = self.A0 + self.A1 * s + self.A2 * s**2
        for beta, a in zip(self.poles, self.lags):
            out = out + a * s / (s + beta)
        return out


def roger_poles(n_lag: int, k_max: float) -> np.ndarray:
    """Lag poles spread over the fitted range: ``beta_j = 1.7 k_max (j/(n+1))^2`` (j = 1..n).

    This is the common heuristic of Tiffany & Adams (NASA TP-2776, 1988); the poles only need to
    lie in the frequency range of interest, the least-squares fit does the rest.
    """
    if n_lag < 1:
        raise InputError("n_lag", n_lag, "an integer >= 1")
    if not (k_max > 0 and np.isfinite(k_max)):
        raise InputError("k_max", k_max, "a positive reduced frequency")
    j = np.arange(1, n_lag + 1)
    return 1.7 * k_max * (j / (n_lag + 1.0)) ** 2


def fit_roger(
    k: ArrayLike,
    Q: ArrayLike,
    poles: ArrayLike,
    *,
    n_poly: int = 3,
    exact_k0: bool = True,
    weights: ArrayLike | None = None,
) -> RogerRFA:
    """Least-squares Roger fit of tabulated ``Q(i k)`` with given lag poles.

    Parameters
    ----------
    k
        Reduced frequencies (>= 0), shape ``(nk,)``.
    Q
        Complex values, shape ``(nk, *qshape)`` (``qshape`` may be empty for a scalar function).
    poles
        Lag poles ``beta_j > 0``.
    n_poly
        Number of polynomial terms kept: 1 (A0), 2 (A0, A1) or 3 (A0, A1, A2).  For C(k), which is
        bounded, use 1.
    exact_k0
        If True and ``k[0] == 0`` the fit reproduces ``Q(0)`` exactly (A0 = Q(0)), so static
        (divergence) results are not affected by the fit.
    weights
        Optional positive weights per k.

    Returns
    -------
    RogerRFA
        Real coefficients.  Each element of Q is fitted independently (real and imaginary parts
        stacked), which is exact least squares for this linear-in-coefficients form.
    """
    k = np.asarray(k, dtype=float)
    Q = np.asarray(Q, dtype=complex)
    poles = np.asarray(poles, dtype=float)
    if k.ndim != 1 or Q.shape[0] != k.size:
        raise InputError("Q", Q.shape, f"an array whose first axis matches k ({k.size})")
    if np.any(k < 0) or np.any(~np.isfinite(k)):
        raise InputError("k", k, "finite reduced frequencies >= 0")
    if np.any(poles <= 0) or np.any(~np.isfinite(poles)):
        raise InputError("poles", poles, "positive finite lag poles")
    if n_poly not in (1, 2, 3):
        raise InputError("n_poly", n_poly, "1, 2 or 3")
    qshape = Q.shape[1:]
    Qf = Q.reshape(k.size, -1)
    s = 1j * k
    cols = [np.ones_like(s), s, s**2][:n_poly] + [s / (s + b) for b in poles]
    B = np.stack(cols, axis=1)  # (nk, ncoef) complex
    w = np.ones(k.size) if weights is None else np.asarray(weights, dtype=float)
    fix0 = exact_k0 and k[0] == 0.0
    if fix0:
        a0 = Qf[0].real
        rhs = Qf - a0[None, :]
        B_use = B[:, 1:]
    else:
        rhs = Qf
        B_use = B
    Bw = B_use * w[:, None]
    rw = rhs * w[:, None]
    Areal = np.concatenate([Bw.real, Bw.imag], axis=0)
    Rreal = np.concatenate([rw.real, rw.imag], axis=0)
    coef, *_ = np.linalg.lstsq(Areal, Rreal, rcond=None)
    if fix0:
        coef = np.vstack([a0[None, :], coef])
    fitted = B @ coef
    rms = float(np.sqrt(np.mean(np.abs(fitted - Qf) ** 2)))
    ncoef_poly = n_poly
    polys = [coef[i].reshape(qshape) for i in range(ncoef_poly)]
    while len(polys) < 3:
        polys.append(np.zeros(qshape))
    lags = coef[ncoef_poly:].reshape((poles.size,) + qshape)
    return RogerRFA(
        poles=poles, A0=polys[0], A1=polys[1], A2=polys[2], lags=lags, k_fit=k, rms_error=rms
    )


def theodorsen_rfa(
    n_lag: int = 4, k_max: float = 2.0, n_k: int = 120, optimize_poles: bool = True
) -> RogerRFA:
    """Roger approximation of C(k) alone: ``C ~ A0 + sum_j c_j s/(s + beta_j)``, ``s = i k``.

    Fitted on ``n_k`` points spaced quadratically in ``[0, k_max]`` (denser at small k, where C
    varies fastest), with ``C(0) = 1`` reproduced exactly and no polynomial terms (C is bounded).

    Parameters
    ----------
    n_lag
        Number of lag poles (aerodynamic states per circulatory input).
    k_max
        Upper end of the fitted reduced-frequency range.
    n_k
        Number of fit points.
    optimize_poles
        If True the (log of the) poles are optimised by nonlinear least squares starting from a
        geometric spread over ``[0.03, 1]``; the coefficients are always the linear least-squares
        solution for the poles.  With 4 poles the max error over ``0 <= k <= 2`` is about 2e-3
        (R.T. Jones' 2-pole fit: 1.5e-2).  If False, :func:`roger_poles` is used.
    """
    if n_k < n_lag + 2:
        raise InputError("n_k", n_k, f"at least n_lag + 2 = {n_lag + 2} fit points")
    kk = k_max * np.linspace(0.0, 1.0, n_k) ** 2
    cc = theodorsen(kk)
    if not optimize_poles:
        return fit_roger(kk, cc, roger_poles(n_lag, k_max), n_poly=1, exact_k0=True)
    from scipy.optimize import least_squares

    def residual(log_poles: np.ndarray) -> np.ndarray:
        r = fit_roger(kk, cc, np.exp(log_poles), n_poly=1, exact_k0=True)
        d = r(kk) - cc
        return np.concatenate([d.real, d.imag])

    x0 = np.log(np.geomspace(0.03, 1.0, n_lag)) if n_lag > 1 else np.array([np.log(0.15)])
    sol = least_squares(residual, x0, xtol=1e-10, ftol=1e-12)
    poles = np.sort(np.exp(sol.x))
    return fit_roger(kk, cc, poles, n_poly=1, exact_k0=True)
