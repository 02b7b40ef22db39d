"""Frequency and damping of the modes in a sampled free response: the matrix-pencil method.

A free response of a linear(ised) system sampled at a constant step ``dt`` is a sum of damped
exponentials ``y_c(k) = sum_i A_ic z_i^k`` with ``z_i = exp(lambda_i dt)``.  The matrix pencil
(Hua & Sarkar, IEEE Trans. ASSP 38:814, 1990), here for several channels at once:

1. the Hankel matrices of every channel, ``Y_c[r, j] = y_c(r + j)`` (``L + 1`` columns,
   ``L`` the pencil parameter, about a third of the samples), stacked;
2. their SVD; the signal subspace is the leading ``order`` right singular vectors ``V``
   (``order`` from the singular values above ``sv_tol`` times the largest, or given);
3. ``z_i`` the eigenvalues of ``pinv(V[:-1]) V[1:]`` (rows = lags);
4. amplitudes by linear least squares, and the fit residual.

A mode is reported once (``frequency >= 0``) with its damping ratio ``zeta = -Re(lambda) /
|lambda|``, its share of the response energy, and a confidence measure: the relative fit
residual of the whole response and the spread of ``lambda`` between the first and the second
half of the record identified separately (a mode that is real decays or grows at one rate in
both halves).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.errors import InputError

__all__ = ["IdentifiedMode", "Identification", "matrix_pencil", "identify", "dominant"]


@dataclass(frozen=True)
class IdentifiedMode:
    """One identified mode: ``lam`` (1/s), frequency (Hz), damping ratio, its energy share of the
    fitted response, and the half-record spreads of its growth rate ``sigma`` (1/s) and
    frequency (Hz) (NaN when the halves did not both find it)."""

    lam: complex
    frequency_hz: float
    zeta: float
    share: float
    sigma_spread: float = np.nan
    frequency_spread_hz: float = np.nan

    @property
    def sigma(self) -> float:
        """Growth rate Re(lambda) (1/s): negative decays."""
        return float(self.lam.real)


@dataclass(frozen=True)
class Identification:
    """Modes (largest share first) and the relative residual of the fit."""

    modes: tuple
    residual: float


def _check_signal(y, dt):
    y = np.asarray(y, float)
    if y.ndim == 1:
        y = y[None, :]
    if y.ndim != 2 or y.shape[1] < 8 or not np.all(np.isfinite(y)):
        raise InputError("signal", y.shape, "finite samples (channels, at least 8 samples)")
    if not (np.isfinite(dt) and dt > 0):
        raise InputError("dt", dt, "a positive sample step (s)")
    return y


def matrix_pencil(y, dt: float, order: int | None = None, sv_tol: float = 1e-6,
                  pencil: int | None = None) -> tuple[np.ndarray, np.ndarray, float]:
    """``(lam (order,), amplitudes (order, channels), residual)`` of the samples ``y``
    (channels, samples) at step ``dt`` (module docstring)."""
    y = _check_signal(y, dt)
    nc, N = y.shape
    L = int(pencil) if pencil is not None else max(2, N // 3)
    L = min(L, N - 2)
    rows = N - L
    Y = np.concatenate([np.lib.stride_tricks.sliding_window_view(yc, L + 1)[:rows] for yc in y], axis=0)
    scale = np.abs(Y).max()
    if scale == 0:
        return np.zeros(0, complex), np.zeros((0, nc)), 0.0
    _, sv, Vh = np.linalg.svd(Y / scale, full_matrices=False)
    if order is None:
        order = int(np.sum(sv > sv_tol * sv[0]))
    order = max(1, min(int(order), L))
    V = Vh[:order].conj().T  # (L + 1, order)
    z = np.linalg.eigvals(np.linalg.pinv(V[:-1]) @ V[1:])
    z = z[np.abs(z) > 1e-12]
    lam = np.log(z.astype(complex)) / dt
    k = np.arange(N)
    Z = np.exp(np.outer(k * dt, lam))
    A, *_ = np.linalg.lstsq(Z, y.T.astype(complex), rcond=None)
    fit = (Z @ A).real
    res = float(np.linalg.norm(fit - y.T) / max(np.linalg.norm(y), 1e-300))
    return lam, A, res


def _modes(lam, A, t_len):
    """Positive-frequency (and real) poles with their energy over the record."""
    keep = lam.imag >= -1e-9 * np.maximum(np.abs(lam), 1.0)
    energy = []
    for li, ai in zip(lam, A):
        # energy of a A exp(lam t) over [0, t_len], summed over channels
        s2 = 2.0 * li.real
        w = t_len if abs(s2 * t_len) < 1e-9 else np.expm1(s2 * t_len) / s2
        energy.append(float(np.sum(np.abs(ai) ** 2)) * w)
    energy = np.asarray(energy)
    pair = np.where(np.abs(lam.imag) > 1e-9 * np.maximum(np.abs(lam), 1.0), 2.0, 1.0)
    return lam[keep], (pair * energy)[keep] / max(energy.sum(), 1e-300)


def identify(t, y, order: int | None = None, sv_tol: float = 1e-6, min_share: float = 1e-3,
             max_samples: int = 1200) -> Identification:
    """The modes of the response ``y`` (samples, channels) or (samples,) at uniform times ``t``.

    ``order``: number of exponentials (twice the oscillatory modes); default from ``sv_tol``.
    Modes below ``min_share`` of the energy are dropped.  Each mode carries the spread of its
    pole between the two halves of the record (the confidence measure with the residual).
    A record longer than ``max_samples`` is decimated by an integer factor (every k-th sample:
    a response integrated at tens of steps per period keeps several samples per period).
    """
    t = np.asarray(t, float)
    y = np.asarray(y, float)
    y = y.reshape(len(t), -1).T if y.ndim == 1 or y.shape[0] == len(t) else y
    if t.ndim != 1 or len(t) < 16:
        raise InputError("t", t.shape, "at least 16 sample times")
    dt = float(np.mean(np.diff(t)))
    if not np.allclose(np.diff(t), dt, rtol=1e-6, atol=0.0):
        raise InputError("t", "non-uniform", "uniformly spaced sample times")
    k = max(1, int(np.ceil(len(t) / max_samples)))
    t, y, dt = t[::k], y[:, ::k], dt * k
    lam, A, res = matrix_pencil(y, dt, order, sv_tol)
    pos, share = _modes(lam, A, t[-1] - t[0])
    half = len(t) // 2
    halves = [matrix_pencil(y[:, :half], dt, order, sv_tol)[0], matrix_pencil(y[:, half:], dt, order, sv_tol)[0]]
    modes = []
    for li, sh in sorted(zip(pos, share), key=lambda p: -p[1]):
        if sh < min_share:
            continue
        near = [h[np.argmin(np.abs(h - li))] if h.size else np.nan for h in halves]
        ok = all(np.isfinite(x) and abs(x - li) < 0.25 * max(abs(li), 1e-12) for x in near)
        ss = float(abs(near[0].real - near[1].real)) if ok else np.nan
        fs = float(abs(abs(near[0].imag) - abs(near[1].imag)) / (2 * np.pi)) if ok else np.nan
        modes.append(IdentifiedMode(lam=complex(li), frequency_hz=float(abs(li.imag) / (2 * np.pi)),
                                    zeta=float(-li.real / max(abs(li), 1e-300)), share=float(sh),
                                    sigma_spread=ss, frequency_spread_hz=fs))
    return Identification(modes=tuple(modes), residual=res)


def dominant(ident: Identification, near_hz: float | None = None) -> IdentifiedMode:
    """The mode nearest ``near_hz`` (among the oscillatory ones), else the largest share."""
    if not ident.modes:
        raise InputError("identification", "no mode", "a response with at least one identified mode")
    if near_hz is None:
        return ident.modes[0]
    osc = [m for m in ident.modes if m.frequency_hz > 0] or list(ident.modes)
    return min(osc, key=lambda m: abs(m.frequency_hz - near_hz))
