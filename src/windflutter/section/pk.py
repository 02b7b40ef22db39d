"""p-k method of the typical section: per-mode k iteration, tracking along a path, onset.

The path parameter ``x`` is the airspeed for a plain section and the rotor speed for the
seed's rotor simple model (:mod:`windflutter.frozen.simple_model`); ``sec_at(x)`` gives the
section and its airspeed there.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy import optimize

from windflutter.aero.theodorsen import theodorsen
from windflutter.errors import ConvergenceError
from windflutter.section.matrices import (
    CirculationFunction,
    c_scalar,
    companion_parts,
    natural_frequencies,
)
from windflutter.section.model import TypicalSection
from windflutter.section.results import (
    SectionResult,
    StabilityCurves,
    check_speeds,
    default_speeds,
    extrapolate,
    section_result,
)

SectionAt = Callable[[float], tuple[TypicalSection, float]]


def pk_eigen(
    sec: TypicalSection,
    U: float,
    lam_guess: complex,
    *,
    frozen_omega: float | None = None,
    c_func: CirculationFunction = theodorsen,
    tol: float = 1e-10,
    max_iter: int = 200,
    mode_index: int | None = None,
) -> tuple[complex, np.ndarray, float]:
    """p-k eigenvalue of one mode at speed U: iterate ``k = |Im lam| b / U`` to convergence.

    Parameters
    ----------
    sec, U
        Section and airspeed (m/s, > 0).
    lam_guess
        Starting eigenvalue (rad/s); the mode followed is the eigenvalue (Im >= 0) nearest to the
        current estimate.
    frozen_omega
        If given, k is frozen at ``frozen_omega b / U`` (the seed's assumption); no iteration.
    c_func
        Circulation function (default exact Theodorsen; e.g. ``lambda k: 1`` for quasi-steady).
    mode_index
        If given and both roots of the eigenproblem (at the mode's k) are oscillatory, the mode
        is the ``mode_index``-th root in ascending frequency (the usual p-k root ordering,
        robust near frequency coalescence); otherwise the root nearest the estimate.

    Returns
    -------
    lam, eigenvector (h down), k
    """
    b = sec.semi_chord
    base, dC = companion_parts(sec, U)

    def solve(omega: float, ref: complex) -> tuple[complex, np.ndarray, float]:
        k = omega * b / U
        lams, V = np.linalg.eig(base + c_scalar(c_func, k) * dC)
        return _pick_root(lams, V, ref, mode_index) + (k,)

    lam = complex(lam_guess)
    if frozen_omega is not None:
        return solve(frozen_omega, lam)
    lam, vec, converged = _frequency_fixed_point(solve, lam, tol, max_iter)
    # a (nearly) non-oscillatory, overdamped root: k is ~0 and its exact value is immaterial
    # (such roots are never reported as flutter)
    if converged or abs(lam.imag) < 0.05 * abs(lam):
        return lam, vec, abs(lam.imag) * b / U
    raise ConvergenceError(f"p-k iteration did not converge at U = {U:.6g} m/s (lambda ~ {lam:.6g})")


def _pick_root(lams: np.ndarray, V: np.ndarray, ref: complex,
               mode_index: int | None) -> tuple[complex, np.ndarray]:
    """The followed root of the companion eigenpairs ``lams, V`` (upper half plane; see pk_eigen)."""
    n = 2
    cand = np.where(lams.imag >= -1e-12 * np.abs(lams))[0]
    if mode_index is not None and cand.size == n and np.all(
            lams[cand].imag > 1e-9 * np.abs(lams[cand])):
        j = cand[np.argsort(lams[cand].imag)[mode_index]]
    else:
        j = cand[np.argmin(np.abs(lams[cand] - ref))]
    return lams[j], V[:n, j]


def _frequency_fixed_point(solve: Callable, lam: complex, tol: float,
                           max_iter: int) -> tuple[complex, np.ndarray, bool]:
    """Fixed point ``omega -> |Im lam(omega)|`` accelerated by the secant method.

    ``solve(omega, ref)`` returns the followed root ``(lam, vector, k)`` with C at ``omega``.
    The secant step on ``F(omega) = |Im lam(omega)| - omega`` falls back to plain (after 30
    steps relaxed) fixed-point steps; a root that stays non-oscillatory (``|Im| < 0.05 |lam|``)
    after 15 steps ends the iteration.  Returns ``(lam, vector, converged)``.
    """
    omega = abs(lam.imag)
    lam, vec, _ = solve(omega, lam)
    F0 = abs(lam.imag) - omega
    w0 = omega
    omega = abs(lam.imag)
    for it in range(max_iter):
        lam_new, vec_new, _ = solve(omega, lam)
        F1 = abs(lam_new.imag) - omega
        lam, vec = lam_new, vec_new
        if abs(F1) <= tol * max(1.0, omega):
            return lam, vec, True
        denom = F1 - F0
        step = -F1 * (omega - w0) / denom if denom != 0 else F1
        w_fp = abs(lam.imag) if it < 30 else omega + 0.5 * F1
        w_new = omega + step
        # accept the secant step only if it stays positive and not wildly far from the fixed point
        if not (np.isfinite(w_new) and w_new >= 0 and abs(w_new - w_fp) <= 2 * abs(F1) + 1e-300):
            w_new = w_fp
        w0, F0, omega = omega, F1, w_new
        if it >= 15 and abs(lam.imag) < 0.05 * abs(lam):
            break
    return lam, vec, False


def _pk_track(sec_at: SectionAt, params: np.ndarray,
              lam0: np.ndarray, **kw) -> tuple[np.ndarray, list[list[np.ndarray]]]:
    """Follow each mode of ``lam0`` along a parameter path; returns lam (n_modes, n)."""
    lam = np.full((len(lam0), len(params)), np.nan + 0j)
    vecs: list[list[np.ndarray]] = [[] for _ in lam0]
    for i, x in enumerate(params):
        sec, U = sec_at(x)
        guess = lam0 if i == 0 else extrapolate(lam, i)
        try:
            for m in range(len(lam0)):
                l, v, _ = pk_eigen(sec, U, guess[m], mode_index=m, **kw)
                lam[m, i] = l
                vecs[m].append(v)
        except ConvergenceError:
            if i < 2:
                raise
            # typically beyond divergence (real root pair): stop the curves here
            return lam[:, :i], vecs
    return lam, vecs


def locate_pk_onset(
    sec_at: SectionAt,
    params: np.ndarray,
    lam0: np.ndarray,
    *,
    omega_min_ratio: float = 1e-3,
    xtol: float = 1e-10,
    max_depth: int = 5,
    **kw,
) -> dict:
    """Track p-k modes along a parameter path and locate the first flutter crossing.

    ``sec_at(x)`` returns ``(section, U)`` for the path parameter ``x`` (the airspeed for a plain
    section, the rotor speed for the rotor model).  Flutter is bracketed on the grid (a mode's
    ``sigma`` goes from < 0 to >= 0 while oscillating) and refined by Brent's method on the
    tracked mode's ``sigma``.  A root is accepted only if ``|sigma| <= 1e-6 |lambda|`` there;
    otherwise (e.g. the p-k root ordering swapped inside the cell, making ``sigma``
    discontinuous) the cell is subdivided and re-tracked, up to ``max_depth`` times.  Returns a
    dict with the curves and, if found, ``x``, ``lam_f``, ``vec``, ``k``, ``U``, ``mode``.
    ``kw`` goes to :func:`pk_eigen`.
    """
    lam, _ = _pk_track(sec_at, params, lam0, **kw)
    params = params[: lam.shape[1]]
    scale = float(np.max(np.abs(lam0.imag))) if np.max(np.abs(lam0.imag)) > 0 else 1.0
    search = _OnsetSearch(sec_at, omega_min_ratio * scale, xtol, max_depth, kw)
    out = {"params": params, "lam": lam, "x": None, "n_tracked": lam.shape[1]}
    found = search.first_root(params, lam, 0)
    if found is not None:
        xr, m, l, v, k, U = found
        out.update(x=xr, lam_f=l, vec=v, k=k, U=U, mode=m)
    return out


class _OnsetSearch:
    """The bracket, Brent and subdivision steps of :func:`locate_pk_onset`."""

    def __init__(self, sec_at: SectionAt, omega_min: float, xtol: float, max_depth: int, kw: dict):
        self.sec_at, self.omega_min, self.xtol, self.max_depth, self.kw = (
            sec_at, omega_min, xtol, max_depth, kw)

    def first_root(self, xs: np.ndarray, lams: np.ndarray, depth: int):
        """First confirmed root ``(x, mode, lam, vec, k, U)`` in the cells of ``xs`` (modes
        ``lams`` tracked on ``xs``), or None."""
        sig, om = lams.real, np.abs(lams.imag)
        for i in range(len(xs) - 1):
            modes = [m for m in range(lams.shape[0])
                     if sig[m, i] < 0 <= sig[m, i + 1] and om[m, i] > self.omega_min
                     and om[m, i + 1] > self.omega_min]
            if not modes:
                continue
            roots = [r for m in modes if (r := self.cell_root(xs[i], xs[i + 1], lams[m, i], m))]
            if roots:
                return min(roots, key=lambda r: r[0])
            if depth < self.max_depth:  # unconfirmed: subdivide this cell and look again
                sub = np.linspace(xs[i], xs[i + 1], 7)
                try:
                    sub_lam, _ = _pk_track(self.sec_at, sub, lams[:, i], **self.kw)
                except ConvergenceError:
                    continue
                found = self.first_root(sub[: sub_lam.shape[1]], sub_lam, depth + 1)
                if found is not None:
                    return found
        return None

    def cell_root(self, a: float, b: float, start: complex, m: int):
        """The confirmed crossing of mode ``m`` (seeded with ``start``) in ``[a, b]``, or None."""
        def f(x: float) -> float:
            sec, U = self.sec_at(x)
            return pk_eigen(sec, U, start, mode_index=m, **self.kw)[0].real

        try:
            fa, fb = f(a), f(b)
            if not (fa < 0 <= fb):
                return None
            xr = optimize.brentq(f, a, b, xtol=self.xtol, rtol=4 * np.finfo(float).eps)
            sec, U = self.sec_at(xr)
            l, v, k = pk_eigen(sec, U, start, mode_index=m, **self.kw)
        except ConvergenceError:
            return None
        if abs(l.real) <= 1e-6 * abs(l) + 1e-12:
            return (xr, m, l, v, k, U)
        return None


def pk_method(sec: TypicalSection, speeds: np.ndarray | None = None, *,
              c_func: CirculationFunction = theodorsen) -> SectionResult:
    """p-k flutter analysis of a typical section on ``speeds`` (m/s; default
    :func:`~windflutter.section.results.default_speeds`)."""
    speeds = default_speeds(sec) if speeds is None else check_speeds(speeds)
    lam0 = 1j * natural_frequencies(sec)
    res = locate_pk_onset(lambda U: (sec, U), speeds, lam0, c_func=c_func)
    lam = res["lam"]
    curves = StabilityCurves.from_roots(speeds[: lam.shape[1]], lam)
    flutter = None
    if res["x"] is not None:
        uf, wf = float(res["U"]), float(abs(res["lam_f"].imag))
        flutter = (uf, wf, wf * sec.semi_chord / uf, res["vec"])
    return section_result("pk", sec, curves, speeds[-1], flutter)
