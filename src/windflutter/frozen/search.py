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

from typing import Callable

import numpy as np
from scipy.optimize import brentq

from windflutter.errors import InputError
from windflutter.linalg_tools import mac, mac_matrix
from windflutter.results import Onset
from windflutter.frozen.pk_roots import STATIC_K, THESIS_K, qep, pk_mode, static_frequency, static_min_eig, structural_eig


_LOST = (complex(np.nan, np.nan), None)

#: roots closer than this (relative) belong to one cluster of near-repeated modes
CLUSTER_REL = 0.03

#: damping ratio below which (as ``-NEUTRAL_ZETA``) a tracked mode counts as unstable.  The
#: eigen-solves round Re(lambda) to ~1e-12 |lambda|, so a neutral (undamped, aerodynamically
#: uncoupled) mode must not count; a real flutter crossing passes -1e-6 within ~1e-4 RPM of its
#: zero (d zeta / d RPM ~ 0.03 per RPM on the NREL 5 MW), far inside the 0.01 RPM tolerance.
NEUTRAL_ZETA = 1e-6


def _unstable(lam: complex, zeta_tol: float = NEUTRAL_ZETA) -> bool:
    """``Re(lambda) > zeta_tol |lambda|`` (damping ratio below ``-zeta_tol``)."""
    return bool(np.isfinite(lam) and lam.real > zeta_tol * abs(lam))


def _same_root(a, b, rtol: float = 1e-6) -> bool:
    """Two tracked results that converged onto one root (same value, same shape)."""
    if a[1] is None or b[1] is None:
        return False
    return abs(a[0] - b[0]) <= rtol * max(abs(a[0]), 1.0) and mac(a[1], b[1]) > 0.99


def _track(system, seeds, n_eig):
    """p-k for every tracked mode at one parameter, one root per mode.

    ``seeds`` are ``(lam, x)`` (the mode's last known root and shape; ``x`` None for a mode
    never found).  When two modes converge onto the same root, the one less similar (MAC)
    to its own seed is solved again with that root excluded; a mode that finds no free root is
    returned lost (NaN) for this parameter only -- its seed is kept, so it is picked up again.
    """
    clustered = {i for g in _clusters(seeds, seeds) if len(g) > 1 for i in g}
    out = [_LOST if (x is None or not np.isfinite(lam)) else
           pk_mode(system, max(lam.imag, 0.0), x, n_eig=n_eig, lam0=lam, near=CLUSTER_REL if i in clustered else None)
           for i, (lam, x) in enumerate(seeds)]
    n = len(out)
    for _ in range(n):
        clash = next(((i, j) for i in range(n) for j in range(i + 1, n) if _same_root(out[i], out[j])), None)
        if clash is None:
            break
        i, j = clash
        mi, mj = mac(out[i][1], seeds[i][1]), mac(out[j][1], seeds[j][1])
        lose = j if mi >= mj else i
        taken = [r for k, r in enumerate(out) if k != lose and r[1] is not None]
        lam, x = seeds[lose]
        res = pk_mode(system, max(lam.imag, 0.0), x, n_eig=n_eig, exclude=taken)
        out[lose] = _LOST if res[1] is None or any(_same_root(res, r) for r in taken) else res
    return out


def _seeds(cur, seeds_prev):
    """Seeds for the next parameter: the current result, or the last good seed of a lost mode."""
    return [(l, x) if x is not None else sp for (l, x), sp in zip(cur, seeds_prev)]


def _light(lam) -> bool:
    """A lightly damped root (damping ratio <= 0.3): a possible onset, tracked with care."""
    return bool(np.isfinite(lam) and -lam.real <= 0.3 * abs(lam))


def _clusters(a, b, rel: float = CLUSTER_REL) -> list[list[int]]:
    """Groups of tracked modes whose roots lie within ``rel`` of each other (at ``a`` or ``b``).

    Such near-repeated roots (the copies of a blade mode on a 3-bladed rotor) have shapes that
    rotate freely inside the group's subspace as the parameter changes: their individual MAC
    says nothing about tracking quality, the subspace does.  Singletons are listed too.
    """
    n = len(b)
    parent = list(range(n))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for res in (a, b):
        lam = np.array([l if x is not None else np.nan for l, x in res], complex)
        for i in range(n):
            for j in range(i + 1, n):
                if np.isfinite(lam[i]) and np.isfinite(lam[j]) and \
                        abs(lam[i] - lam[j]) <= rel * max(abs(lam[i]), abs(lam[j])):
                    parent[find(i)] = find(j)
    groups: dict[int, list[int]] = {}
    for i in range(n):
        groups.setdefault(find(i), []).append(i)
    return list(groups.values())


def _orth(X: np.ndarray) -> np.ndarray:
    return np.linalg.qr(X)[0]


def _subspace_mac(Xa: np.ndarray, Xb: np.ndarray) -> float:
    """Smallest squared cosine of the principal angles between span(Xa) and span(Xb) (0..1)."""
    s = np.linalg.svd(_orth(Xa).conj().T @ _orth(Xb), compute_uv=False)
    return float(np.min(s) ** 2)


def _relabel(prev, cur, clusters):
    """Permute ``cur`` inside each cluster so that every mode keeps the shape nearest its own."""
    from scipy.optimize import linear_sum_assignment

    out = list(cur)
    for g in clusters:
        g = [i for i in g if prev[i][1] is not None and cur[i][1] is not None]
        if len(g) < 2:
            continue
        m = mac_matrix(np.stack([prev[i][1] for i in g], 1), np.stack([cur[i][1] for i in g], 1))
        _, col = linear_sum_assignment(-m)
        for k, i in enumerate(g):
            out[i] = cur[g[col[k]]]
    return out


def _similarity(a, b, clusters=None) -> float:
    """Tracking quality between consecutive results: the smallest MAC of the lightly damped modes.

    For a cluster of near-repeated roots (:func:`_clusters`) the subspace MAC of the group
    replaces the members' individual values.
    """
    clusters = _clusters(a, b) if clusters is None else clusters
    worst = 1.0
    for g in clusters:
        g = [i for i in g if a[i][1] is not None and b[i][1] is not None
             and _light(a[i][0]) and _light(b[i][0])]  # heavily damped: not an onset candidate
        if not g:
            continue
        if len(g) == 1:
            worst = min(worst, mac(a[g[0]][1], b[g[0]][1]))
        else:
            worst = min(worst, _subspace_mac(np.stack([a[i][1] for i in g], 1), np.stack([b[i][1] for i in g], 1)))
    return worst


def _advance(system_at, p0, cur0, seeds0, p1, n_eig, depth, max_depth=3, min_mac=0.8):
    """Track from ``p0`` to ``p1``, halving the step where the shapes change too much.

    Returns the list of ``(p, result, seeds)`` after ``p0`` (ending at ``p1``).  (A linear
    predictor of the roots at ``p1`` from the previous step was tried as the Newton start: 5 %
    fewer Newton steps, no measurable gain, not kept.)
    """
    cur1 = _track(system_at(p1), _seeds(cur0, seeds0), n_eig)
    groups = _clusters(cur0, cur1)
    cur1 = _relabel(cur0, cur1, groups)
    if depth < max_depth and _similarity(cur0, cur1, groups) < min_mac:
        pm = 0.5 * (p0 + p1)
        first = _advance(system_at, p0, cur0, seeds0, pm, n_eig, depth + 1, max_depth, min_mac)
        _, cm, sm = first[-1]
        return first + _advance(system_at, pm, cm, sm, p1, n_eig, depth + 1, max_depth, min_mac)
    return [(p1, cur1, _seeds(cur1, _seeds(cur0, seeds0)))]


def _cluster_root(res):
    """The least stable root ``(lambda, x, member)`` of a cluster's tracked results ``res``.

    Its real part is continuous in the parameter even where the members exchange shapes, so it
    is what the onset root-finding follows.
    """
    ok = [k for k, (l, x) in enumerate(res) if x is not None and np.isfinite(l)]
    if not ok:
        return complex(np.nan, np.nan), None, 0
    k = max(ok, key=lambda k: res[k][0].real)
    return res[k][0], res[k][1], k


def _cluster_onset(system_at, pa, pb, ca, cb, g, n_eig, xtol):
    """Onset ``(q0, lambda, x, mode)`` of cluster ``g`` between ``pa`` (stable) and ``pb``.

    Brent's method on the real part of the cluster's least stable root; each evaluation tracks
    the cluster from the nearest parameter already solved (continuation: small steps, so the
    Newton refinement converges and the members are not lost).
    """
    known = {pa: [ca[i] for i in g], pb: [cb[i] for i in g]}

    def solve(q):
        q_near = min(known, key=lambda k: abs(k - q))
        if q not in known:
            known[q] = _track(system_at(q), known[q_near], n_eig)
        return _cluster_root(known[q])

    try:
        q0 = brentq(lambda q: solve(q)[0].real, pa, pb, xtol=xtol)
    except ValueError:  # no sign change of the followed root (lost between the points)
        q0 = pb
    lam, xq, k = solve(q0)
    return q0, lam, xq, g[k]


def pk_search(system_at: Callable[[float], object], params, n_track: int = 8, n_eig: int = 20,
              xtol: float = 1e-3, min_frequency: float = 1e-3, divergence: bool = True,
              stop_at_onset: bool = True, max_refine: int = 3, zeta_tol: float = NEUTRAL_ZETA,
              static_k: float = STATIC_K) -> Onset:
    """p-k search over increasing ``params``.

    With ``stop_at_onset=False`` the whole grid is swept (Campbell data in ``eigenvalues``).
    Between grid points the step is halved (up to ``max_refine`` times) where a lightly damped
    mode changes shape too much (MAC < 0.8) to be followed reliably; the flutter crossing is
    checked on every sub-step, the results are reported on the grid.

    Parameters
    ----------
    system_at : p -> OperatingSystem.
    params : increasing grid of the parameter (its first value must be stable).
    n_track : number of lowest structural modes followed.
    xtol : tolerance of the onset parameter (same unit as params).
    min_frequency : a mode with Im(lambda) below this (rad/s) is static, not flutter.
    static_k : so is a mode whose reduced frequency at 75 % span is below this (:data:`STATIC_K`);
        a static crossing is found as divergence (the static stiffness turning singular).
    zeta_tol : a mode is unstable when its damping ratio is below ``-zeta_tol`` (see
        :data:`NEUTRAL_ZETA`): an undamped mode without aerodynamic coupling (e.g. a tower mode
        of a model whose tower top is held) has ``Re(lambda) = +-1e-15`` and is not flutter.
    """
    params = np.asarray(params, float)
    if params.ndim != 1 or params.size < 2 or np.any(np.diff(params) <= 0):
        raise InputError("params", params.tolist()[:5], "an increasing grid of at least 2 values")
    sys0 = system_at(params[0])
    w2, V = structural_eig(sys0)
    n_track = min(n_track, len(w2))
    modes = [(1j * float(np.sqrt(max(w2[i], 0.0))), V[:, i].astype(complex)) for i in range(n_track)]
    lams = np.zeros((params.size, n_track), complex)
    res = Onset(params=params, method="pk")
    cur = _track(sys0, modes, n_eig)
    seeds = _seeds(cur, modes)
    lams[0] = [l for l, _ in cur]
    res.vectors0 = [x for _, x in cur]
    g_prev = static_min_eig(sys0) if divergence else None
    flutter_found = False
    for ip in range(1, params.size):
        p = params[ip]
        steps = _advance(system_at, params[ip - 1], cur, seeds, p, n_eig, 0, max_refine)
        chain = [(params[ip - 1], cur)] + [(q, c) for q, c, _ in steps]
        cur, seeds = steps[-1][1], steps[-1][2]
        lams[ip] = [l for l, _ in cur]
        if divergence and res.divergence is None:
            g = static_min_eig(system_at(p))
            if g_prev > 0 >= g:
                res.divergence = brentq(lambda q: static_min_eig(system_at(q)), params[ip - 1], p, xtol=xtol)
            g_prev = g
        if not flutter_found:
            cand = []
            for (pa, ca), (pb, cb) in zip(chain[:-1], chain[1:]):
                for g in _clusters(ca, cb):
                    g = [i for i in g if ca[i][1] is not None and cb[i][1] is not None]
                    new = [i for i in g if _unstable(cb[i][0], zeta_tol) and cb[i][0].imag > min_frequency]
                    if new:  # a static root (reduced frequency below static_k) is divergence, not flutter
                        w_static = static_frequency(system_at(pb), static_k)
                        new = [i for i in new if cb[i][0].imag >= w_static]
                    if not new:
                        continue
                    if any(_unstable(ca[i][0], zeta_tol) for i in g):
                        # a member unstable already (from the first grid point on): follow each
                        # newly unstable mode on its own
                        groups = [[i] for i in new if not _unstable(ca[i][0], zeta_tol)]
                    else:
                        # the onset is where the least stable root of the cluster crosses: a
                        # continuous function of q even when near-repeated members swap shapes
                        groups = [g]
                    cand += [_cluster_onset(system_at, pa, pb, ca, cb, g, n_eig, xtol) for g in groups]
                if cand:
                    break
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
        e = qep(M, D, K, n_eig, shift=0.0)
        i = int(np.argmin(np.abs(e.values.imag)))
        if best is None or abs(e.values[i].imag) < abs(best[0].imag):
            best = (e.values[i], e.vectors[:, i], k)
    return best


def thesis_search(system_at: Callable[[float], object], params, k_values=THESIS_K, n_eig: int = 20,
                  static_k: float = STATIC_K) -> Onset:
    """The seed's search (ch. 3.3.2) over the stepped ``params``.

    Flutter: first grid point whose selected eigenvalue has ``Re >= 0`` (the seed's step 7,
    no interpolation) and a reduced frequency of at least ``static_k`` (:data:`STATIC_K`, at
    75 % span).  Below it the root is static: its crossing is divergence, at the parameter where
    ``Re`` of the selected eigenvalue, linearly interpolated from the previous grid point, is
    zero (the grid point itself when ``Re`` was already >= 0 there).  Divergence is also found
    as in the seed: ``Im`` of the selected eigenvalue changes sign between grid
    points -> linear interpolation of the parameter at ``Im = 0`` and of ``Re`` there; accepted if
    ``Re > 0``; when ``Im`` never changes sign, a quadratic through the smallest ``|Im|`` point
    and its neighbours is tried (the seed's note and fig. 3.17).
    """
    params = np.asarray(params, float)
    sel = []
    res = Onset(params=params, method="thesis")
    for ip, p in enumerate(params):
        system = system_at(p)
        lam, x, k = thesis_select(system, k_values, n_eig)
        sel.append(lam)
        if lam.real >= 0 and abs(lam.imag) < static_frequency(system, static_k):
            if res.divergence is None:  # a static root crossing: divergence, not flutter at ~0 Hz
                a = sel[-2] if ip > 0 else None
                t = 1.0 if a is None or a.real >= 0 else a.real / (a.real - lam.real)
                res.divergence = float(p if a is None else params[ip - 1] + t * (p - params[ip - 1]))
        elif res.flutter is None and lam.real >= 0:
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
