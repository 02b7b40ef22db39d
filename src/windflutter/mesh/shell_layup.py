"""The layup on the shell mesh's chordwise grid: which arcs become key arcs (web attachments and
layer boundaries), layers extended to the blade ends, web keys filled where a web is absent, uncovered
contour positions filled from the nearest covered station, a layer's arc interval and material
(helpers of :mod:`windflutter.mesh.blade_shell`)."""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError

MIN_KEY_GAP = 0.004  # minimum arc gap between two key arcs anywhere on the span (-)


def choose_key_arcs(curves: list[tuple[str, np.ndarray]], max_keys: int, priority: int) -> list[tuple[str, np.ndarray]]:
    """Select a consistently ordered set of key-arc curves.

    Parameters
    ----------
    curves : (name, (n_st,) arc values) candidates; the first ``priority`` are the webs' and are
        tried first.
    max_keys : maximum number of keys kept.

    Returns
    -------
    The kept curves sorted by mean arc; every pair differs by at least ``MIN_KEY_GAP`` at all
    stations and none touches the trailing edge (arc 0 / 1).
    """
    kept: list[tuple[str, np.ndarray]] = []
    for name, c in curves:
        if len(kept) >= max_keys:
            break
        if np.any(c < MIN_KEY_GAP) or np.any(c > 1.0 - MIN_KEY_GAP):
            continue
        ok = True
        for _, k in kept:
            d = c - k
            if np.min(np.abs(d)) < MIN_KEY_GAP or not (np.all(d > 0) or np.all(d < 0)):
                ok = False
                break
        if ok:
            kept.append((name, c))
    return sorted(kept, key=lambda t: float(np.mean(t[1])))


class _ExtendedLayer:
    """A layer whose span extent is widened to the blade ends; beyond its original extent it
    keeps the thickness it has at that end."""

    def __init__(self, layer, s0: float, s1: float, lo: bool, hi: bool):
        self._l = layer
        self._s0, self._s1 = s0, s1
        self.s_start = 0.0 if lo else layer.s_start
        self.s_end = 1.0 if hi else layer.s_end
        self.name, self.material = layer.name, layer.material

    def _clamp(self, s):
        return np.clip(np.asarray(s, dtype=float), self._s0 if self.s_start == 0.0 else -np.inf, self._s1 if self.s_end == 1.0 else np.inf)

    def thickness_at(self, s):
        return self._l.thickness_at(self._clamp(s))

    def arcs_at(self, s):
        return self._l.arcs_at(self._clamp(s))

    def orientation_at(self, s):
        return self._l.orientation_at(self._clamp(s))


def extend_to_blade_ends(layers) -> list:
    """If the shell layup as a whole starts after the root (ends before the tip), the layers
    present at its first (last) position are extended with constant properties to the root
    (tip): e.g. the seed's appendix-A tables start 2 m from the root.  A layup covering the whole
    span is returned unchanged."""
    live = [lay for lay in layers if np.max(lay.thickness) > 0]
    if not live:
        return list(layers)
    s0 = min(lay.s_start for lay in live)
    s1 = max(lay.s_end for lay in live)
    out = []
    for lay in layers:
        # a layer counts as present at s0 if it starts there and has thickness just after it
        lo = s0 > 1e-9 and abs(lay.s_start - s0) < 1e-9 and float(lay.thickness_at(s0 + 1e-6)) > 0
        hi = s1 < 1 - 1e-9 and abs(lay.s_end - s1) < 1e-9 and float(lay.thickness_at(s1 - 1e-6)) > 0
        out.append(_ExtendedLayer(lay, s0, s1, lo, hi) if (lo or hi) else lay)
    return out


def fill_web_keys(raw: list, eta: np.ndarray) -> list[tuple[str, np.ndarray]]:
    """Web attachment arcs along the whole span, ordered, from their values where the webs exist.

    Outside its extent a web still needs a grid column (one structured topology): there its
    key keeps the relative position it has, at the nearest station where it exists, between
    its ordered neighbours (webs with larger extents placed first; 0 and 1 at the ends), so
    keys never cross where webs converge (e.g. a trailing-edge web ending mid-span).

    Parameters
    ----------
    raw : (name, (n_st,) arc, (n_st,) bool where the web exists).
    """
    mean = [float(np.mean(c[on])) for _, c, on in raw]
    order = list(np.argsort(mean))  # position in the chordwise ordering
    done: dict[int, np.ndarray] = {}
    idx = np.arange(len(eta))
    for k in sorted(range(len(raw)), key=lambda k: -int(raw[k][2].sum())):
        name, c, on = raw[k]
        pos = order.index(k)
        lower = [order[p] for p in range(pos - 1, -1, -1) if order[p] in done]
        upper = [order[p] for p in range(pos + 1, len(order)) if order[p] in done]
        L = done[lower[0]] if lower else np.zeros_like(c)
        U = done[upper[0]] if upper else np.ones_like(c)
        t = (c - L) / np.maximum(U - L, 1e-12)
        # its own arcs only where they lie between its neighbours (a file's arcs may cross a
        # neighbour's where the web begins: the IEA 10 MW's trailing-edge web over the rear web's at
        # 2-4 % span); elsewhere, as where it is absent, the position of its nearest such station
        gap = MIN_KEY_GAP / np.maximum(U - L, 1e-12)
        inside = on & (t > gap) & (t < 1.0 - gap)
        if inside.any():
            on = inside
        near = idx[on][np.abs(idx[:, None] - idx[on][None, :]).argmin(axis=1)]
        t = np.where(on, t, t[near])
        done[k] = L + np.clip(t, 0.0, 1.0) * (U - L)
    return [(raw[k][0], done[k]) for k in range(len(raw))]


def fill_uncovered(T: np.ndarray, A: np.ndarray, n_rows: int, nc: int) -> tuple[np.ndarray, np.ndarray]:
    """Give skin elements no layer covers the laminate of the nearest covered element at the same
    chordwise position along the span (e.g. a layup table that starts 2 m from the root, as the
    seed's appendix A).  Raises InputError if a whole chordwise column is uncovered."""
    tot = T.sum(axis=1).reshape(n_rows, nc)
    if np.all(tot > 0):
        return T, A
    T, A = T.copy(), A.copy()
    rows = np.arange(n_rows)
    for j in range(nc):
        ok = np.where(tot[:, j] > 0)[0]
        if ok.size == 0:
            raise InputError("blade.layup", f"no layer at contour position {j}/{nc} anywhere on the span",
                             "layers covering the whole skin")
        src = ok[np.abs(rows[:, None] - ok[None, :]).argmin(axis=1)]
        T[rows * nc + j] = T[src * nc + j]
        A[rows * nc + j] = A[src * nc + j]
    return T, A


def arc_interval(arc: np.ndarray, i: np.ndarray, j: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Contour interval of skin element (row i, column j): node arcs averaged over the two
    bounding stations; the last column ends at 1 (closing the contour)."""
    nc = arc.shape[1]
    a = 0.5 * (arc[i, j] + arc[i + 1, j])
    jn = (j + 1) % nc
    b = 0.5 * (arc[i, jn] + arc[i + 1, jn])
    b = np.where(jn == 0, 1.0, b)
    return a, b


def layer_material(materials: dict, name: str, layer: str):
    m = materials.get(name)
    if m is None:
        raise InputError(f"blade.layup.layers[{layer}].material", name, "a material defined in the materials list")
    return m
