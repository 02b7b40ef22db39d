"""Strip geometry of a deflected blade: strip motions, finite rotations, deflected strips, tip motion.

The structure is linear (small strains, first-order displacements ``u``); this module turns its
strip motions into a deflected strip geometry for the aerodynamics.  Two kinematics:

* ``finite=True`` (default), moderate rotations by composition along the span.  From the blade
  root outwards, the rotation of strip ``j`` relative to strip ``j - 1`` is the linear increment
  ``d_theta = theta_j - theta_(j-1)``, which the linear structure computes in the undeformed
  section axes, i.e. in the section's own (material) frame; the finite rotations are composed,
  ``R_j = R_(j-1) exp(d_theta)``, and the piece of blade between the two strip points (its
  undeformed vector ``d`` plus its linear strain ``e = du - theta_mid x d``) is turned by the
  rotation half-way, ``p'_j = p'_(j-1) + R_(j-1) exp(d_theta / 2) (d + e)``.  This keeps the
  length of the bent blade (its span shortens by about ``0.5 delta^2 / L`` at the tip of a
  cantilever deflected by ``delta``) and turns the bending of an elastically twisted section
  with its twist (a flapwise curvature of a section twisted by ``phi`` moves the tip edgewise by
  about ``phi`` times the flapwise deflection);
* ``finite=False``, linear: ``p' = p + u`` and ``R_j = exp(theta_j)``.

The chord and span directions of each strip turn with ``R_j`` (they stay orthonormal).

Blade frames ("pitching system", as HAWC2 and OpenFAST report blade deflections): ``z`` along
the coned blade axis from the hub centre to the blade root, ``x`` downwind normal to it in the
plane of the shaft, turned with the blade pitch about ``-z``, ``y = z x x`` (towards the trailing
edge at zero twist).  The pitch is read from the root strip's chord direction minus its
structural twist, so the frames follow the model as built (``MeshSettings.pitch``).

Units: SI (m, rad).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from windflutter.aero.sections import AeroSections, RotorGeometry
from windflutter.errors import InputError

__all__ = ["Deflection", "strip_motion", "rotation_matrices", "rotation_vectors", "blade_strips", "deflection",
           "deflected_sections", "pitching_frames", "tip_motion"]


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0, n, 1.0)


def strip_motion(sections: AeroSections, u: np.ndarray) -> np.ndarray:
    """(ns, 6) rigid motion ``(ux, uy, uz, rx, ry, rz)`` of every strip's elastic-axis point (m, rad),
    global axes, from the full-numbering displacement ``u`` through ``sections.motion_map``."""
    mm = sections.motion_map
    u = np.asarray(u, float)
    if u.shape != (mm.shape[1],) or not np.all(np.isfinite(u)):
        raise InputError("u", u.shape, f"a finite ({mm.shape[1]},) displacement vector (full numbering)")
    return (mm @ u).reshape(-1, 6)


def rotation_matrices(theta: np.ndarray) -> np.ndarray:
    """(n, 3, 3) finite rotations of the rotation vectors ``theta`` (n, 3) (rad), Rodrigues' formula
    ``R = I + sin(t) K + (1 - cos(t)) K^2`` with ``K`` the cross-product matrix of the unit axis."""
    theta = np.atleast_2d(np.asarray(theta, float))
    t = np.linalg.norm(theta, axis=1)
    k = theta / np.where(t > 0, t, 1.0)[:, None]
    K = np.zeros((theta.shape[0], 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    K[:, 1, 0], K[:, 2, 0], K[:, 2, 1] = k[:, 2], -k[:, 1], k[:, 0]
    s, c = np.sin(t)[:, None, None], np.cos(t)[:, None, None]
    return np.eye(3)[None] + s * K + (1.0 - c) * (K @ K)


def rotation_vectors(R: np.ndarray) -> np.ndarray:
    """(n, 3) rotation vectors (rad) of the rotations ``R`` (n, 3, 3) (inverse of
    :func:`rotation_matrices`, angles below pi)."""
    R = np.asarray(R, float).reshape(-1, 3, 3)
    ax = np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = 0.5 * np.linalg.norm(ax, axis=1)
    c = 0.5 * (np.trace(R, axis1=1, axis2=2) - 1.0)
    t = np.arctan2(s, c)
    f = np.where(s > 1e-12, t / np.where(s > 1e-12, 2.0 * s, 1.0), 0.5 + t**2 / 12.0)
    return ax * f[:, None]


def blade_strips(sections: AeroSections) -> list[np.ndarray]:
    """Strip indices of every blade present, ordered from root to tip (by radius)."""
    blade = np.asarray(sections.blade)
    radius = np.asarray(sections.radius, float)
    out = []
    for b in np.unique(blade):
        idx = np.flatnonzero(blade == b)
        out.append(idx[np.argsort(radius[idx], kind="stable")])
    return out


@dataclass(frozen=True)
class Deflection:
    """Deflected strip geometry (arrays over the strips, global axes).

    Attributes
    ----------
    motion : (ns, 6) linear strip motions (m, rad).
    origin : (ns, 3) deflected elastic-axis points (m); ``shift`` (ns, 3) their displacement.
    R : (ns, 3, 3) finite strip rotations.
    cut0, cut : (ns, 3) undeformed and deflected inner-edge points of the strips (m).
    R_cut : (ns, 3, 3) finite rotations at the inner edges.
    """

    motion: np.ndarray
    origin: np.ndarray
    shift: np.ndarray
    R: np.ndarray
    cut0: np.ndarray
    cut: np.ndarray
    R_cut: np.ndarray


def inner_edges(p, t, w):
    """Undeformed inner-edge points: mean of the outer edge inboard and the inner edge (root: inner edge)."""
    inner = p - 0.5 * w[:, None] * t
    cut = inner.copy()
    cut[1:] = 0.5 * (inner[1:] + p[:-1] + 0.5 * w[:-1, None] * t[:-1])
    return cut


def _compose(p, t, w, motion):
    """Moderate-rotation chain of one blade (strips root -> tip): deflected points, strip rotations,
    undeformed and deflected inner edges, rotations at the inner edges."""
    uu, th = motion[:, :3], motion[:, 3:]
    n = len(p)
    cut0 = inner_edges(p, t, w)
    th_root = th[0] - (th[1] - th[0]) * w[0] / (w[0] + w[1]) if n > 1 else 0.5 * th[0]
    u_root = uu[0] + np.cross(th[0], cut0[0] - p[0])
    # piece j runs from the previous point (root edge for j = 0) to strip point j: its undeformed
    # vector d, linear strain e = du - theta_mid x d, half rotation increment
    th_prev = np.vstack([th_root, th[:-1]])
    d = p - np.vstack([cut0[:1], p[:-1]])
    e = (uu - np.vstack([u_root, uu[:-1]])) - np.cross(0.5 * (th + th_prev), d)
    half = rotation_matrices(0.5 * (th - th_prev))
    R, R_mid = np.empty((n, 3, 3)), np.empty((n, 3, 3))
    R_prev = rotation_matrices(th_root)[0]
    for j in range(n):  # the only sequential part: composing 3x3 rotations
        R_mid[j] = R_prev @ half[j]
        R[j] = R_prev = R_mid[j] @ half[j]
    origin = cut0[0] + u_root + np.cumsum(np.einsum("jab,jb->ja", R_mid, d + e), axis=0)
    R_cut = R_mid.copy()
    R_cut[0] = rotation_matrices(th_root)[0]
    # deflected inner edges: the rigid transfer of the strips on either side, averaged
    cut = origin + np.einsum("jab,jb->ja", R, cut0 - p)
    cut[1:] = 0.5 * (cut[1:] + origin[:-1] + np.einsum("jab,jb->ja", R[:-1], cut0[1:] - p[:-1]))
    cut[0] = cut0[0] + u_root
    return origin, R, cut0, cut, R_cut


def deflection(sections: AeroSections, motion: np.ndarray, finite: bool = True) -> Deflection:
    """Deflected strip points and rotations of the strip motions ``motion`` (ns, 6) (module docstring)."""
    motion = np.asarray(motion, float)
    ns = sections.n_sections
    if motion.shape != (ns, 6) or not np.all(np.isfinite(motion)):
        raise InputError("motion", motion.shape, f"finite ({ns}, 6) strip motions")
    p = np.asarray(sections.origin, float)
    t = _unit(np.asarray(sections.e_span, float))
    w = np.asarray(sections.width, float)
    origin, R, cut0, cut, R_cut = (np.empty((ns, 3)), np.empty((ns, 3, 3)), np.empty((ns, 3)), np.empty((ns, 3)),
                                   np.empty((ns, 3, 3)))
    for idx in blade_strips(sections):
        if finite:
            out = _compose(p[idx], t[idx], w[idx], motion[idx])
        else:
            c0 = inner_edges(p[idx], t[idx], w[idx])
            th = motion[idx, 3:]
            thc = th.copy()
            thc[1:] = 0.5 * (th[1:] + th[:-1])
            uc = motion[idx, :3] + np.cross(th, c0 - p[idx])
            out = (p[idx] + motion[idx, :3], rotation_matrices(th), c0, c0 + uc, rotation_matrices(thc))
        for arr, val in zip((origin, R, cut0, cut, R_cut), out):
            arr[idx] = val
    return Deflection(motion=motion, origin=origin, shift=origin - p, R=R, cut0=cut0, cut=cut, R_cut=R_cut)


def deflected_sections(sections: AeroSections, rotor: RotorGeometry, defl: Deflection) -> AeroSections:
    """A copy of the undeformed ``sections`` with the deflected points, chord and span directions
    of ``defl`` and the radius recomputed from the shaft axis.  Chord, width, polars and
    ``motion_map`` stay those of the undeformed strips (the structure is linear about them)."""
    axis = _unit(np.asarray(rotor.shaft_axis, float))
    rel = defl.origin - np.asarray(rotor.hub_center, float)
    radius = np.linalg.norm(rel - (rel @ axis)[:, None] * axis[None, :], axis=1)
    return dataclasses.replace(
        sections, origin=defl.origin.copy(), radius=radius,
        e_chord=np.einsum("jab,jb->ja", defl.R, np.asarray(sections.e_chord, float)),
        e_span=np.einsum("jab,jb->ja", defl.R, np.asarray(sections.e_span, float)))


def _turn(v: np.ndarray, k: np.ndarray, angle: float) -> np.ndarray:
    """``v`` turned by ``angle`` about the unit axis ``k`` (right hand)."""
    return v * np.cos(angle) + np.cross(k, v) * np.sin(angle) + k * (k @ v) * (1.0 - np.cos(angle))


def pitching_frames(sections: AeroSections, rotor: RotorGeometry) -> np.ndarray:
    """(nb, 3, 3) blade frames, columns ``(x, y, z)`` in global axes, one per blade present
    (order of :func:`blade_strips`), see the module docstring."""
    hub = np.asarray(rotor.hub_center, float)
    n = _unit(np.asarray(rotor.shaft_axis, float))
    frames = []
    for idx in blade_strips(sections):
        j = idx[0]
        span = _unit(np.asarray(sections.e_span[j], float))
        root = np.asarray(sections.origin[j], float) - 0.5 * float(sections.width[j]) * span
        z = _unit(root - hub)
        y_h = np.cross(z, _unit(n - (n @ z) * z))
        # the root chord is y_h turned by twist + pitch about -z: undo the structural twist
        y = _turn(_unit(np.asarray(sections.e_chord[j], float)), z, float(sections.twist[j]))
        y = _unit(y - (y @ z) * z)
        if np.linalg.norm(y) < 0.5:  # a chord along the blade axis: no pitch to read
            y = y_h
        frames.append(np.column_stack([np.cross(y, z), y, z]))
    return np.array(frames).reshape(-1, 3, 3)


def tip_motion(sections: AeroSections, defl: Deflection, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Tip translation (nb, 3) (m) and rotation vector (nb, 3) (rad) of every blade in its frame.

    The tip is the outer edge of the outermost strip, carried rigidly by that strip; components
    along the frame axes (x flapwise, y edgewise, z along the blade).  The rotation is the
    strip's finite rotation; its z component is the elastic twist (negative: towards feather,
    nose down, with the conventions of :func:`pitching_frames`).
    """
    d, r = [], []
    for b, idx in enumerate(blade_strips(sections)):
        j = idx[-1]
        arm = 0.5 * float(sections.width[j]) * _unit(np.asarray(sections.e_span[j], float))
        tip = defl.shift[j] + defl.R[j] @ arm - arm
        F = frames[b]
        d.append(F.T @ tip)
        r.append(F.T @ rotation_vectors(defl.R[j])[0])
    return np.array(d).reshape(-1, 3), np.array(r).reshape(-1, 3)
