"""Pieces shared by the steady state's two fixed points (the linear structure's in
:mod:`windflutter.steady.state`, the co-rotational beam's in :mod:`windflutter.steady.exact`):
Aitken's relaxation and the convergence measure of the strip motions and loads."""

from __future__ import annotations

import numpy as np

__all__ = ["aitken", "strip_change"]


def aitken(w: float, r: np.ndarray, r_prev: np.ndarray | None) -> float:
    """Aitken's update of the relaxation factor ``w`` of a fixed point from its last two residuals
    (clipped to [0.05, 1.5]; unchanged on the first step or when they are equal)."""
    if r_prev is None:
        return w
    dr = r - r_prev
    den = float(dr @ dr)
    return float(np.clip(-w * float(r_prev @ dr) / den, 0.05, 1.5)) if den > 0 else w


def _change(new: np.ndarray, old: np.ndarray, floor) -> float:
    """Largest change of (ns, 6) arrays relative to their largest translation / rotation (force / moment)."""
    d = np.abs(new - old)
    ref = np.maximum(np.abs(new), np.abs(old))
    return max(float(d[:, c].max(initial=0.0)) / max(float(ref[:, c].max(initial=0.0)), fl)
               for c, fl in zip((slice(0, 3), slice(3, 6)), floor))


def strip_change(new, old, sections) -> float:
    """Relative change between two aerodynamic states (``.defl.motion`` and ``.loads.loads``, (ns, 6)
    each) of the strips ``sections``: the larger of the strip motions' change (floors 1e-9 of the
    rotor radius, 1e-9 rad) and the strip loads' (floor 1e-9 of the largest old load)."""
    radius = float(np.max(sections.radius)) + float(np.max(sections.width))
    floor_f = 1e-9 * max(float(np.abs(old.loads.loads).max(initial=0.0)), 1e-6)
    return max(_change(new.defl.motion, old.defl.motion, (1e-9 * radius, 1e-9)),
               _change(new.loads.loads, old.loads.loads, (floor_f,) * 2))
