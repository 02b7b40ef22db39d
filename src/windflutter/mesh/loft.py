"""Blade geometry on plain arrays: airfoil parametrisation, interpolation and the skin loft.

Conventions (windIO / IEC blade frame, see ``docs/mesh.md``)
-------------------------------------------------------------
* Airfoil coordinates are non-dimensional (chord 1), ``x`` from the leading edge (0) to the
  trailing edge (1), listed from the trailing edge over the **suction side** to the leading
  edge and back over the pressure side (windIO).  The non-dimensional arc ``s`` runs 0 -> 1 in
  that order, as the windIO ``nd_arc`` of the layup.
* Blade frame: ``z_b`` along the pitch axis root -> tip, ``x_b`` towards the suction side
  (downwind at zero pitch for an upwind rotor), ``y_b = z_b x x_b`` towards the trailing edge.
* Twist and pitch are positive towards feather: the chord LE -> TE direction is
  ``cos(theta) y_b + sin(theta) x_b`` (a rotation about ``-z_b``).
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError


def orient_airfoil(xy: np.ndarray, name: str = "airfoil") -> np.ndarray:
    """Return the airfoil as an open polyline TE -> suction side -> LE -> pressure side.

    The first listed half is taken as the suction side (windIO); if its mean ``y`` is below
    the other half's the ``y`` axis is flipped so that ``y > 0`` is the suction side.  A
    duplicated closing point is dropped.

    Parameters
    ----------
    xy : (m, 2) non-dimensional coordinates.
    name : used in error messages.

    Returns
    -------
    (m', 2) float array.
    """
    xy = np.asarray(xy, dtype=float)
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 8 or not np.all(np.isfinite(xy)):
        raise InputError(f"airfoils[{name}].coordinates", getattr(xy, "shape", xy), "at least 8 finite (x, y) points")
    if np.allclose(xy[0], xy[-1]) and xy.shape[0] > 8:
        # closed loop with the TE point repeated: keep a single TE point only if it is sharp
        xy = xy[:-1]
    ile = int(np.argmin(xy[:, 0]))
    if ile == 0 or ile == xy.shape[0] - 1:
        raise InputError(f"airfoils[{name}].coordinates", "leading edge at an end", "coordinates starting at the trailing edge")
    if np.mean(xy[: ile + 1, 1]) < np.mean(xy[ile:, 1]):
        xy = xy * np.array([1.0, -1.0])
    return xy


def arc_parameter(xy: np.ndarray) -> np.ndarray:
    """Normalised arc length of the closed polyline through ``xy`` (0 at the first point).

    The closing segment (last point back to the first, the trailing-edge thickness) is part of
    the loop, so the returned values are in ``[0, 1)``.
    """
    d = np.linalg.norm(np.diff(np.vstack([xy, xy[:1]]), axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(d)])
    return s[:-1] / s[-1]


def resample_airfoil(xy: np.ndarray, s_new: np.ndarray) -> np.ndarray:
    """Points of the closed airfoil loop at normalised arc positions ``s_new`` (periodic in 1).

    Parameters
    ----------
    xy : (m, 2) airfoil from :func:`orient_airfoil`.
    s_new : (k,) arc positions in [0, 1).
    """
    s = arc_parameter(xy)
    sp = np.concatenate([s, [1.0]])
    loop = np.vstack([xy, xy[:1]])
    t = np.mod(np.asarray(s_new, dtype=float), 1.0)
    return np.column_stack([np.interp(t, sp, loop[:, 0]), np.interp(t, sp, loop[:, 1])])


def leading_edge_arc(xy: np.ndarray) -> float:
    """Arc position of the leading edge (minimum x) of an oriented airfoil."""
    return float(arc_parameter(xy)[int(np.argmin(xy[:, 0]))])


def relative_thickness(xy: np.ndarray, n: int = 201) -> float:
    """Maximum thickness over chord of an oriented airfoil (upper minus lower surface)."""
    ile = int(np.argmin(xy[:, 0]))
    up = xy[: ile + 1][::-1]  # LE -> TE
    lo = xy[ile:]
    x = np.linspace(0.0, 1.0, n)
    yu = np.interp(x, up[:, 0], up[:, 1])
    yl = np.interp(x, lo[:, 0], lo[:, 1])
    return float(np.max(yu - yl) / (xy[:, 0].max() - xy[:, 0].min()))


def distribute_counts(lengths: np.ndarray, n_total: int) -> np.ndarray:
    """Split ``n_total`` intervals over segments proportionally to ``lengths`` (each >= 1)."""
    lengths = np.asarray(lengths, dtype=float)
    k = len(lengths)
    if n_total < k:
        raise InputError("mesh.n_chord", n_total, f"at least {k} chordwise elements (one per layup segment)")
    raw = lengths / lengths.sum() * n_total
    counts = np.maximum(1, np.floor(raw).astype(int))
    while counts.sum() < n_total:
        counts[np.argmax(raw - counts)] += 1
    while counts.sum() > n_total:
        i = np.argmax(np.where(counts > 1, counts - raw, -np.inf))
        counts[i] -= 1
    return counts


def segmented_grid(keys: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Arc grid on [0, 1) through ``0 = keys[0] < keys[1] < ... < 1`` with ``counts[i]`` intervals each.

    Parameters
    ----------
    keys : (k,) segment start arcs, the first 0.
    counts : (k,) number of intervals in each segment (the last one ends at 1).

    Returns
    -------
    (sum(counts),) arcs; the closing point 1 == 0 is not repeated.
    """
    ends = np.append(keys[1:], 1.0)
    parts = [np.linspace(a, b, c, endpoint=False) for a, b, c in zip(keys, ends, counts)]
    return np.concatenate(parts)


def chord_frame(twist: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit chord (LE -> TE) and suction-side normal in blade axes (x_b, y_b, z_b) for twist (rad)."""
    t = np.asarray(twist, dtype=float)
    e_c = np.stack([np.sin(t), np.cos(t), np.zeros_like(t)], axis=-1)
    e_n = np.stack([np.cos(t), -np.sin(t), np.zeros_like(t)], axis=-1)
    return e_c, e_n


def loft(
    shapes: np.ndarray, chord: np.ndarray, twist: np.ndarray, pitch_axis: np.ndarray, ref_axis: np.ndarray
) -> np.ndarray:
    """Loft a stack of sections into skin node coordinates (blade axes).

    Parameters
    ----------
    shapes : (k, m, 2) unit airfoils at the k stations, same arc positions.
    chord, twist, pitch_axis : (k,) chord (m), twist (rad), pitch-axis fraction (-).
    ref_axis : (k, 3) reference-axis points (m), blade axes.

    Returns
    -------
    (k, m, 3) node coordinates; node (i, j) is station i, chordwise point j.
    """
    e_c, e_n = chord_frame(twist)
    x = shapes[:, :, 0:1] - np.asarray(pitch_axis)[:, None, None]
    y = shapes[:, :, 1:2]
    c = np.asarray(chord)[:, None, None]
    return ref_axis[:, None, :] + c * x * e_c[:, None, :] + c * y * e_n[:, None, :]


def quad_grid(n_station: int, n_chord: int, offset: int = 0, closed: bool = True) -> np.ndarray:
    """Quad connectivity of a (n_station x n_chord) node grid, node id ``offset + i*n_chord + j``.

    With ``closed`` the chordwise direction wraps around (skin).  Node order is counter-clockwise
    seen from outside for a skin whose chordwise order runs TE -> suction -> LE -> pressure and
    whose stations run root -> tip in a right-handed blade frame.
    """
    i = np.arange(n_station - 1)[:, None]
    j = np.arange(n_chord if closed else n_chord - 1)[None, :]
    jn = (j + 1) % n_chord
    a = offset + i * n_chord + j
    b = offset + i * n_chord + jn
    c = offset + (i + 1) * n_chord + jn
    d = offset + (i + 1) * n_chord + j
    return np.stack([a, d, c, b], axis=-1).reshape(-1, 4)


def stack_weights(
    eta_af: np.ndarray, tc_af: np.ndarray, eta: np.ndarray, tc_target: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Neighbouring airfoils ``j, j+1`` and blend weights ``w`` for span positions ``eta``.

    Where the two airfoils differ in relative thickness and a target thickness distribution is
    given, ``w`` makes the blended thickness ``(1-w) tc_j + w tc_{j+1}`` equal the target
    (clipped to [0, 1]); otherwise ``w`` is linear in span.  (Blending by thickness keeps the
    blade's t/c distribution, as windIO tools do.)
    """
    eta_af = np.asarray(eta_af, dtype=float)
    eta = np.asarray(eta, dtype=float)
    j = np.clip(np.searchsorted(eta_af, eta, side="right") - 1, 0, len(eta_af) - 2)
    w = np.clip((eta - eta_af[j]) / np.maximum(eta_af[j + 1] - eta_af[j], 1e-300), 0.0, 1.0)
    if tc_target is not None:
        tc_af = np.asarray(tc_af, dtype=float)
        d = tc_af[j + 1] - tc_af[j]
        ok = np.abs(d) > 1e-4
        wt = np.clip((np.asarray(tc_target, dtype=float) - tc_af[j]) / np.where(ok, d, 1.0), 0.0, 1.0)
        w = np.where(ok, wt, w)
    return j, w
