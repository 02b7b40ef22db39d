"""Searches for the first unstable point along a parameter (rotor speed, or flight speed).

Both searches work on a callable ``system_at(p) -> OperatingSystem`` (see
:mod:`windflutter.solve.aeroelastic`), so the same code serves a turbine (p = rotor speed at a
fixed wind speed) and a fixed wing (p = flight speed).

* :func:`thesis_search` -- the seed's algorithm (ch. 3.3.2): 8 reduced frequencies, the
  eigenvalue of smallest ``|Im|``, divergence by the sign change of ``Im`` (linear interpolation,
  quadratic fit when it does not change sign), flutter when that eigenvalue has ``Re >= 0``.
* :func:`pk_search` -- p-k iteration per tracked mode (``k`` matched to the mode's own
  frequency), modes followed by MAC over a grid, onset by bracketing + Brent root-finding of the
  tracked mode's ``Re(lambda)``; divergence by the smallest real eigenvalue of the static
  (k = 0) stiffness crossing zero.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.linalg as sla
from scipy.optimize import brentq

from windflutter.errors import ConvergenceError, InputError
from windflutter.solve.qep import solve_qep
from windflutter.stability.tracking import mac_matrix, mac

#: the seed's reduced frequencies (ch. 3.3.2, step 3)
THESIS_K = (0.001, 0.1429, 0.2857, 0.4286, 0.5714, 0.7143, 0.8571, 1.0)


@dataclass
class Onset:
    """First unstable point along the parameter.

    Attributes
    ----------
    flutter : parameter at flutter onset (None if none found in range).
    flutter_frequency : circular frequency at onset (rad/s).
    flutter_mode : index of the tracked mode (pk) / label.
    flutter_vector : mode shape at onset (working basis).
    divergence : parameter at divergence onset or None.
    history : per-grid-point data (params, eigenvalues of tracked modes (n_p, n_modes)).
    """

    flutter: float | None = None
    flutter_frequency: float | None = None
    flutter_mode: int | None = None
    flutter_vector: np.ndarray | None = None
    divergence: float | None = None
    params: np.ndarray = field(default_factory=lambda: np.zeros(0))
    eigenvalues: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), complex))
    method: str = "pk"
    vectors0: list | None = None


def _qep(M, D, K, n_eig, shift=0.0):
    return solve_qep(M, D, K, shift=shift, n_eig=min(n_eig, 2 * M.shape[0]))


# ---------------------------------------------------------------------------- p-k
def pk_mode(system, omega0: float, x0: np.ndarray | None, tol: float = 1e-6, maxiter: int = 40,
            n_eig: int = 20):
    """p-k iteration for one mode: solve with Theodorsen frozen at the mode's own frequency.

    Returns (lambda, x).  A mode whose frequency falls to zero is returned with the aero at k=0.
    """
    w = max(float(omega0), 0.0)
    lam, x = None, x0
    change = np.inf
    cache = getattr(system, "_qep_cache", None)
    if cache is None:
        cache = {}
        try:
            system._qep_cache = cache  # identical frequencies (symmetric blades) share solves
        except AttributeError:
            pass
    for it in range(maxiter):
        key = (w, n_eig)
        if key not in cache:
            M, D, K = system.matrices(w)
            cache[key] = _qep(M, D, K, n_eig, shift=1j * w)
        e = cache[key]
        vals, vecs = e.values, e.vectors
        phys = vals.imag >= -1e-9 * max(1.0, abs(w))
        if not np.any(phys):
            phys = np.ones_like(phys)
        vals, vecs = vals[phys], vecs[:, phys]
        if x is not None:
            m = mac_matrix(x[:, None], vecs)[0]
            score = m - 0.05 * np.abs(vals - 1j * w) / max(abs(w), 1.0)
        else:
            score = -np.abs(vals - 1j * w)
        i = int(np.argmax(score))
        lam, x_new = vals[i], vecs[:, i]
        w_new = max(lam.imag, 0.0)
        change = abs(w_new - w) / max(abs(w_new), 1.0)
        if change <= tol:
            return lam, x_new
        if it >= 4 and -lam.real > 0.3 * abs(lam):
            # heavily damped (zeta > 0.3): far from any onset; its frequency may wander between
            # close roots, so stop refining it
            return lam, x_new
        if it >= maxiter // 3:  # under-relax an oscillating iteration (heavily damped modes)
            w_new = 0.5 * (w + w_new)
        w, x = w_new, x_new
    # not converged: return the last iterate (typically a heavily damped mode whose frequency
    # keeps jumping between close roots; it does not decide the onset)
    return lam, x


def static_min_eig(system) -> float:
    """Signed distance of the static stiffness from singularity (divergence when it crosses 0).

    ``sign(det Kt(k=0)) * min |mu|`` over the eigenvalues of ``Kt x = mu M x``: continuous, and
    it changes sign exactly when a real eigenvalue crosses zero (complex pairs never flip the
    sign of the determinant).
    """
    M, D, K = system.matrices(0.0)
    Md = M.toarray() if hasattr(M, "toarray") else np.asarray(M)
    Kd = K.toarray() if hasattr(K, "toarray") else np.asarray(K)
    Kd, Md = Kd.real, Md.real
    mu = sla.eig(Kd, Md, right=False)
    mu = mu[np.isfinite(mu)]
    sK, _ = np.linalg.slogdet(Kd)
    sM, _ = np.linalg.slogdet(Md)
    return float(sK * sM * np.min(np.abs(mu)))


def _track(system, modes, n_eig):
    out = []
    for w, x in modes:
        if x is None or not np.isfinite(w):  # a mode lost earlier stays lost
            out.append((complex(np.nan, np.nan), None))
            continue
        out.append(pk_mode(system, w, x, n_eig=n_eig))
    return out


def _drop_duplicates(cur, prev, rtol: float = 1e-6):
    """Two tracked modes that landed on the same eigenvalue: keep the one more similar (MAC) to
    its own previous shape, mark the other as lost (NaN)."""
    n = len(cur)
    for i in range(n):
        for j in range(i + 1, n):
            li, lj = cur[i][0], cur[j][0]
            if cur[i][1] is None or cur[j][1] is None:
                continue
            if abs(li - lj) <= rtol * max(abs(li), 1.0) and mac(cur[i][1], cur[j][1]) > 0.99:
                mi = mac(cur[i][1], prev[i][1]) if prev[i][1] is not None else 0.0
                mj = mac(cur[j][1], prev[j][1]) if prev[j][1] is not None else 0.0
                k = j if mi >= mj else i
                cur[k] = (complex(np.nan, np.nan), None)


def pk_search(system_at: Callable[[float], object], params, n_track: int = 8, n_eig: int = 20,
              xtol: float = 1e-3, min_frequency: float = 1e-3, divergence: bool = True,
              stop_at_onset: bool = True) -> Onset:
    """p-k search over increasing ``params``.

    With ``stop_at_onset=False`` the whole grid is swept (Campbell data in ``eigenvalues``).

    Parameters
    ----------
    system_at : p -> OperatingSystem.
    params : increasing grid of the parameter (its first value must be stable).
    n_track : number of lowest structural modes followed.
    xtol : tolerance of the onset parameter (same unit as params).
    min_frequency : a mode with Im(lambda) below this (rad/s) is static, not flutter.
    """
    params = np.asarray(params, float)
    if params.ndim != 1 or params.size < 2 or np.any(np.diff(params) <= 0):
        raise InputError("params", params.tolist()[:5], "an increasing grid of at least 2 values")
    sys0 = system_at(params[0])
    M, D, K = sys0.matrices(0.0)
    Ks = sys0.Ks.toarray() if hasattr(sys0.Ks, "toarray") else sys0.Ks
    Md = sys0.model.Mr.toarray() if hasattr(sys0.model.Mr, "toarray") else sys0.model.Mr
    w2, V = sla.eigh(0.5 * (Ks + Ks.T), 0.5 * (Md + Md.T))
    n_track = min(n_track, len(w2))
    modes = [(float(np.sqrt(max(w2[i], 0.0))), V[:, i].astype(complex)) for i in range(n_track)]
    lams = np.zeros((params.size, n_track), complex)
    vecs = [None] * params.size
    res = Onset(params=params, method="pk")
    cur = _track(sys0, modes, n_eig)
    lams[0] = [l for l, _ in cur]
    vecs[0] = cur
    res.vectors0 = [x for _, x in cur]
    g_prev = static_min_eig(sys0) if divergence else None
    flutter_found = False
    for ip in range(1, params.size):
        p = params[ip]
        sysp = system_at(p)
        prev = cur
        cur = _track(sysp, [(max(l.imag, 0.0), x) for l, x in prev], n_eig)
        _drop_duplicates(cur, prev)
        lams[ip] = [l for l, _ in cur]
        vecs[ip] = cur
        if divergence and res.divergence is None:
            g = static_min_eig(sysp)
            if g_prev > 0 >= g:
                res.divergence = brentq(lambda q: static_min_eig(system_at(q)), params[ip - 1], p, xtol=xtol)
            g_prev = g
        if not flutter_found:
            cand = []
            for i, (l, _) in enumerate(cur):
                if prev[i][1] is None or cur[i][1] is None:
                    continue
                if l.real >= 0 and l.imag > min_frequency and prev[i][0].real < 0:
                    pm = params[ip - 1]
                    seed = prev[i]

                    def f(q, seed=seed):
                        lam, _ = pk_mode(system_at(q), max(seed[0].imag, 0.0), seed[1], n_eig=n_eig)
                        return lam.real

                    try:
                        q0 = brentq(f, pm, p, xtol=xtol)
                    except ValueError:
                        q0 = p
                    lam, x = pk_mode(system_at(q0), max(seed[0].imag, 0.0), seed[1], n_eig=n_eig)
                    cand.append((q0, lam, x, i))
            if cand:
                q0, lam, x, i = min(cand, key=lambda c: c[0])
                res.flutter, res.flutter_frequency, res.flutter_vector, res.flutter_mode = q0, lam.imag, x, i
                flutter_found = True
        if stop_at_onset and flutter_found and (res.divergence is not None or not divergence):
            res.params, res.eigenvalues = params[: ip + 1], lams[: ip + 1]
            return res
    res.eigenvalues = lams
    return res


# ------------------------------------------------------------------------ thesis
def thesis_select(system, k_values=THESIS_K, n_eig: int = 20):
    """The seed's steps 4-7 at one parameter: smallest-|Im| eigenvalue over the 8 k values."""
    U75, b75 = system.reference(0.75)
    best = None
    for k in k_values:
        w = k * U75 / b75
        M, D, K = system.matrices(w)
        e = _qep(M, D, K, n_eig, shift=0.0)
        i = int(np.argmin(np.abs(e.values.imag)))
        if best is None or abs(e.values[i].imag) < abs(best[0].imag):
            best = (e.values[i], e.vectors[:, i], k)
    return best


def thesis_search(system_at: Callable[[float], object], params, k_values=THESIS_K, n_eig: int = 20) -> Onset:
    """The seed's search (ch. 3.3.2) over the stepped ``params``.

    Flutter: first grid point whose selected eigenvalue has ``Re >= 0`` (the seed's step 7,
    no interpolation).  Divergence: ``Im`` of the selected eigenvalue changes sign between grid
    points -> linear interpolation of the parameter at ``Im = 0`` and of ``Re`` there; accepted if
    ``Re > 0``; when ``Im`` never changes sign, a quadratic through the smallest ``|Im|`` point
    and its neighbours is tried (the seed's note and fig. 3.17).
    """
    params = np.asarray(params, float)
    sel = []
    res = Onset(params=params, method="thesis")
    for ip, p in enumerate(params):
        lam, x, k = thesis_select(system_at(p), k_values, n_eig)
        sel.append(lam)
        if res.flutter is None and lam.real >= 0:
            res.flutter, res.flutter_frequency, res.flutter_vector = float(p), float(abs(lam.imag)), x
        if ip > 0 and res.divergence is None:
            a, b = sel[-2], sel[-1]
            if np.sign(a.imag) != np.sign(b.imag) and a.imag != 0:
                t = a.imag / (a.imag - b.imag)
                re = a.real + t * (b.real - a.real)
                if re > 0:
                    res.divergence = float(params[ip - 1] + t * (p - params[ip - 1]))
        if res.flutter is not None and res.divergence is not None:
            break
    vals = np.array(sel)
    res.params = params[: len(sel)]
    res.eigenvalues = vals[:, None]
    if res.divergence is None and len(sel) >= 3:
        i = int(np.argmin(np.abs(vals.imag)))
        i = min(max(i, 1), len(sel) - 2)
        pp = res.params[i - 1: i + 2]
        c = np.polyfit(pp, np.abs(vals[i - 1: i + 2].imag), 2)
        roots = [r.real for r in np.roots(c) if abs(r.imag) < 1e-12 and pp[0] <= r.real <= pp[-1]]
        if roots:
            r = min(roots)
            re = np.interp(r, pp, vals[i - 1: i + 2].real)
            if re > 0:
                res.divergence = float(r)
    return res
