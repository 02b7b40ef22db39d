"""4-node shells: pyfe3d 0.11 ``Quad4`` stiffness/mass, our own full membrane geometric stiffness.

What comes from pyfe3d (BSD-3, pinned ``>=0.11.0,<0.12``): the Quad4 element (FSDT, mixed
integration after Hughes et al. 1977, physics-based Allman/Hughes-Brezzi drilling stiffness),
its consistent/lumped mass, and the laminate ABD/transverse-shear stiffness
(``shellprop_utils.laminated_plate``) with the ply angles measured from a per-element material
direction.  What is ours: the mapping from :class:`ShellProperty` laminates, vectorised COO
assembly, and the membrane geometric stiffness (pyfe3d's KG only uses the out-of-plane
displacement gradient, which gives about half of the in-plane stiffening).
"""

from __future__ import annotations

import functools

import numpy as np

from windflutter.config.declarations import SHELL_SHEAR_MODELS
from windflutter.errors import InputError, check_choice
from windflutter.structure.fem import FEModel, IsotropicMaterial, OrthotropicMaterial, ShellProperty
from windflutter.structure.shell_shear import element_frames, mitc4_correction


def pyfe3d_shellprop(p: ShellProperty, index: int = 0):
    """pyfe3d ``ShellProp`` of a laminate (ply angles in degrees from the material axis)."""
    from pyfe3d.shellprop_utils import laminated_plate

    if not p.plies:
        raise InputError(f"shell_properties[{index}].plies", (), "at least one ply")
    stack, plyts, props, rhos = [], [], [], []
    for j, ply in enumerate(p.plies):
        m = ply.material
        if not (np.isfinite(ply.thickness) and ply.thickness > 0):
            raise InputError(f"shell_properties[{index}].plies[{j}].thickness", ply.thickness, "a positive thickness (m)")
        if isinstance(m, IsotropicMaterial):
            # nu = 0.5 (incompressible limit) is admissible: the shell is plane stress, whose
            # stiffness E/(1 - nu^2) and G = E/(2 (1 + nu)) stay regular (only the 3D bulk modulus
            # E/(3 (1 - 2 nu)) would not).  WISDEM's IEA 10 MW balsa has nu = 0.5.
            if not (m.E > 0 and -1 < m.nu <= 0.5 and m.rho >= 0):
                raise InputError(f"shell_properties[{index}].plies[{j}].material", m, "E > 0, -1 < nu <= 0.5, rho >= 0")
            props.append((m.E, m.nu))
        elif isinstance(m, OrthotropicMaterial):
            if not (m.E1 > 0 and m.E2 > 0 and m.G12 > 0 and m.G13 > 0 and m.G23 > 0 and m.rho >= 0
                    and m.nu12**2 < m.E1 / m.E2):
                raise InputError(f"shell_properties[{index}].plies[{j}].material", m,
                                 "positive moduli, rho >= 0 and nu12^2 < E1/E2")
            props.append((m.E1, m.E2, m.nu12, m.G12, m.G13, m.G23))
        else:
            raise InputError(f"shell_properties[{index}].plies[{j}].material", type(m).__name__,
                             "an IsotropicMaterial or OrthotropicMaterial")
        stack.append(np.degrees(ply.angle))
        plyts.append(ply.thickness)
        rhos.append(m.rho)
    return laminated_plate(stack=stack, plyts=plyts, laminaprops=props, rhos=rhos, offset=p.offset)


@functools.lru_cache(maxsize=16384)
def _cached_shellprop(p: ShellProperty):
    return pyfe3d_shellprop(p)


def _shellprop(p: ShellProperty, index: int):
    """:func:`pyfe3d_shellprop` cached by value (read only by the element routines; a deflected
    shell blade's element forces and stress are computed at every operating point)."""
    try:
        return _cached_shellprop(p)
    except InputError:
        pyfe3d_shellprop(p, index)  # the same error, naming the property's index
        raise


@functools.lru_cache(maxsize=16384)
def _laminate_ab(p: ShellProperty) -> tuple[tuple, tuple]:
    sp = pyfe3d_shellprop(p)
    return ((sp.A11, sp.A12, sp.A16), (sp.A12, sp.A22, sp.A26), (sp.A16, sp.A26, sp.A66)), \
        ((sp.B11, sp.B12, sp.B16), (sp.B12, sp.B22, sp.B26), (sp.B16, sp.B26, sp.B66))


def _membrane_ab(p: ShellProperty, index: int) -> tuple[tuple, tuple]:
    """The laminate's membrane ``A`` and coupling ``B`` (3 x 3 each, N/m and N) of
    :func:`pyfe3d_shellprop`, cached by value (a shell blade's steady state asks for them at every
    rotor speed: 0.3 s a call on the NREL 5 MW)."""
    try:
        return _laminate_ab(p)
    except InputError:
        pyfe3d_shellprop(p, index)  # the same error, naming the property's index
        raise


def shell_coo(fe: FEModel, mass: str = "consistent"):
    """COO triplets ((r, c, v) for K, (r, c, v) for M) of all shell elements (pyfe3d Quad4)."""
    return _quad4_coo(fe, 0 if mass == "consistent" else 1)


def shell_kc0_coo(fe: FEModel):
    """COO triplets (r, c, v) of the shells' linear stiffness alone (pyfe3d Quad4 ``KC0``, global
    axes), ``Quad4Data().KC0_SPARSE_SIZE`` consecutive entries per element in ``fe.shell_conn`` order."""
    return _quad4_coo(fe, None)[0]


def element_blocks(triplets: tuple, conn: np.ndarray) -> np.ndarray:
    """(ne, 24, 24) dense element blocks (DOFs node by node in ``conn`` order) of COO ``triplets``
    ``(r, c, v)`` written element by element, the same number per element (pyfe3d's layout)."""
    r, c, v = triplets
    ne = conn.shape[0]
    nk = r.size // max(ne, 1)
    li, lj = (element_local_dof(d.reshape(ne, nk), conn) for d in (r, c))
    flat = (np.arange(ne)[:, None] * 576 + 24 * li + lj).ravel()
    return np.bincount(flat, weights=v, minlength=576 * ne).reshape(ne, 24, 24)


def shell_element_blocks(fe: FEModel, mass: str = "consistent") -> tuple[np.ndarray, np.ndarray]:
    """``(K, M)`` each (ne, 24, 24): every shell element's stiffness and mass in global axes, DOFs
    node by node in ``fe.shell_conn`` order -- the blocks :func:`shell_coo` assembles (the
    model's transverse shear included), e.g. to carry them rigidly to another configuration
    (:func:`turned_blocks`)."""
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    Kt, Mt = shell_coo(fe, mass)
    return element_blocks(Kt, conn), element_blocks(Mt, conn)


def turned_blocks(B: np.ndarray, Re: np.ndarray) -> np.ndarray:
    """Element blocks ``B`` (ne, 24, 24) (global axes, :func:`shell_element_blocks`) of elements
    carried rigidly by the rotations ``Re`` (ne, 3, 3): ``Q B Q^T``, ``Q`` the eight diagonal blocks
    ``Re`` (each node's translation and rotation).  An element's stiffness and mass in its own frame
    do not change under a rigid rotation: this is the co-rotational element's material part."""
    ne = B.shape[0]
    Re = np.asarray(Re, dtype=float)
    X = np.matmul(Re[:, None], np.asarray(B, dtype=float).reshape(ne, 8, 3, 24))
    X = np.matmul(X.reshape(ne, 24, 8, 3), np.swapaxes(Re, 1, 2)[:, None])
    return X.reshape(ne, 24, 24)


def _quad4_coo(fe: FEModel, mtype: int | None):
    """(K triplets, M triplets or None): mass type 0 consistent, 1 lumped, None no mass."""
    from pyfe3d import Quad4, Quad4Data, Quad4Probe

    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    pid = np.asarray(fe.shell_prop, dtype=np.int64)
    matdir = np.asarray(fe.shell_matdir, dtype=float)
    ne = conn.shape[0]
    props = [_shellprop(p, i) for i, p in enumerate(fe.shell_properties)]
    data = Quad4Data()
    nk, nm = data.KC0_SPARSE_SIZE, (data.M_SPARSE_SIZE if mtype is not None else 0)
    Kr = np.zeros(ne * nk, dtype=np.int64)
    Kc = np.zeros(ne * nk, dtype=np.int64)
    Kv = np.zeros(ne * nk)
    Mr = np.zeros(ne * nm, dtype=np.int64)
    Mc = np.zeros(ne * nm, dtype=np.int64)
    Mv = np.zeros(ne * nm)
    x = np.ascontiguousarray(np.asarray(fe.nodes, dtype=float).ravel())
    check_quads(fe)
    probe = Quad4Probe()
    q = Quad4(probe)
    c6 = 6 * conn
    Xe = np.asarray(fe.nodes, dtype=float)[conn]
    cs = material_rotation(Xe, matdir)
    mitc4 = shear_model(fe) == "mitc4"
    Ats, h = (np.zeros((ne, 2, 2)), np.zeros(ne)) if mitc4 else (None, None)
    for e in range(ne):
        q.c1, q.c2, q.c3, q.c4 = int(c6[e, 0]), int(c6[e, 1]), int(c6[e, 2]), int(c6[e, 3])
        q.init_k_KC0 = e * nk
        q.init_k_M = e * nm
        # element axes only (no material vector: pyfe3d then leaves m11..m22 alone), then the
        # material rotation computed robustly here (see material_rotation)
        q.update_rotation_matrix(x)
        c, sn = cs[e]
        q.m11, q.m12, q.m21, q.m22 = c, -sn, sn, c
        q.update_probe_xe(x)
        prop = props[pid[e]]
        q.update_KC0(Kr, Kc, Kv, prop)
        if mitc4:  # the element's own transverse shear stiffness, for its MITC4 shear below
            Ats[e] = prop.calc_Ats_element(np.degrees(np.arctan2(sn, c)))
            h[e] = prop.h
        if mtype is not None:
            q.update_M(Mr, Mc, Mv, prop, mtype)
    if mitc4 and ne:
        _add_blocks(Kv, Kr, Kc, conn, mitc4_correction(Xe, Ats, h))
    if mtype is None:
        return (Kr, Kc, Kv), None
    if mtype == 1:  # lumped mass writes only the first 120 entries per element
        keep = (np.arange(ne * nm) % nm) < 120
        Mr, Mc, Mv = Mr[keep], Mc[keep], Mv[keep]
    return (Kr, Kc, Kv), (Mr, Mc, Mv)


def shear_model(fe: FEModel) -> str:
    """The shells' transverse shear formulation of ``fe``, checked (:data:`~windflutter.config.
    declarations.SHELL_SHEAR_MODELS`)."""
    return check_choice("shell_shear", fe.shell_shear, SHELL_SHEAR_MODELS)


def _add_blocks(Kv: np.ndarray, Kr: np.ndarray, Kc: np.ndarray, conn: np.ndarray, D: np.ndarray) -> None:
    """Add the (ne, 24, 24) element blocks ``D`` (global axes, DOFs node by node in ``conn``
    order) to pyfe3d's triplet values ``Kv`` in place, entry by entry at pyfe3d's own positions."""
    ne = conn.shape[0]
    rows, cols = Kr.reshape(ne, -1), Kc.reshape(ne, -1)
    dofs = (6 * conn[:, :, None] + np.arange(6)).reshape(ne, 24)
    li, lj = element_local_dof(rows[:1], conn[:1])[0], element_local_dof(cols[:1], conn[:1])[0]
    if np.array_equal(dofs[:, li], rows) and np.array_equal(dofs[:, lj], cols):  # one layout: the first's
        Kv += D.reshape(ne, -1)[:, li * 24 + lj].ravel()
    else:
        li, lj = element_local_dof(rows, conn), element_local_dof(cols, conn)
        Kv += np.take_along_axis(D.reshape(ne, -1), li * 24 + lj, axis=1).ravel()


def element_local_dof(dof: np.ndarray, conn: np.ndarray) -> np.ndarray:
    """Each global DOF of ``dof`` (ne, m), one row an element's (pyfe3d's triplets of one element), as
    its local index in that element (its node's place in ``conn`` x 6 + component)."""
    return np.argmax(dof[:, :, None] // 6 == conn[:, None, :], axis=2) * 6 + dof % 6


def material_rotation(X: np.ndarray, matdir: np.ndarray) -> np.ndarray:
    """(cos phi, sin phi) per element: angle ``phi`` from pyfe3d's Quad4 element x axis to the
    material direction projected on the element, positive about the element normal.

    pyfe3d 0.11 ``Quad4.update_rotation_matrix(x, xmat...)`` computes ``cos = xmat . x_e`` from
    two unit vectors and ``sin = sqrt(1 - cos**2)``; when the material axis is (numerically) the
    element x axis, round-off gives ``cos = 1 + 2.2e-16`` and ``sin = NaN`` (16 % of randomly
    oriented rectangles with the exact x axis as material direction), which poisons K and M.
    Here ``phi = atan2(xmat . y_e, xmat . x_e)`` (no square root; exact at 0), and pyfe3d's
    sign convention ``m11 = m22 = cos``, ``m12 = -sin``, ``m21 = sin`` is applied by the caller.
    The element frame is pyfe3d's: ``z`` along ``(x2 - x4) x (x3 - x1)``, ``x`` along
    ``(x3 - x1) + (x2 - x4)``, ``y = z x x``.  A material direction normal to the element gives
    ``phi = 0`` (pyfe3d's behaviour: element axes).

    Parameters
    ----------
    X : (ne, 4, 3) node coordinates of each quad (m).
    matdir : (ne, 3) material direction vectors (any length).
    """
    R, _ = element_frames(X)
    ex, ey = R[:, 0], R[:, 1]
    md = np.asarray(matdir, dtype=float)
    a, b = np.sum(md * ex, axis=1), np.sum(md * ey, axis=1)
    normal = np.hypot(a, b) <= 1e-10 * np.maximum(np.linalg.norm(md, axis=1), 1e-300)
    phi = np.where(normal, 0.0, np.arctan2(b, a))
    return np.column_stack([np.cos(phi), np.sin(phi)])


def check_quads(fe: FEModel) -> None:
    """Reject degenerate quads (zero area or repeated nodes) with an InputError."""
    X = np.asarray(fe.nodes, dtype=float)[np.asarray(fe.shell_conn, dtype=np.int64)]
    nrm = np.cross(X[:, 2] - X[:, 0], X[:, 1] - X[:, 3])
    a2 = np.linalg.norm(nrm, axis=1)
    diag = np.maximum(np.linalg.norm(X[:, 2] - X[:, 0], axis=1), np.linalg.norm(X[:, 1] - X[:, 3], axis=1))
    bad = np.nonzero(a2 <= 1e-10 * diag**2)[0]
    if bad.size:
        e = int(bad[0])
        raise InputError(f"shell_conn[{e}]", np.asarray(fe.shell_conn)[e].tolist(), "a non-degenerate quadrilateral")


_GP = np.array([-1.0, 1.0]) / np.sqrt(3.0)
_XI = np.array([-1.0, 1.0, 1.0, -1.0])
_ETA = np.array([-1.0, -1.0, 1.0, 1.0])


def shell_frames(fe: FEModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per-element local frame with x along the projected material direction.

    Returns
    -------
    R : (ne, 3, 3) rows = local x, y, z (normal) in global axes.
    xy : (ne, 4, 2) local in-plane node coordinates (m) relative to the centroid.
    X : (ne, 4, 3) global node coordinates.
    """
    X = np.asarray(fe.nodes, dtype=float)[np.asarray(fe.shell_conn, dtype=np.int64)]
    n = np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 1])
    n /= np.linalg.norm(n, axis=1)[:, None]
    md = np.asarray(fe.shell_matdir, dtype=float)
    ex = md - np.sum(md * n, axis=1)[:, None] * n
    nx = np.linalg.norm(ex, axis=1)
    fallback = (X[:, 2] - X[:, 0]) + (X[:, 1] - X[:, 3])  # pyfe3d's element x axis: v13 + v42
    fallback -= np.sum(fallback * n, axis=1)[:, None] * n
    use_fb = nx <= 1e-8 * np.maximum(np.linalg.norm(md, axis=1), 1e-300)
    ex[use_fb] = fallback[use_fb]
    ex /= np.linalg.norm(ex, axis=1)[:, None]
    ey = np.cross(n, ex)
    R = np.stack([ex, ey, n], axis=1)
    d = X - X.mean(axis=1, keepdims=True)
    xy = np.einsum("eij,enj->eni", R[:, :2, :], d)
    return R, xy, X


def _grad(xy: np.ndarray, xi: float, eta: float) -> tuple[np.ndarray, np.ndarray]:
    """Shape-function gradients (ne, 2, 4) in local x, y and det J (ne,) at (xi, eta)."""
    dxi = 0.25 * _XI * (1 + eta * _ETA)
    deta = 0.25 * _ETA * (1 + xi * _XI)
    dN = np.stack([dxi, deta])  # (2, 4)
    J = np.einsum("an,eni->eai", dN, xy)  # (ne, 2, 2): J[a, i] = d x_i / d xi_a
    det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
    Jinv = np.stack([np.stack([J[:, 1, 1], -J[:, 0, 1]], -1), np.stack([-J[:, 1, 0], J[:, 0, 0]], -1)], 1) / det[:, None, None]
    G = np.einsum("eia,an->ein", Jinv, dN)
    return G, det


def shell_membrane_resultants(fe: FEModel, u0: np.ndarray) -> np.ndarray:
    """Membrane resultants (Nxx, Nyy, Nxy) (N/m) at element centroids, in the material frame.

    ``N = A eps + B kappa`` with strains from the bilinear fields, kappa with pyfe3d's sign
    convention (kxx = ry_x, kyy = -rx_y, kxy = ry_y - rx_x).
    """
    R, xy, _ = shell_frames(fe)
    ab = [_membrane_ab(p, i) for i, p in enumerate(fe.shell_properties)]
    A = np.array([a for a, _ in ab])
    B = np.array([b for _, b in ab])
    pid = np.asarray(fe.shell_prop, dtype=np.int64)
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    U = np.asarray(u0, dtype=float).reshape(-1, 6)[conn]  # (ne, 4, 6)
    ut = np.einsum("eij,enj->eni", R, U[:, :, :3])
    rt = np.einsum("eij,enj->eni", R, U[:, :, 3:])
    G, _ = _grad(xy, 0.0, 0.0)
    du = np.einsum("ean,eni->eia", G, ut)  # du[:, i, a] = d u_i / d x_a
    dr = np.einsum("ean,eni->eia", G, rt)
    eps = np.stack([du[:, 0, 0], du[:, 1, 1], du[:, 0, 1] + du[:, 1, 0]], axis=1)
    kap = np.stack([dr[:, 1, 0], -dr[:, 0, 1], dr[:, 1, 1] - dr[:, 0, 0]], axis=1)
    return np.einsum("eij,ej->ei", A[pid], eps) + np.einsum("eij,ej->ei", B[pid], kap)


def membrane_element_matrices(fe: FEModel, resultants: np.ndarray) -> np.ndarray:
    """(ne, 4, 4) ``int G^T Nm G dA`` of each element (N/m x m^2 / m^2 = N/m): the membrane
    initial-stress matrix per translation component (2x2 Gauss, ``G`` the in-plane shape-function
    gradients, ``Nm = [[Nxx, Nxy], [Nxy, Nyy]]`` of the given ``resultants`` (ne, 3), N/m)."""
    Nres = np.asarray(resultants, dtype=float)
    if Nres.shape != (len(fe.shell_conn), 3) or not np.all(np.isfinite(Nres)):
        raise InputError("resultants", Nres.shape, f"finite ({len(fe.shell_conn)}, 3) membrane resultants (N/m)")
    xy = shell_frames(fe)[1]
    Nm = np.stack([np.stack([Nres[:, 0], Nres[:, 2]], -1), np.stack([Nres[:, 2], Nres[:, 1]], -1)], 1)
    Ge = np.zeros((Nm.shape[0], 4, 4))
    for xi in _GP:
        for eta in _GP:
            G, det = _grad(xy, xi, eta)
            Ge += det[:, None, None] * np.einsum("ean,eab,ebm->enm", G, Nm, G)
    return Ge


def shell_membrane_kg(fe: FEModel, u0: np.ndarray | None, directions: str = "all", resultants: np.ndarray | None = None):
    """COO triplets of the full membrane geometric stiffness of all shells.

    The membrane resultants are those of the displacement ``u0``
    (:func:`shell_membrane_resultants`), or given: ``resultants`` (ne, 3) ``(Nxx, Nyy, Nxy)`` (N/m)
    in each element's material frame (e.g. the stress of another configuration of the same mesh,
    carried with its elements).

    ``directions="normal"`` keeps only the element-normal translation (``(x) n n^T`` instead of
    ``(x) I3``), i.e. a plate-type KG like pyfe3d's; it exists to demonstrate (tests, docs) how
    much in-plane stiffening that misses.

    ``KG_e = int G^T Nm G dA (x) I3`` on (ux, uy, uz) of the 4 nodes, with ``G`` the (2, 4)
    in-plane shape-function gradients, ``Nm = [[Nxx, Nxy], [Nxy, Nyy]]`` (centroid, constant
    per element), 2x2 Gauss.  ``I3`` is frame-invariant, so no rotation to global is needed.
    """
    if directions not in ("all", "normal"):
        raise InputError("directions", directions, "'all' or 'normal'")
    Nres = shell_membrane_resultants(fe, u0) if resultants is None else resultants
    Rf = shell_frames(fe)[0]
    Ge = membrane_element_matrices(fe, Nres)  # checks the resultants
    ne = Ge.shape[0]
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    # expand (4x4) (x) I3 -> rows/cols on translational DOFs
    rn = np.repeat(conn, 4, axis=1)  # (ne, 16) node of row
    cn = np.tile(conn, (1, 4))
    v = Ge.reshape(ne, 16)
    comp = np.arange(3)
    P = np.broadcast_to(np.eye(3), (ne, 3, 3)) if directions == "all" else np.einsum("ei,ej->eij", Rf[:, 2], Rf[:, 2])
    r = (6 * rn[:, :, None, None] + comp[None, None, :, None]) + 0 * comp[None, None, None, :]
    c = (6 * cn[:, :, None, None] + comp[None, None, None, :]) + 0 * comp[None, None, :, None]
    vals = v[:, :, None, None] * P[:, None, :, :]
    return r.ravel(), c.ravel(), vals.ravel()
