"""6x6 section matrices from HAWC2 Timoshenko st columns, about the c2 (half-chord) point.

HAWC2 gives, per station, principal properties and where they act in the local c2 frame
(x towards the leading edge, y towards the suction side, rotated with the c2 twist): axial and
bending (``E A``, ``E I_x``, ``E I_y``) at the elastic centre ``(x_e, y_e)``, shear and torsion
(``k_x G A``, ``k_y G A``, ``G I_p``) at the shear centre ``(x_sh, y_sh)``, both in principal axes
turned by ``pitch`` about z; mass ``m`` at ``(x_cg, y_cg)`` with radii of gyration ``ri_x, ri_y``
about the elastic centre.  In the BeamDyn order and frame (x towards the suction side, y towards
the trailing edge: ``x_bd = y_h2``, ``y_bd = -x_h2``, z unchanged, angles about z unchanged) the
matrices about the reference point O are ``K_O = sum_P (R T_P)^T D_P (R T_P)``, with ``T_P`` the
rigid-offset strain transfer to point P (``eps_P = eps + k1 y_P - k2 x_P``, ``g1_P = g1 - k3 y_P``,
``g2_P = g2 + k3 x_P``) and R the rotation into principal axes; the mass matrix is the rigid-body
matrix of the section about O (inertia moved from the elastic centre to the CG, then to O).
"""

from __future__ import annotations

import numpy as np

from windflutter.model.beamprops import beamdyn_mass_matrix


def _transfer(px: np.ndarray, py: np.ndarray) -> np.ndarray:
    """(n, 6, 6) strain transfer from O to the point (px, py) (BeamDyn order)."""
    n = px.size
    T = np.tile(np.eye(6), (n, 1, 1))
    T[:, 2, 3], T[:, 2, 4] = py, -px  # axial strain from the curvatures
    T[:, 0, 5], T[:, 1, 5] = -py, px  # shear strains from the twist rate
    return T


def _rotation(theta: np.ndarray) -> np.ndarray:
    """(n, 6, 6) components in axes turned by ``theta`` about z (vectors (1, 2) and (4, 5))."""
    c, s = np.cos(theta), np.sin(theta)
    R = np.tile(np.eye(6), (theta.size, 1, 1))
    for a, b in ((0, 1), (3, 4)):
        R[:, a, a], R[:, a, b], R[:, b, a], R[:, b, b] = c, s, -s, c
    return R


def hawc2_stiffness(st: dict[str, np.ndarray]) -> np.ndarray:
    """(n, 6, 6) BeamDyn-order stiffness about the c2 point."""
    E, G, A = st["E"], st["G"], st["A"]
    theta = np.radians(st["pitch"])
    R = _rotation(theta)
    n = E.size
    D_c = np.zeros((n, 6, 6))
    D_c[:, 2, 2] = E * A
    D_c[:, 3, 3] = E * st["I_y"]  # bending about x_bd = y_h2: edgewise
    D_c[:, 4, 4] = E * st["I_x"]  # bending about y_bd = -x_h2: flapwise
    D_s = np.zeros((n, 6, 6))
    D_s[:, 0, 0] = st["k_y"] * G * A  # shear along x_bd = y_h2
    D_s[:, 1, 1] = st["k_x"] * G * A  # shear along y_bd = -x_h2
    D_s[:, 5, 5] = G * st["I_p"]
    K = np.zeros((n, 6, 6))
    for D, (x, y) in ((D_c, ("x_e", "y_e")), (D_s, ("x_sh", "y_sh"))):
        B = R @ _transfer(st[y], -st[x])
        K += B.transpose(0, 2, 1) @ D @ B
    return 0.5 * (K + K.transpose(0, 2, 1))


def hawc2_mass(st: dict[str, np.ndarray]) -> np.ndarray:
    """(n, 6, 6) BeamDyn-order mass matrix about the c2 point (inertia about O)."""
    m = st["m"]
    theta = np.radians(st["pitch"])
    c, s = np.cos(theta), np.sin(theta)
    # principal mass moments about the elastic centre: about x_bd (= y_h2) ri_y^2 m, about y_bd ri_x^2 m
    j1, j2 = m * st["ri_y"] ** 2, m * st["ri_x"] ** 2
    J = np.empty((m.size, 2, 2))  # in BeamDyn axes: R^T diag(j1, j2) R
    J[:, 0, 0] = c * c * j1 + s * s * j2
    J[:, 1, 1] = s * s * j1 + c * c * j2
    J[:, 0, 1] = J[:, 1, 0] = c * s * (j1 - j2)
    ex, ey = st["y_e"], -st["x_e"]  # elastic centre, BeamDyn axes
    gx, gy = st["y_cg"], -st["x_cg"]  # CG, BeamDyn axes
    J_G = J - _parallel(m, gx - ex, gy - ey)
    J_O = J_G + _parallel(m, gx, gy)
    return beamdyn_mass_matrix(m, gx, gy, J_O[:, 0, 0], J_O[:, 1, 1], J_O[:, 0, 0] + J_O[:, 1, 1], -J_O[:, 0, 1])


def _parallel(m: np.ndarray, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
    """In-plane (2x2) parallel-axis term m (|d|^2 I - d d^T) of a mass at offset (dx, dy)."""
    P = np.empty((m.size, 2, 2))
    P[:, 0, 0], P[:, 1, 1] = m * dy * dy, m * dx * dx
    P[:, 0, 1] = P[:, 1, 0] = -m * dx * dy
    return P
