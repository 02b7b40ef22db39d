"""Transverse shear of the 4-node shells by assumed covariant strains (MITC4).

pyfe3d's ``Quad4`` integrates the transverse shear at one point (Hughes et al. 1977; its module
documentation): the element then has a zero-energy mode besides the rigid-body ones, the
``w``-hourglass ``w = (x - x_c)(y - y_c)`` at zero rotations, which survives assembly wherever no
support holds it.  A compressive membrane stress gives that mode a negative geometric stiffness,
and a blade's stiffness then turns indefinite in a mode that alternates node to node
(``docs/mesh.md``, "Transverse shear").  Here the shear energy of each element is replaced by that of
the MITC4 element of Dvorkin and Bathe (1984, Eng. Comput. 1(1) 77-88): the covariant transverse
shear strains are taken at the midpoints of the four edges (where the bilinear element represents
them without locking) and interpolated across the element, the energy integrated with 2 x 2 Gauss
points.  The element passes the constant-shear patch test, keeps the Kirchhoff limit free of
shear locking and has no spurious mode.

What is replaced is computed here in pyfe3d's own element frame and with its own element
transverse shear stiffness (``ShellProp.calc_Ats_element``): pyfe3d's one-point shear terms are
subtracted and the MITC4 terms added to each element's 24 x 24 block, the rest of pyfe3d's
element (membrane, bending, drilling, coupling) kept as it is.
"""

from __future__ import annotations

import numpy as np

_XI = np.array([-1.0, 1.0, 1.0, -1.0])
_ETA = np.array([-1.0, -1.0, 1.0, 1.0])
_GP = np.array([-1.0, 1.0]) / np.sqrt(3.0)
# the tying points: (node a, node b) of the edge, the natural direction of the strain (0: xi, 1: eta)
_EDGES = {"C": (0, 1, 0), "A": (3, 2, 0), "B": (0, 3, 1), "D": (1, 2, 1)}
W, RX, RY = 2, 3, 4  # local DOF offsets within a node's six


def element_frames(X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """pyfe3d's ``Quad4`` frame: ``R`` (ne, 3, 3), rows the element x, y, z axes (z along
    ``(x2 - x4) x (x3 - x1)``, x along ``(x3 - x1) + (x2 - x4)``), and the nodes' in-plane
    coordinates ``xy`` (ne, 4, 2) in it (a warped element projected on its plane)."""
    v13 = X[:, 2] - X[:, 0]
    v42 = X[:, 1] - X[:, 3]
    ez = np.cross(v42, v13)
    ez /= np.linalg.norm(ez, axis=1, keepdims=True)
    ex = v13 + v42
    ex /= np.linalg.norm(ex, axis=1, keepdims=True)
    ey = np.cross(ez, ex)
    R = np.stack([ex, ey, ez], axis=1)
    xy = np.einsum("eij,enj->eni", R[:, :2, :], X - X.mean(axis=1, keepdims=True))
    return R, xy


def _jacobian(xy: np.ndarray, xi: float, eta: float) -> tuple[np.ndarray, np.ndarray]:
    """``J`` (ne, 2, 2), ``J[a, i] = d x_i / d xi_a``, and the shape-function derivatives (2, 4)."""
    dN = np.stack([0.25 * _XI * (1 + eta * _ETA), 0.25 * _ETA * (1 + xi * _XI)])
    return np.einsum("an,eni->eai", dN, xy), dN


def _cartesian(J: np.ndarray, Bnat: np.ndarray) -> np.ndarray:
    """Rows ``(gamma_xz, gamma_yz)`` (ne, 2, 24) from the natural rows ``(e_xi, e_eta)``: ``e = J gamma``."""
    return np.linalg.solve(J, Bnat)


def _energy(B: np.ndarray, C: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """``weight B^T C B`` per element (ne, 24, 24), batched matrix products (an einsum of the four
    operands took 0.1 s a call on 4600 elements)."""
    return np.matmul(np.swapaxes(B, 1, 2), weight[:, None, None] * np.matmul(C, B))


def _shear_c(Ats: np.ndarray) -> np.ndarray:
    """pyfe3d's ``[[A44, A45], [A45, A55]]`` (rows yz, xz) as the matrix of ``(gamma_xz, gamma_yz)``."""
    return Ats[:, ::-1, ::-1]


def mitc4_shear(xy: np.ndarray, Ats: np.ndarray) -> np.ndarray:
    """MITC4 transverse shear stiffness (ne, 24, 24) in the element frame (DOFs per node ``u, v, w,
    r_x, r_y, r_z``; ``gamma_xz = w_,x + r_y``, ``gamma_yz = w_,y - r_x``, pyfe3d's convention)."""
    ne = xy.shape[0]
    tied = {}
    for name, (a, b, d) in _EDGES.items():
        g = 0.5 * (xy[:, b] - xy[:, a])  # d x / d xi_d along the edge (ne, 2)
        row = np.zeros((ne, 24))
        row[:, 6 * b + W] += 0.5
        row[:, 6 * a + W] -= 0.5
        for n in (a, b):  # the edge midpoint's rotation psi = (r_y, -r_x), half of each node's
            row[:, 6 * n + RY] += 0.5 * g[:, 0]
            row[:, 6 * n + RX] -= 0.5 * g[:, 1]
        tied[name] = row
    C = _shear_c(Ats)
    K = np.zeros((ne, 24, 24))
    for xi in _GP:
        for eta in _GP:
            J, _ = _jacobian(xy, xi, eta)
            e_xi = 0.5 * (1 - eta) * tied["C"] + 0.5 * (1 + eta) * tied["A"]
            e_eta = 0.5 * (1 - xi) * tied["B"] + 0.5 * (1 + xi) * tied["D"]
            B = _cartesian(J, np.stack([e_xi, e_eta], axis=1))
            K += _energy(B, C, np.linalg.det(J))
    return K


def _pyfe3d_rows(xy: np.ndarray, xi: float, eta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """pyfe3d's gradient and rotation rows of ``(gamma_xz, gamma_yz)`` (ne, 2, 24) at a point, det J."""
    ne = xy.shape[0]
    J, dN = _jacobian(xy, xi, eta)
    G = np.linalg.solve(J, np.broadcast_to(dN, (ne, 2, 4)))  # (ne, 2, 4): d N / d x, d N / d y
    N = 0.25 * (1 + xi * _XI) * (1 + eta * _ETA)
    grad, rot = np.zeros((ne, 2, 24)), np.zeros((ne, 2, 24))
    grad[:, :, W::6] = G
    rot[:, 0, RY::6] = N
    rot[:, 1, RX::6] = -N
    return grad, rot, np.linalg.det(J)


def one_point_shear(xy: np.ndarray, Ats: np.ndarray, thick: np.ndarray) -> np.ndarray:
    """pyfe3d ``Quad4``'s transverse shear stiffness (ne, 24, 24), element frame: every term at the
    centroid (weight 4) where ``h / sqrt(area) < 1``; for thicker elements the gradient-gradient
    term with 2 x 2 points."""
    C = _shear_c(Ats)
    grad, rot, det = _pyfe3d_rows(xy, 0.0, 0.0)
    B = grad + rot
    K = _energy(B, C, 4.0 * det)
    if np.any(thick):
        t = np.asarray(thick, bool)
        Kg = np.zeros((int(t.sum()), 24, 24))
        for xi in _GP:
            for eta in _GP:
                g, _, d = _pyfe3d_rows(xy[t], xi, eta)
                Kg += _energy(g, C[t], d)
        K[t] += Kg - _energy(grad[t], C[t], 4.0 * det[t])
    return K


def to_global(K: np.ndarray, R: np.ndarray) -> np.ndarray:
    """Element-frame blocks (ne, 24, 24) in global axes: ``T^T K T``, ``T`` = eight blocks ``R``."""
    ne = K.shape[0]
    Kl = K.reshape(ne, 8, 3, 8, 3)
    return np.einsum("eca,eIcJd,edb->eIaJb", R, Kl, R, optimize=True).reshape(ne, 24, 24)


def mitc4_correction(X: np.ndarray, Ats: np.ndarray, h: np.ndarray) -> np.ndarray:
    """What turns pyfe3d's ``Quad4`` blocks into MITC4's (ne, 24, 24), global axes: MITC4's shear
    minus pyfe3d's.  ``X`` (ne, 4, 3) the nodes, ``Ats`` (ne, 2, 2) pyfe3d's element transverse
    shear stiffness ``[[A44, A45], [A45, A55]]`` (N/m), ``h`` (ne,) the laminate thicknesses (m)."""
    R, xy = element_frames(X)
    d = xy[:, [0, 1, 2, 3, 0]]
    area = 0.5 * np.abs(np.sum(d[:, :-1, 0] * d[:, 1:, 1] - d[:, 1:, 0] * d[:, :-1, 1], axis=1))
    thick = np.asarray(h, float) >= np.sqrt(area)
    return to_global(mitc4_shear(xy, Ats) - one_point_shear(xy, Ats, thick), R)
