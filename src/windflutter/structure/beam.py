"""Two-node 3D Timoshenko beam with a full 6x6 section stiffness and mass (our own element).

Stiffness: *exact* for a uniform element (any fully coupled 6x6 section), obtained from the
flexibility of the element clamped at node 0 and loaded at node 1.  The section resultants
``R(s) = [F; M + s e1 x F]`` (``s`` the distance to node 1) are exact for end loads, so the
complementary energy ``1/2 int R^T C^-1 R dx`` gives the exact tip flexibility

    F = L C^-1 + L^2/2 (A1^T C^-1 + C^-1 A1) + L^3/3 A1^T C^-1 A1,   A1 = [[0, 0], [S(e1), 0]],

and the element stiffness is ``H^T F^-1 H`` with ``H`` mapping nodal DOFs to the deformation of
node 1 relative to the rigid motion of node 0.  This is the "exact/interdependent" option: no
shear locking, shear, extension-bending-torsion couplings and offsets of tension and shear
centres (off-diagonal terms of the 6x6) are all represented exactly for end loads.

Strain measures (section frame, x along the beam): ``Gamma = u' + e1 x theta`` (axial strain,
gamma_xy, gamma_xz) and ``kappa = theta'`` (twist rate, kappa_y, kappa_z), work-conjugate to
(N, Vy, Vz, T, My, Mz).

Mass: consistent mass from the 6x6 section mass with cubic Hermite interpolation of the
transverse translations (rotations ``theta_z = v'``, ``theta_y = -w'``) and linear interpolation
of the axial displacement and twist, integrated with 4-point Gauss (exact for the cubic
products).  Rotary inertia and mass-centre offsets enter through the 6x6 section mass.

Geometric stiffness (prestress): ``N int (v'^2 + w'^2) dx`` with the same Hermite fields.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.linalg_tools import congruence
from windflutter.structure.fem import FEModel

_E1X = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])  # S(e1): S(e1) b = e1 x b
GAUSS_XI, GAUSS_W = np.polynomial.legendre.leggauss(4)
GAUSS_XI = 0.5 * (GAUSS_XI + 1.0)
GAUSS_W = 0.5 * GAUSS_W


def beam_frames(fe: FEModel) -> tuple[np.ndarray, np.ndarray]:
    """Element lengths (m) and rotation matrices (rows = section axes x, y, z in global).

    Returns
    -------
    L : (nb,) lengths (m).
    R : (nb, 3, 3) with ``R @ v_global = v_local``.
    """
    conn = np.asarray(fe.beam_conn, dtype=np.int64)
    x = np.asarray(fe.nodes, dtype=float)
    d = x[conn[:, 1]] - x[conn[:, 0]]
    L = np.linalg.norm(d, axis=1)
    if np.any(L <= 1e-12 * max(1.0, float(np.abs(x).max(initial=0.0)))):
        bad = int(np.argmin(L))
        raise InputError(f"beam_conn[{bad}]", conn[bad].tolist(), "two distinct node positions (zero-length beam)")
    e1 = d / L[:, None]
    o = np.asarray(fe.beam_orient, dtype=float)
    y = o - np.sum(o * e1, axis=1)[:, None] * e1
    ny = np.linalg.norm(y, axis=1)
    on = np.linalg.norm(o, axis=1)
    if np.any(ny <= 1e-8 * np.maximum(on, 1e-300)):
        bad = int(np.argmin(ny / np.maximum(on, 1e-300)))
        raise InputError(f"beam_orient[{bad}]", o[bad].tolist(), "a non-zero vector not parallel to the beam axis")
    y = y / ny[:, None]
    z = np.cross(e1, y)
    R = np.stack([e1, y, z], axis=1)
    return L, R


def _section_arrays(fe: FEModel) -> tuple[np.ndarray, np.ndarray]:
    """Validated section compliance (ns,6,6) and section mass (ns,6,6)."""
    C_inv, Ms = [], []
    for i, s in enumerate(fe.beam_sections):
        C = np.asarray(s.stiffness, dtype=float)
        M = np.asarray(s.mass, dtype=float)
        if C.shape != (6, 6) or not np.all(np.isfinite(C)):
            raise InputError(f"beam_sections[{i}].stiffness", C.shape, "a finite (6, 6) array")
        if M.shape != (6, 6) or not np.all(np.isfinite(M)):
            raise InputError(f"beam_sections[{i}].mass", M.shape, "a finite (6, 6) array")
        Cs = 0.5 * (C + C.T)
        try:
            np.linalg.cholesky(Cs)
        except np.linalg.LinAlgError:
            raise InputError(f"beam_sections[{i}].stiffness", "not positive definite",
                             "a symmetric positive-definite 6x6 section stiffness") from None
        if np.any(np.linalg.eigvalsh(0.5 * (M + M.T)) < -1e-7 * max(np.abs(M).max(), 1e-300)):
            raise InputError(f"beam_sections[{i}].mass", "not positive semi-definite",
                             "a symmetric positive semi-definite 6x6 section mass")
        C_inv.append(np.linalg.inv(Cs))
        Ms.append(0.5 * (M + M.T))
    return np.array(C_inv).reshape(-1, 6, 6), np.array(Ms).reshape(-1, 6, 6)


def block_rotation(R: np.ndarray) -> np.ndarray:
    """(nb, 12, 12) block-diagonal rotation global -> local."""
    nb = R.shape[0]
    T = np.zeros((nb, 12, 12))
    for k in range(4):
        T[:, 3 * k:3 * k + 3, 3 * k:3 * k + 3] = R
    return T


def _H(L: np.ndarray) -> np.ndarray:
    """(nb, 6, 12) map local nodal DOFs -> node-1 deformation relative to node-0 rigid motion."""
    nb = L.shape[0]
    H = np.zeros((nb, 6, 12))
    I3 = np.eye(3)
    H[:, 0:3, 0:3] = -I3
    H[:, 0:3, 3:6] = L[:, None, None] * _E1X
    H[:, 0:3, 6:9] = I3
    H[:, 3:6, 3:6] = -I3
    H[:, 3:6, 9:12] = I3
    return H


def beam_tip_stiffness(L: np.ndarray, C_inv: np.ndarray) -> np.ndarray:
    """Exact (nb, 6, 6) tip stiffness of uniform cantilevers of lengths L and compliances C_inv."""
    A1 = np.zeros((6, 6))
    A1[3:, :3] = _E1X
    L_ = L[:, None, None]
    F = (L_ * C_inv + 0.5 * L_**2 * (A1.T @ C_inv + C_inv @ A1) + (L_**3 / 3.0) * (A1.T @ C_inv @ A1))
    F = 0.5 * (F + np.transpose(F, (0, 2, 1)))
    return np.linalg.inv(F)


def shape_functions(L: np.ndarray, xi: float) -> tuple[np.ndarray, np.ndarray]:
    """Section motion N (nb, 6, 12) and transverse slopes dN (nb, 2, 12) at xi in [0, 1].

    Rows of N: u, v, w, theta_x, theta_y, theta_z (local); rows of dN: v', w'.
    """
    nb = L.shape[0]
    H1, H2, H3, H4 = 1 - 3 * xi**2 + 2 * xi**3, xi - 2 * xi**2 + xi**3, 3 * xi**2 - 2 * xi**3, -xi**2 + xi**3
    d1, d2, d3, d4 = -6 * xi + 6 * xi**2, 1 - 4 * xi + 3 * xi**2, 6 * xi - 6 * xi**2, -2 * xi + 3 * xi**2
    N = np.zeros((nb, 6, 12))
    dN = np.zeros((nb, 2, 12))
    # axial u and twist: linear
    N[:, 0, 0], N[:, 0, 6] = 1 - xi, xi
    N[:, 3, 3], N[:, 3, 9] = 1 - xi, xi
    # v (local y) with theta_z = v'
    N[:, 1, 1], N[:, 1, 5], N[:, 1, 7], N[:, 1, 11] = H1, H2 * L, H3, H4 * L
    dv = np.stack([d1 / L, d2 * np.ones_like(L), d3 / L, d4 * np.ones_like(L)], axis=1)  # dv/dx coefficients
    N[:, 5, 1], N[:, 5, 5], N[:, 5, 7], N[:, 5, 11] = dv[:, 0], dv[:, 1], dv[:, 2], dv[:, 3]
    # w (local z) with theta_y = -w'
    N[:, 2, 2], N[:, 2, 4], N[:, 2, 8], N[:, 2, 10] = H1, -H2 * L, H3, -H4 * L
    N[:, 4, 2], N[:, 4, 4], N[:, 4, 8], N[:, 4, 10] = -dv[:, 0], dv[:, 1], -dv[:, 2], dv[:, 3]
    dN[:, 0, :] = N[:, 5, :]
    dN[:, 1, :] = -N[:, 4, :]
    return N, dN


def gauss_shape_functions(L: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`shape_functions` at every Gauss point (:data:`GAUSS_XI`): N (nq, nb, 6, 12) and
    dN (nq, nb, 2, 12), for quadratures done in one batched product."""
    both = [shape_functions(L, xi) for xi in GAUSS_XI]
    return np.stack([n for n, _ in both]), np.stack([d for _, d in both])


def gauss_sum(L: np.ndarray, A: np.ndarray) -> np.ndarray:
    """``sum_q w_q L A[..., q, e, :, :]``: the Gauss quadrature over the elements' lengths of
    integrands ``A`` (..., nq, nb, i, j) (summed point after point, as a loop would)."""
    return (GAUSS_W[:, None, None, None] * L[None, :, None, None] * A).sum(axis=-4)


def beam_section_integrals(fe: FEModel, elements: np.ndarray, sections, origin: np.ndarray):
    """Element matrices and nodal loads of section quantities, by Gauss quadrature along the beam
    elements ``elements`` (mask or indices) of ``fe``: the generic assembly a section kernel is
    passed to (the rotating-frame terms of :mod:`windflutter.rotor.spin` are one).

    ``sections(X, R) -> (A, a)`` gives, at the Gauss points' positions ``X`` (nq, ne, 3) from
    ``origin`` in the element frames ``R`` (ne, 3, 3) (global -> local), section matrices ``A``
    (k, nq, ne, 6, 6) and section loads ``a`` (nq, ne, 6) per metre, in the element frames.

    Returns ``(mats, loads, dofs)``: ``int N^T A N dx`` (k, ne, 12, 12) and the loads lumped on
    the two nodes with the linear weights ``(1 - xi, xi)`` (ne, 12), both in global axes, and the
    elements' global DOFs (ne, 12).
    """
    conn = np.asarray(fe.beam_conn, dtype=np.int64)[elements]
    L, R = beam_frames(fe)
    L, R = L[elements], R[elements]
    x = np.asarray(fe.nodes, float) - np.asarray(origin, float)
    xi = GAUSS_XI[:, None, None]
    A, a = sections(np.einsum("eij,qej->qei", R, (1.0 - xi) * x[conn[:, 0]] + xi * x[conn[:, 1]]), R)
    N, _ = gauss_shape_functions(L)
    mats = gauss_sum(L, congruence(N, A))
    wl = (GAUSS_W[:, None] * L[None, :])[..., None]
    loads = np.concatenate([(wl * (1.0 - xi) * a).sum(0), (wl * xi * a).sum(0)], axis=1)
    T = block_rotation(R)
    return congruence(T, mats), np.einsum("eki,ek->ei", T, loads), element_dofs(conn)


def beam_local_matrices(fe: FEModel) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Element stiffness and mass in section frames.

    Returns
    -------
    K_loc, M_loc : (nb, 12, 12) local matrices.
    L : (nb,) lengths (m).
    R : (nb, 3, 3) rotations global -> local.
    """
    L, R = beam_frames(fe)
    C_inv, Ms = _section_arrays(fe)
    sec = np.asarray(fe.beam_section, dtype=np.int64)
    Kt = beam_tip_stiffness(L, C_inv[sec])
    H = _H(L)
    K_loc = congruence(H, Kt)
    N, _ = gauss_shape_functions(L)
    M_loc = gauss_sum(L, congruence(N, Ms[sec][None]))
    return K_loc, M_loc, L, R


def beam_global_matrices(fe: FEModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Element matrices in global axes and their global DOF indices.

    Returns
    -------
    K_e, M_e : (nb, 12, 12).
    dofs : (nb, 12) int, global DOF numbers.
    """
    K_loc, M_loc, L, R = beam_local_matrices(fe)
    K_e, M_e = congruence(block_rotation(R), np.stack([K_loc, M_loc]))
    dofs = element_dofs(np.asarray(fe.beam_conn, dtype=np.int64))
    return K_e, M_e, dofs


def element_dofs(conn: np.ndarray) -> np.ndarray:
    """(ne, 6*nn) global DOF numbers of elements with connectivity ``conn`` (ne, nn)."""
    return (6 * conn[:, :, None] + np.arange(6)[None, None, :]).reshape(conn.shape[0], 6 * conn.shape[1])


def beam_axial_force(fe: FEModel, u0: np.ndarray) -> np.ndarray:
    """Axial force N (N, tension positive) in each beam element for the displacement field u0.

    The element's section resultant is constant for end loads; N is its x component.
    """
    L, R = beam_frames(fe)
    C_inv, _ = _section_arrays(fe)
    Kt = beam_tip_stiffness(L, C_inv[np.asarray(fe.beam_section, dtype=np.int64)])
    dofs = element_dofs(np.asarray(fe.beam_conn, dtype=np.int64))
    ue = np.asarray(u0, dtype=float)[dofs]
    ul = np.einsum("eij,ej->ei", block_rotation(R), ue)
    P = np.einsum("eij,ejk,ek->ei", Kt, _H(L), ul)
    return P[:, 0]


def beam_geometric_matrices(fe: FEModel, N_axial: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Geometric stiffness (nb, 12, 12) in global axes for axial forces N_axial (N) and DOFs."""
    L, R = beam_frames(fe)
    _, dN = gauss_shape_functions(L)
    KG_loc = gauss_sum(L, N_axial[None, :, None, None] * np.einsum("qeki,qekj->qeij", dN, dN))
    T = block_rotation(R)
    KG = congruence(T, KG_loc)
    return KG, element_dofs(np.asarray(fe.beam_conn, dtype=np.int64))
