"""Mode labels ("1st flap collective", "1st tower fore-aft", ...) from energy fractions.

For each mode shape ``phi`` (full numbering):

1. Kinetic-energy density ``e = phi * (M phi)`` summed per node group decides whether the mode
   lives in the blades (``rotor`` group) or in the tower (``tower`` group; hub and nacelle count
   with neither).
2. Blade modes: each aerodynamic strip's rigid motion (``AeroSections.motion_map @ phi``) is
   split into flapwise translation (normal to the chord and the span), edgewise translation
   (along the chord) and torsion (rotation about the span times a radius of gyration of a
   quarter chord), weighted by the strip width; the largest sum names the mode.  With several
   blades, blade participations ``c_k`` (projection of blade k's strip motions on the most
   active blade's) are split into the collective (mean) and cyclic parts of the multi-blade
   transformation; by Parseval the collective energy fraction is ``B mean(c)^2 / sum c^2``:
   above 1/2 the mode is ``collective``, else ``asymmetric``; a mode confined to one blade is
   labelled with that blade.
3. Tower modes: the tower nodes' kinetic energy in x (fore-aft), y (side-side) and rz
   (torsion); for shell towers torsion is recognised by the tangential share of the wall
   nodes' horizontal motion (> 3/4; bending gives 1/2).  A shell tower's wall modes (its rings
   deforming into lobes, :func:`wall_waves`) are ``tower wall n=k``, counted within their wave
   number.

Ordinals count modes of the same kind in frequency order; with ``B`` blades each order is a
family of ``B`` modes (one collective and ``B - 1`` asymmetric), so the order is
``ceil(count / B)``.
"""

from __future__ import annotations

import functools

import numpy as np
import scipy.sparse as sp

@functools.lru_cache(maxsize=256)
def ordinal(n: int) -> str:
    """``1st``, ``2nd``, ``3rd``, ``4th`` ... ``11th``, ``12th``, ``13th``, ``21st``, ``22nd``, ``111th``."""
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


#: a mode whose tower rings deform (the wall's motion relative to each ring's rigid motion) with more
#: than this share of the rings' kinetic energy is a mode of a shell tower's wall
WALL_SHARE = 0.5


def tower_rings(nodes: np.ndarray, tower: np.ndarray) -> list[np.ndarray]:
    """A shell tower's rings of wall nodes (one array per height, bottom up; a node on the axis, the
    tower top's, left out), or [] when a height has fewer than 3 (a beam tower)."""
    tw = np.asarray(tower, dtype=np.int64)
    X = np.asarray(nodes, float)
    z = X[tw, 2]
    if z.size == 0:
        return []
    tol = 1e-6 * max(float(np.ptp(z)), 1.0)
    key = np.round(z / tol).astype(np.int64)
    rings = []
    for k in np.unique(key):
        ring = tw[key == k]
        r = np.linalg.norm(X[ring, :2] - X[ring, :2].mean(axis=0), axis=1)
        rings.append(ring[r > 1e-3 * r.max()] if r.max() > 0 else ring[:0])
    return rings if all(r.size >= 3 for r in rings) else []


def wall_waves(nodes: np.ndarray, masses: np.ndarray, shapes: np.ndarray, tower: np.ndarray) -> np.ndarray:
    """(n,) the circumferential wave number of each mode (columns of ``shapes``, full numbering) that
    is a mode of a shell tower's wall, -1 for the others (all of them for a beam tower).

    A ring of a (vertical) tower moves as a rigid section in its bending, torsion and axial modes (a
    beam's kinematics); in the wall's own modes -- ovalling (``n = 2``), triangular (``n = 3``) ...
    lobes around, with little or no motion of the section -- it deforms.  Each ring's rigid motion
    (translation and rotation) is fitted to its nodes' translations by least squares weighted by the
    nodes' translational ``masses`` (n_nodes,); a mode whose rings' deformation carries more than
    :data:`WALL_SHARE` of their kinetic energy is a wall mode, its wave number the ``n != 1``
    (``n = 1`` radial is a section's translation) with the largest radial content
    ``|sum m u_r e^{-i n theta}|^2`` summed over the rings."""
    n = shapes.shape[1]
    rings = tower_rings(nodes, tower)
    if not rings:
        return np.full(n, -1)
    X = np.asarray(nodes, float)
    md = np.asarray(masses, float)
    U = np.asarray(shapes).reshape(-1, 6, n)[:, :3, :]
    e_all, e_wall = np.zeros(n), np.zeros(n)
    n_max = max(r.size for r in rings) // 2
    waves = np.zeros((n_max + 1, n))
    for ring in rings:
        m, u = md[ring], U[ring]  # (k,), (k, 3, n)
        d = X[ring] - np.average(X[ring], axis=0, weights=m)
        A = np.zeros((ring.size, 3, 6))  # rigid motion t + w x d of each node
        A[:, :, :3] = np.eye(3)
        A[:, 0, 4], A[:, 0, 5] = d[:, 2], -d[:, 1]
        A[:, 1, 3], A[:, 1, 5] = -d[:, 2], d[:, 0]
        A[:, 2, 3], A[:, 2, 4] = d[:, 1], -d[:, 0]
        N = np.einsum("k,kia,kib->ab", m, A, A)
        p = np.linalg.lstsq(N, np.einsum("k,kia,kin->an", m, A, u), rcond=None)[0]
        r = u - np.einsum("kia,an->kin", A, p)
        e_all += np.einsum("k,kin->n", m, u**2)
        e_wall += np.einsum("k,kin->n", m, r**2)
        theta = np.arctan2(d[:, 1], d[:, 0])
        ur = np.einsum("kj,kjn->kn", np.stack([np.cos(theta), np.sin(theta)], 1), u[:, :2, :])
        waves += np.abs(np.exp(-1j * np.outer(np.arange(n_max + 1), theta)) @ (m[:, None] * ur)) ** 2
    waves[1] = -1.0
    wall = e_wall > WALL_SHARE * np.maximum(e_all, 1e-300)
    return np.where(wall, np.argmax(waves, axis=0), -1)


def blade_motion_components(sections, shapes: np.ndarray) -> np.ndarray:
    """(3, ns, n) flap, edge and torsion amplitudes (m) of each strip for each mode."""
    q = sections.motion_map @ shapes  # (6 ns, n)
    ns = sections.n_sections
    q = q.reshape(ns, 6, -1)
    u, th = q[:, :3, :], q[:, 3:, :]
    ec, es = sections.e_chord, sections.e_span
    ef = np.cross(es, ec)
    flap = np.einsum("jc,jcn->jn", ef, u)
    edge = np.einsum("jc,jcn->jn", ec, u)
    tors = np.einsum("jc,jcn->jn", es, th) * 0.25 * sections.chord[:, None]
    return np.stack([flap, edge, tors])


def frame_components(sections, shapes: np.ndarray, frame: np.ndarray, strip: int = -1) -> np.ndarray:
    """(3, n) motion of one strip (default the outermost) for each mode, in the axes ``frame``
    (3, 3; columns x, y, z in global axes): translation along x and y (m) and rotation about z (rad).
    With the blade's pitching frame (:func:`windflutter.steady.geometry.pitching_frames`: x flapwise
    downwind, y edgewise, z the pitch axis) these are the tip flap, edge and torsion as HAWC2 and
    HAWCStab2 report them, undeformed axes turned with the pitch only."""
    j = strip % sections.n_sections
    q = sections.motion_map[6 * j: 6 * j + 6] @ shapes  # (6, n)
    frame = np.asarray(frame, float)
    return np.stack([frame[:, 0] @ q[:3], frame[:, 1] @ q[:3], frame[:, 2] @ q[3:]])


def label_modes(fe, M: sp.spmatrix, shapes: np.ndarray, sections=None) -> list[str]:
    """One label per column of ``shapes`` (full numbering, modes in ascending frequency).

    Parameters
    ----------
    fe : the :class:`FEModel` (node groups ``rotor``/``blade<k>``/``tower``).
    M : full-numbering mass matrix.
    shapes : (n_dof, n) mode shapes.
    sections : :class:`AeroSections` of the model (needed to label blade modes).
    """
    shapes = np.asarray(shapes)
    n = shapes.shape[1]
    e = shapes * (M @ shapes)  # (n_dof, n)
    groups = fe.node_groups

    def dofs(nodes, comps=(0, 1, 2, 3, 4, 5)):
        nodes = np.asarray(nodes, dtype=np.int64)
        return (6 * nodes[:, None] + np.array(comps)[None, :]).ravel()

    total = np.maximum(np.abs(e.sum(axis=0)), 1e-300)
    blade_nodes = [groups[k] for k in sorted(groups) if k.startswith("blade")]
    nbl = len(blade_nodes)
    e_bl = sum((e[dofs(g)].sum(axis=0) for g in blade_nodes), np.zeros(n))
    comps = blade_motion_components(sections, shapes) if (sections is not None and sections.n_sections) else None
    counts: dict[str, int] = {}
    labels = []
    waves = wall_waves(fe.nodes, np.asarray(M.diagonal())[0::6], shapes, groups["tower"]) if "tower" in groups \
        else np.full(n, -1)
    for m in range(n):
        if comps is not None and (e_bl[m] >= 0.5 * total[m] or "tower" not in groups):
            w = sections.width[:, None]
            en = (comps[:, :, m] ** 2 * w.T).sum(axis=1)
            kind = ("flap", "edge", "torsion")[int(np.argmax(en))]
            kidx = int(np.argmax(en))
            variant = ""
            if nbl > 1:
                c = comps[kidx, :, m]
                b = sections.blade
                amps = np.array([np.sqrt(np.sum(w[b == k, 0] * c[b == k] ** 2)) for k in range(nbl)])
                kref = int(np.argmax(amps))
                ref = c[b == kref]
                proj = np.array([np.sum(w[b == k, 0] * c[b == k] * ref) for k in range(nbl)]) / max(np.sum(w[b == kref, 0] * ref**2), 1e-300)
                if np.sum(amps > 0.1 * amps.max()) == 1:
                    variant = f"blade {kref + 1}"
                elif nbl * np.mean(proj) ** 2 > 0.5 * np.sum(proj**2):
                    variant = "collective"
                else:
                    variant = "asymmetric"
            counts[kind] = counts.get(kind, 0) + 1
            order = (counts[kind] + nbl - 1) // nbl if nbl > 1 else counts[kind]
            labels.append(f"{ordinal(order)} {kind}" + (f" {variant}" if variant else ""))
        elif "tower" in groups:
            tn = groups["tower"]
            ex = e[dofs(tn, (0,))].sum(axis=0)[m]
            ey = e[dofs(tn, (1,))].sum(axis=0)[m]
            rz = e[dofs(tn, (5,))].sum(axis=0)[m]
            if waves[m] >= 0:
                kind = f"tower wall n={waves[m]}"
            elif _tangential_share(fe.nodes[tn], shapes[:, m], tn) > 0.75 or rz > max(ex, ey):
                kind = "tower torsion"
            else:
                kind = "tower fore-aft" if ex >= ey else "tower side-side"
            counts[kind] = counts.get(kind, 0) + 1
            labels.append(f"{ordinal(counts[kind])} {kind}")
        else:
            labels.append("other")
    return labels


def _tangential_share(xyz: np.ndarray, phi: np.ndarray, nodes: np.ndarray) -> float:
    """Share of the horizontal displacement (squared) of off-axis tower nodes that is tangential
    about the vertical axis through x = y = 0: 1 for torsion, 1/2 for bending of a shell tower,
    0 when all nodes are on the axis (beam tower; torsion then shows in rz)."""
    r = xyz[:, :2]
    rn = np.linalg.norm(r, axis=1)
    off = rn > 1e-6
    if not np.any(off):
        return 0.0
    u = np.stack([phi[6 * nodes[off]], phi[6 * nodes[off] + 1]], axis=1)
    t = np.stack([-r[off, 1], r[off, 0]], axis=1) / rn[off, None]
    ut = np.sum(u * t, axis=1)
    tot = np.sum(u * u)
    return float(np.sum(ut**2) / tot) if tot > 0 else 0.0
