"""Thin-walled beam properties (6x6 stiffness and mass) from the shell layup, per blade element row.

Used for the beam model when the turbine gives no 6x6 properties (e.g. the seed's UpWind layup),
and as an independent classical check of the shell model.  Classical thin-walled theory on the
lofted contour (same geometry and laminates as the shell mesh):

* every skin/web element is a strip of width ``ds`` at section position ``r = (y, z)`` (y flap,
  z edge, turned with the twist; origin on the reference/pitch axis);
* axial stiffness per width ``1/a11`` and in-plane shear stiffness per width ``1/a66`` of the
  laminate (``a = A^-1``, classical lamination theory; x = span), so hoop stresses are free;
* axial strain at r: ``eps = Gamma_x + kappa_y z - kappa_z y`` (the beam element's strain
  measures) gives ``K[0,0] = sum EA``, ``K[0,4] = sum EA z``, ``K[0,5] = -sum EA y``,
  ``K[4,4] = sum EA z^2``, ``K[5,5] = sum EA y^2``, ``K[4,5] = -sum EA y z``;
* torsion: single closed cell along the outer skin (Bredt-Batho ``GJ = 4 A^2 / sum ds/(Gt)``),
  webs neglected in torsion; shear stiffness ``sum Gt ds t_y^2`` / ``t_z^2`` (tangent
  components), shear-centre offsets neglected;
* mass: ``sum rho t ds [[I, -S(r)], [S(r), |r|^2 I - r r^T]]``.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.mesh.blade_shell import blade_shell_mesh
from windflutter.mesh.frames import skew
from windflutter.mesh.loft import chord_frame
from windflutter.mesh.settings import MeshSettings
from windflutter.model.turbine import BeamProperties
from windflutter.structure.fem import IsotropicMaterial, ShellProperty


def ply_Q(m, angle: float) -> np.ndarray:
    """Plane-stress reduced stiffness (3x3, Pa) of a ply rotated by ``angle`` (rad)."""
    if isinstance(m, IsotropicMaterial):
        E1 = E2 = m.E
        nu12 = m.nu
        G12 = m.G
    else:
        E1, E2, nu12, G12 = m.E1, m.E2, m.nu12, m.G12
    nu21 = nu12 * E2 / E1
    d = 1.0 - nu12 * nu21
    Q11, Q22, Q12, Q66 = E1 / d, E2 / d, nu12 * E2 / d, G12
    c, s = np.cos(angle), np.sin(angle)
    Qb11 = Q11 * c**4 + 2 * (Q12 + 2 * Q66) * s**2 * c**2 + Q22 * s**4
    Qb22 = Q11 * s**4 + 2 * (Q12 + 2 * Q66) * s**2 * c**2 + Q22 * c**4
    Qb12 = (Q11 + Q22 - 4 * Q66) * s**2 * c**2 + Q12 * (s**4 + c**4)
    Qb66 = (Q11 + Q22 - 2 * Q12 - 2 * Q66) * s**2 * c**2 + Q66 * (s**4 + c**4)
    Qb16 = (Q11 - Q12 - 2 * Q66) * s * c**3 + (Q12 - Q22 + 2 * Q66) * s**3 * c
    Qb26 = (Q11 - Q12 - 2 * Q66) * s**3 * c + (Q12 - Q22 + 2 * Q66) * s * c**3
    return np.array([[Qb11, Qb12, Qb16], [Qb12, Qb22, Qb26], [Qb16, Qb26, Qb66]])


def laminate_membrane(p: ShellProperty) -> tuple[float, float, float]:
    """(axial stiffness per width 1/a11 (N/m), shear stiffness per width 1/a66 (N/m),
    areal mass (kg/m^2)) of a laminate, x = material axis."""
    A = sum(ply_Q(q.material, q.angle) * q.thickness for q in p.plies)
    a = np.linalg.inv(A)
    return 1.0 / a[0, 0], 1.0 / a[2, 2], p.mass_per_area


def thin_walled_properties(turbine, n_chord: int = 48, n_span: int = 40) -> BeamProperties:
    """6x6 beam properties of the blade from its layup (see module docstring), at the
    ``n_span`` element-row midpoints of a shell mesh with ``n_chord`` elements around."""
    blade = turbine.blade
    if blade.layup is None:
        raise InputError("blade.layup", None, "a layup or 6x6 beam properties for the beam model")
    bm = blade_shell_mesh(blade, turbine.airfoils, turbine.materials, MeshSettings(n_chord=n_chord, n_span=n_span))
    mem = np.array([laminate_membrane(p) for p in bm.properties])  # (np, 3)
    EAw, GAw, mw = mem[bm.prop, 0], mem[bm.prop, 1], mem[bm.prop, 2]
    P = bm.nodes[bm.conn]  # (ne, 4, 3)
    # element row (between stations i and i+1): nearest row centre along the span
    eta_mid = 0.5 * (bm.eta[:-1] + bm.eta[1:])
    zc = 0.5 * (bm.ref_axis[:-1, 2] + bm.ref_axis[1:, 2])
    row = np.argmin(np.abs(P[:, :, 2].mean(axis=1)[:, None] - zc[None, :]), axis=1)
    mid_a = 0.5 * (P[:, 0] + P[:, 1])  # midpoint of the spanwise edge at chordwise node a
    mid_b = 0.5 * (P[:, 3] + P[:, 2])
    ref_mid = 0.5 * (bm.ref_axis[:-1] + bm.ref_axis[1:])
    tw = 0.5 * (bm.twist[:-1] + bm.twist[1:])
    e_c, e_n = chord_frame(tw)
    K = np.zeros((n_span, 6, 6))
    M = np.zeros((n_span, 6, 6))
    skin = bm.region == 0
    for i in range(n_span):
        sel = row == i
        a = mid_a[sel] - ref_mid[i]
        b = mid_b[sel] - ref_mid[i]
        ya, za = a @ e_n[i], a @ e_c[i]
        yb, zb = b @ e_n[i], b @ e_c[i]
        ds = np.hypot(yb - ya, zb - za)
        y, z = 0.5 * (ya + yb), 0.5 * (za + zb)
        ea, ga, m = EAw[sel] * ds, GAw[sel] * ds, mw[sel] * ds
        B = np.stack([np.ones_like(y), z, -y], axis=1)
        K[i][np.ix_([0, 4, 5], [0, 4, 5])] = (ea[:, None] * B).T @ B
        ty, tz = (yb - ya) / ds, (zb - za) / ds
        K[i, 1, 1] = np.sum(ga * ty**2)
        K[i, 2, 2] = np.sum(ga * tz**2)
        sk = skin[sel]
        area = 0.5 * abs(np.sum(ya[sk] * zb[sk] - yb[sk] * za[sk]))
        K[i, 3, 3] = 4 * area**2 / np.sum(ds[sk] / GAw[sel][sk])
        r = np.stack([np.zeros_like(y), y, z], axis=1)
        S = skew(r)
        M[i, :3, :3] = np.eye(3) * m.sum()
        Sm = np.einsum("e,eij->ij", m, S)
        M[i, :3, 3:] = -Sm
        M[i, 3:, :3] = Sm
        M[i, 3:, 3:] = np.einsum("e,eij->ij", m, np.einsum("ei,ei->e", r, r)[:, None, None] * np.eye(3) - r[:, :, None] * r[:, None, :])
    return BeamProperties(s=eta_mid, stiffness=K, mass=M, twist=tw, length=blade.length,
                          source=f"thin-walled sections of the shell layup ({n_chord}x{n_span})")
