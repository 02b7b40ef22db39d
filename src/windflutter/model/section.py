"""Thin-walled beam section properties of a blade from its composite layup.

A classical thin-walled model (no warping, no elastic couplings except axial-bending through the
offset of the tension centre):

* each laminate is reduced to membrane moduli from classical lamination theory,
  ``E_x t = A11 - A12^2 / A22`` and ``G t = A66`` (x = span direction, ply angles from the span);
* the wall midline is the outer airfoil contour scaled by the chord, offset inwards by half the
  local laminate thickness (capped at a quarter of the local airfoil thickness near the trailing
  edge, where the two skins meet);
* axial and bending stiffness, mass and mass moments are line integrals over the skin and the
  webs about the reference (pitch) axis;
* torsion stiffness from multi-cell Bredt-Batho shear flow (cells separated by the webs);
* shear stiffness ``GA`` from the wall shear rigidity projected on each direction (no shear
  correction), adequate for slender blades where shear deformation is minor;
* the shear centre from the shear flow of a bending-moment gradient with no twist in any cell
  (:func:`shear_centre`): the shear and torsion stiffness act there, which couples shear and
  torsion about the reference axis (``K13 = -GA_y z_s``, ``K23 = GA_z y_s``).

Frame and order follow :class:`windflutter.model.turbine.BeamProperties` (section y flapwise
towards the suction side, z chordwise towards the TE, both in the twisted chord frame; order
N, V_y, V_z, T, M_y, M_z).  With the axial strain ``eps = eps0 + z kappa_y - y kappa_z``:
``K00 = int E``, ``K04 = int E z``, ``K05 = -int E y``, ``K44 = int E z^2``,
``K45 = -int E y z``, ``K55 = int E y^2``.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.model.airfoil_geom import nd_arc
from windflutter.model.turbine import BeamProperties, IsotropicMaterial, Material, Turbine
from windflutter.model.v1arcs import contour_at


# ------------------------------------------------------------------------------ laminate theory
def ply_qbar(material: Material, angle: float) -> np.ndarray:
    """Transformed reduced stiffness (Qbar11, Qbar22, Qbar12, Qbar66) of a ply at ``angle`` (rad)
    from the laminate x axis."""
    if isinstance(material, IsotropicMaterial):
        E, nu = material.E, material.nu
        d = 1.0 - nu * nu
        Q11 = Q22 = E / d
        Q12 = nu * E / d
        Q66 = material.G
    else:
        E1, E2, n12, G12 = material.E1, material.E2, material.nu12, material.G12
        n21 = n12 * E2 / E1
        d = 1.0 - n12 * n21
        Q11, Q22, Q12, Q66 = E1 / d, E2 / d, n12 * E2 / d, G12
    c, s = np.cos(angle), np.sin(angle)
    c2, s2 = c * c, s * s
    q11 = Q11 * c2 * c2 + 2 * (Q12 + 2 * Q66) * s2 * c2 + Q22 * s2 * s2
    q22 = Q11 * s2 * s2 + 2 * (Q12 + 2 * Q66) * s2 * c2 + Q22 * c2 * c2
    q12 = (Q11 + Q22 - 4 * Q66) * s2 * c2 + Q12 * (s2 * s2 + c2 * c2)
    q66 = (Q11 + Q22 - 2 * Q12 - 2 * Q66) * s2 * c2 + Q66 * (s2 * s2 + c2 * c2)
    return np.array([q11, q22, q12, q66])


def laminate_membrane(plies: list[tuple[Material, float, float]]) -> tuple[float, float, float]:
    """(E_x t, G t, rho t) of a laminate given (material, thickness, angle) plies (N/m, N/m, kg/m^2)."""
    A = np.zeros(4)
    rt = 0.0
    for mat, t, ang in plies:
        if t > 0:
            A += ply_qbar(mat, ang) * t
            rt += mat.rho * t
    if A[0] <= 0:
        return 0.0, 0.0, rt
    return A[0] - A[2] ** 2 / A[1], A[3], rt


# --------------------------------------------------------------------------------- thin walls
def thin_wall_properties(
    skin_yz: np.ndarray,
    skin_Et: np.ndarray,
    skin_Gt: np.ndarray,
    skin_mt: np.ndarray,
    webs: list[tuple[int, int, float, float, float]] = (),
    with_shear_centre: bool = True,
) -> tuple[np.ndarray, np.ndarray]:
    """6x6 stiffness and mass of a closed thin-walled section (BeamSection order).

    Parameters
    ----------
    skin_yz : (n+1, 2) closed midline polygon (first point repeated at the end), (y, z) in m
        relative to the reference axis, ordered TE -> suction -> LE -> pressure -> TE.
    skin_Et, skin_Gt, skin_mt : (n,) per-segment E t (N/m), G t (N/m), rho t (kg/m^2).
    webs : (i_suction, i_pressure, E t, G t, rho t) straight walls between polygon vertices;
        ``i_suction < i_pressure``; listed from the leading edge to the trailing edge (the
        suction-side index decreasing).
    with_shear_centre : put the shear and torsion stiffness at the shear centre (default); False:
        at the reference axis, no shear-torsion coupling (the calculator until Dec 2026).
    """
    p0, p1 = skin_yz[:-1], skin_yz[1:]
    segs = [(p0, p1, skin_Et, skin_Gt, skin_mt)]
    for i, j, Et, Gt, mt in webs:
        segs.append((skin_yz[[i]], skin_yz[[j]], np.array([Et]), np.array([Gt]), np.array([mt])))
    P0 = np.concatenate([s[0] for s in segs])
    P1 = np.concatenate([s[1] for s in segs])
    Et = np.concatenate([s[2] for s in segs])
    Gt = np.concatenate([s[3] for s in segs])
    mt = np.concatenate([s[4] for s in segs])
    d = P1 - P0
    L = np.hypot(d[:, 0], d[:, 1])
    # exact integrals of linear coordinates over each straight segment
    y0, z0, y1, z1 = P0[:, 0], P0[:, 1], P1[:, 0], P1[:, 1]
    Iy = L * (y0 + y1) / 2
    Iz = L * (z0 + z1) / 2
    Iyy = L * (y0 * y0 + y0 * y1 + y1 * y1) / 3
    Izz = L * (z0 * z0 + z0 * z1 + z1 * z1) / 3
    Iyz = L * (2 * y0 * z0 + y0 * z1 + y1 * z0 + 2 * y1 * z1) / 6
    K = np.zeros((6, 6))
    K[0, 0] = np.sum(Et * L)
    K[0, 4] = K[4, 0] = np.sum(Et * Iz)
    K[0, 5] = K[5, 0] = -np.sum(Et * Iy)
    K[4, 4] = np.sum(Et * Izz)
    K[5, 5] = np.sum(Et * Iyy)
    K[4, 5] = K[5, 4] = -np.sum(Et * Iyz)
    # shear: wall shear rigidity projected on each direction
    cy, cz = d[:, 0] / np.where(L > 0, L, 1), d[:, 1] / np.where(L > 0, L, 1)
    K[1, 1] = np.sum(Gt * L * cy * cy)
    K[2, 2] = np.sum(Gt * L * cz * cz)
    gj = _bredt_batho(skin_yz, skin_Gt, webs)
    if with_shear_centre:
        # shear and torsion act at the shear centre: gamma_y(s) = gamma_y - z_s kappa_x,
        # gamma_z(s) = gamma_z + y_s kappa_x (strains about the reference axis)
        ys, zs = shear_centre(skin_yz, skin_Et, skin_Gt, webs, K)
        K[1, 3] = K[3, 1] = -K[1, 1] * zs
        K[2, 3] = K[3, 2] = K[2, 2] * ys
        gj += K[1, 1] * zs * zs + K[2, 2] * ys * ys
    K[3, 3] = gj
    M = np.zeros((6, 6))
    m = np.sum(mt * L)
    M[0, 0] = M[1, 1] = M[2, 2] = m
    my, mz = np.sum(mt * Iy), np.sum(mt * Iz)  # m * c_y, m * c_z
    # [[m I, m S^T], [m S, J]] with S = skew(c), c = (0, c_y, c_z)
    S = np.array([[0.0, -mz, my], [mz, 0.0, 0.0], [-my, 0.0, 0.0]])
    M[3:, :3] = S
    M[:3, 3:] = S.T
    Jyy, Jzz, Jyz = np.sum(mt * Iyy), np.sum(mt * Izz), np.sum(mt * Iyz)
    M[3, 3] = Jyy + Jzz
    M[4, 4] = Jzz
    M[5, 5] = Jyy
    M[4, 5] = M[5, 4] = -Jyz
    return K, M


def shear_centre(skin_yz: np.ndarray, skin_Et: np.ndarray, skin_Gt: np.ndarray, webs=(),
                 K: np.ndarray | None = None) -> tuple[float, float]:
    """Shear centre ``(y_s, z_s)`` (m, about the reference axis) of a closed multi-cell thin wall.

    For a unit gradient of each bending moment (no axial force) the axial stress resultant changes
    along the span by ``E t (eps0' + z kappa_y' - y kappa_z')``; lumped on the polygon's vertices it is
    what the wall shear flows carry off each vertex (``dq/ds = -dn_x/dx``).  The flows ``q`` (one per
    skin segment and web) follow from that balance at every vertex and from zero twist in every
    closed loop of a cycle basis (the skin ring, and per web the skin between its feet closed by the
    web: ``sum q L / (G t) = 0``).  The shear centre is the point about which the two flows' resultant
    forces have the moments the flows have.  Arguments as :func:`thin_wall_properties`; ``K`` its
    stiffness (the axial-bending block is used), computed if not given.
    """
    n = skin_yz.shape[0] - 1
    P = skin_yz[:-1]
    a = np.concatenate([np.arange(n), [int(w[0]) for w in webs]]).astype(np.int64)
    b = np.concatenate([(np.arange(n) + 1) % n, [int(w[1]) for w in webs]]).astype(np.int64)
    Et = np.concatenate([skin_Et, [w[2] for w in webs]])
    Gt = np.concatenate([skin_Gt, [w[3] for w in webs]])
    P0, P1 = P[a], P[b]
    L = np.hypot(*(P1 - P0).T)
    mid = 0.5 * (P0 + P1)
    ne, nw = a.size, len(webs)
    if K is None:
        K, _ = thin_wall_properties(skin_yz, skin_Et, skin_Gt, np.zeros(n), webs, with_shear_centre=False)
    C = np.linalg.inv(K[np.ix_([0, 4, 5], [0, 4, 5])])
    balance = np.zeros((n, ne))
    balance[a, np.arange(ne)] += 1.0  # a flow leaves its first vertex
    balance[b, np.arange(ne)] -= 1.0  # and enters its second
    loops = np.zeros((1 + nw, ne))
    loops[0, :n] = 1.0
    for k, w in enumerate(webs):
        loops[1 + k, int(w[0]):int(w[1])] = 1.0
        loops[1 + k, n + k] = -1.0
    A = np.vstack([balance, loops * (L / np.maximum(Gt, 1e-30))[None, :]])
    f = np.zeros((n + 1 + nw, 2))  # the two unit bending-moment gradients, solved together
    for j, load in enumerate(((0.0, 1.0, 0.0), (0.0, 0.0, 1.0))):
        e0, ky, kz = C @ np.array(load)
        dn = Et * (e0 + mid[:, 1] * ky - mid[:, 0] * kz) * L  # axial force gradient of each wall
        np.add.at(f[:, j], a, 0.5 * dn)
        np.add.at(f[:, j], b, 0.5 * dn)
    q = np.linalg.lstsq(A, f, rcond=None)[0]  # (ne, 2)
    F = q.T @ (P1 - P0)  # (2, 2): each load's resultant force (F_y, F_z)
    rows = np.stack([F[:, 1], -F[:, 0]], axis=1)  # moment = y_s F_z - z_s F_y
    rhs = q.T @ (P0[:, 0] * P1[:, 1] - P0[:, 1] * P1[:, 0])
    ys, zs = np.linalg.solve(rows, rhs)
    return float(ys), float(zs)


def _polygon_area(yz: np.ndarray) -> float:
    y, z = yz[:, 0], yz[:, 1]
    return 0.5 * abs(np.sum(y[:-1] * z[1:] - y[1:] * z[:-1]))


def _bredt_batho(skin_yz: np.ndarray, skin_Gt: np.ndarray, webs) -> float:
    """Torsion constant G J of a multi-cell section (cells split by the webs)."""
    n = skin_yz.shape[0] - 1
    seg_len = np.hypot(*np.diff(skin_yz, axis=0).T)
    flex = seg_len / np.maximum(skin_Gt, 1e-30)  # ds / (G t) per skin segment
    cuts = sorted([(i, j, Gt) for i, j, _, Gt, _ in webs], key=lambda w: -w[0])  # LE web first
    nc = len(cuts) + 1
    areas = np.zeros(nc)
    D = np.zeros((nc, nc))
    # cell k lies between cut k-1 (towards the LE) and cut k (towards the TE)
    for k in range(nc):
        if k == 0:
            lo, hi = (cuts[0][0], cuts[0][1]) if cuts else (0, n)
            idx = np.arange(lo, hi)  # suction-side web foot -> LE -> pressure-side web foot
            poly = skin_yz[lo:hi + 1]
        elif k == nc - 1:
            lo, hi = cuts[-1][0], cuts[-1][1]
            idx = np.concatenate([np.arange(0, lo), np.arange(hi, n)])
            poly = np.concatenate([skin_yz[hi:n + 1], skin_yz[1:lo + 1]])
        else:
            a_lo, a_hi = cuts[k - 1][0], cuts[k - 1][1]
            b_lo, b_hi = cuts[k][0], cuts[k][1]
            idx = np.concatenate([np.arange(b_lo, a_lo), np.arange(a_hi, b_hi)])
            poly = np.concatenate([skin_yz[b_lo:a_lo + 1], skin_yz[a_hi:b_hi + 1]])
        poly = np.vstack([poly, poly[:1]])
        areas[k] = _polygon_area(poly)
        D[k, k] = np.sum(flex[idx])
    for k, (i, j, Gt) in enumerate(cuts):
        fw = np.hypot(*(skin_yz[i] - skin_yz[j])) / max(Gt, 1e-30)
        D[k, k] += fw
        D[k + 1, k + 1] += fw
        D[k, k + 1] = D[k + 1, k] = -fw
    q = np.linalg.solve(D, 2.0 * areas)  # shear flows per unit twist rate
    return float(2.0 * areas @ q)


def _offset_inwards(yz: np.ndarray, t_seg: np.ndarray, xg: np.ndarray, yg: np.ndarray, chord: float) -> np.ndarray:
    """Move the closed polygon's vertices inwards by half the laminate thickness (vertex value =
    mean of the two adjacent segments), capped at 1/4 of the local airfoil thickness."""
    n = t_seg.size
    tv = 0.5 * (t_seg + np.roll(t_seg, 1))  # vertex i between segments i-1 and i
    P = yz[:-1]
    tang = np.roll(P, -1, axis=0) - np.roll(P, 1, axis=0)
    tang /= np.maximum(np.linalg.norm(tang, axis=1, keepdims=True), 1e-30)
    area2 = np.sum(P[:, 0] * np.roll(P[:, 1], -1) - np.roll(P[:, 0], -1) * P[:, 1])
    # counter-clockwise in (y, z) -> inward normal is the tangent turned +90 deg
    sign = 1.0 if area2 > 0 else -1.0
    normal = sign * np.column_stack([-tang[:, 1], tang[:, 0]])
    i_le = int(np.argmin(xg[:-1]))
    xs, ys = xg[: i_le + 1][::-1], yg[: i_le + 1][::-1]
    xp, yp = xg[i_le:-1], yg[i_le:-1]
    xv = xg[:-1]
    h = np.interp(xv, xs[np.argsort(xs)], ys[np.argsort(xs)]) - np.interp(xv, xp[np.argsort(xp)], yp[np.argsort(xp)])
    off = np.minimum(0.5 * tv, 0.25 * np.abs(h) * chord)
    Q = P + normal * off[:, None]
    return np.vstack([Q, Q[:1]])[: n + 1]


# ------------------------------------------------------------------------------ blade sections
def layup_beam_sections(turbine: Turbine, s: np.ndarray | None = None, n_contour: int = 240) -> BeamProperties:
    """Beam properties of the blade from its layup (thin-walled model, see module docstring).

    Parameters
    ----------
    turbine : turbine with a blade layup.
    s : span positions (default: 41 stations).
    n_contour : points on the resampled airfoil contour.
    """
    b = turbine.blade
    if b.layup is None or not b.layup.layers:
        raise InputError("blade.layup", None, "a composite layup to compute section properties")
    s = np.linspace(0.0, 1.0, 41) if s is None else np.asarray(s, dtype=float)
    mats = turbine.materials
    for lay in b.layup.layers:
        if lay.material not in mats:
            raise InputError(f"blade.layup.layers[{lay.name}].material", lay.material, "a defined material")
    n = s.size
    Ks, Ms = np.zeros((n, 6, 6)), np.zeros((n, 6, 6))
    for k, sk in enumerate(s):
        x, y = contour_at(sk, b.airfoil_positions, b.airfoil_names, turbine.airfoils,
                          float(b.at("relative_thickness", sk)))
        # resample the contour uniformly in arc length (closed polygon)
        a = nd_arc(x, y)
        keep = np.concatenate([[True], np.diff(a) > 1e-12])
        x, y, a = x[keep], y[keep], a[keep]
        ag = np.linspace(0.0, 1.0, n_contour + 1)
        xg, yg = np.interp(ag, a, x), np.interp(ag, a, y)
        xg[-1], yg[-1] = xg[0], yg[0]  # close a blunt trailing edge
        chord, pa = float(b.at("chord", sk)), float(b.at("pitch_axis", sk))
        yz = np.column_stack([yg * chord, (xg - pa) * chord])
        amid = 0.5 * (ag[:-1] + ag[1:])
        plies: list[list] = [[] for _ in range(n_contour)]
        for lay in b.layup.shell_layers:
            t = float(lay.thickness_at(sk))
            if t <= 0:
                continue
            a0, a1 = (float(v) for v in lay.arcs_at(sk))
            inside = (amid >= a0) & (amid <= a1) if a1 >= a0 else (amid >= a0) | (amid <= a1)
            ang = float(lay.orientation_at(sk))
            for i in np.nonzero(inside)[0]:
                plies[i].append((mats[lay.material], t, ang))
        props = np.array([laminate_membrane(p) for p in plies])
        t_seg = np.array([sum(t for _, t, _ in p) for p in plies])
        yz = _offset_inwards(yz, t_seg, xg, yg, chord)
        webs = []
        for w in b.layup.webs:
            if not (w.s_start - 1e-12 <= sk <= w.s_end + 1e-12):
                continue
            wp = [(mats[lay.material], float(lay.thickness_at(sk)), float(lay.orientation_at(sk)))
                  for lay in b.layup.web_layers(w.name)]
            Et, Gt, mt = laminate_membrane(wp)
            if Et <= 0:
                continue
            a0, a1 = (float(v) for v in w.arcs_at(sk))
            i, j = int(np.argmin(np.abs(ag[:-1] - a0))), int(np.argmin(np.abs(ag[:-1] - a1)))
            webs.append((min(i, j), max(i, j), Et, Gt, mt))
        if np.any(props[:, 0] <= 0):
            i = int(np.argmax(props[:, 0] <= 0))
            raise InputError("blade.layup", f"no laminate at span {sk:.3f}, arc {amid[i]:.3f}",
                             "shell layers covering the whole contour")
        Ks[k], Ms[k] = thin_wall_properties(yz, props[:, 0], props[:, 1], props[:, 2], webs)
    return BeamProperties(s=s, stiffness=Ks, mass=Ms, twist=b.at("twist", s), length=b.length,
                          source="thin-walled layup section (model/section.py)")
