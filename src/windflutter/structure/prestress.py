"""Prestress: linear static solution, geometric stiffness, centrifugal load, spin softening.

The geometric (stress) stiffness ``K_sigma`` of a prestressed state is built from a displacement
field ``u0`` (typically ``static_solve(struct, F)``):

* beams: ``N int (v'^2 + w'^2) dx`` on the transverse translations (section frame), N the
  element's axial force (Hermite fields, see :mod:`windflutter.structure.beam`); with
  ``moments=True`` the initial-stress matrix of ALL the element's stress resultants -- axial and
  shear forces, torsion and bending moments -- the geometric part of the co-rotational tangent
  (:mod:`windflutter.structure.corotational`) at the undeformed configuration with the linear
  element forces of ``u0`` (its axial-force part is the Hermite matrix above);
* shells: the COMPLETE initial-stress matrix of the flat facets (default, ``shell="complete"``):
  the co-rotational (EICR) geometric stiffness of each element's nodal forces and moments with its
  membrane initial stress on the deformational motion, :mod:`windflutter.structure.shell_stress`
  (a rigid motion's energy is the external loads' second-order work); or (``shell="membrane"``,
  kept for comparison) the membrane geometric stiffness alone ``int N_ab dS/dx_a dS/dx_b dA (x) I3``
  on all three translations, with the membrane resultants N_ab from the laminate ``A`` and ``B``
  matrices at the element centroid (:mod:`windflutter.structure.shell`), whose hoop resultants
  stiffen rigid rotations of a curved wall (docs/structure.md).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.errors import InputError
from windflutter.linalg_tools import skew as _skew
from windflutter.structure.assembly import Structural
from windflutter.structure.beam import beam_axial_force, beam_geometric_matrices
from windflutter.structure.corotational import beam_tangent, linear_resultants, reference_configuration
from windflutter.structure.fem import FEModel
from windflutter.structure.linalg import NotPositiveDefinite, SPDFactor
from windflutter.structure.shell import shell_membrane_kg, shell_membrane_resultants
from windflutter.structure.shell_stress import shell_complete_kg, shell_element_forces

SHELL_KG = ("complete", "membrane")


def static_solve(struct: Structural, F: np.ndarray, K_extra: sp.spmatrix | None = None) -> np.ndarray:
    """Linear static displacement ``u = T (T^T K T)^-1 T^T F`` in the full numbering.

    Parameters
    ----------
    struct : assembled structure.
    F : (n_dof,) or (n_dof, k) nodal loads (N, N m) in the full numbering; loads on constrained
        DOFs are reactions and are ignored, loads on rigid-link dependent DOFs are carried over to
        the independent node.
    K_extra : optional extra full-numbering stiffness (e.g. spin softening).

    Returns
    -------
    u : displacements (m, rad), same shape as F.
    """
    F = np.asarray(F, dtype=float)
    if F.shape[0] != struct.n_dof or not np.all(np.isfinite(F)):
        raise InputError("F", F.shape, f"a finite load array with first dimension {struct.n_dof}")
    K = struct.Kr
    if K_extra is not None:
        K = (K + struct.reduce(sp.csr_matrix(K_extra))).tocsr()

    try:
        q = SPDFactor(K.tocsc()).solve(struct.reduce_vector(F))
    except NotPositiveDefinite:
        q = spla.splu(K.tocsc()).solve(struct.reduce_vector(F))
    return struct.expand(q)


def geometric_stiffness(fe: FEModel, u0: np.ndarray, moments: bool = False, shell: str = "complete",
                        constraint_forces: np.ndarray | None = None) -> sp.csr_matrix:
    """Geometric stiffness (full numbering, CSR, symmetric) of the prestressed state ``u0``.

    Parameters
    ----------
    fe : the model.
    u0 : (n_dof,) static displacement field (m, rad) in the full numbering.
    moments : beams: the terms of every stress resultant (shear, torsion, bending moments), not
        the axial force's alone (module docstring).
    shell : shells: ``"complete"`` (default) or ``"membrane"`` (module docstring).
    constraint_forces : (n_dof,) ``K u0 - F`` of the state (the loads ``F``): with the complete
        shell matrix, the ribs' term (:func:`diaphragm_geometric_stiffness`) is added.
    """
    if shell not in SHELL_KG:
        raise InputError("shell", shell, f"one of {SHELL_KG}")
    u0 = np.asarray(u0, dtype=float)
    if u0.shape != (fe.n_dof,) or not np.all(np.isfinite(u0)):
        raise InputError("u0", u0.shape, f"a finite ({fe.n_dof},) displacement vector")
    n = fe.n_dof
    rows, cols, vals = [], [], []
    if len(fe.beam_conn):
        if moments:
            KG = beam_tangent(fe, reference_configuration(fe), linear_resultants(fe, u0)).K_geo.tocoo()
            rows.append(KG.row)
            cols.append(KG.col)
            vals.append(KG.data)
        else:
            KG = axial_geometric_stiffness(fe, beam_axial_force(fe, u0)).tocoo()
            rows.append(KG.row)
            cols.append(KG.col)
            vals.append(KG.data)
    if len(fe.shell_conn):
        if shell == "complete":
            r, c, v = shell_complete_kg(fe, shell_element_forces(fe, u0), shell_membrane_resultants(fe, u0))
        else:
            r, c, v = shell_membrane_kg(fe, u0)
        rows.append(r)
        cols.append(c)
        vals.append(v)
    if not rows:
        return sp.csr_matrix((n, n))
    A = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)).tocsr()
    A = ((A + A.T) * 0.5).tocsr()
    if constraint_forces is not None and shell == "complete" and fe.diaphragms:
        A = (A + diaphragm_geometric_stiffness(fe, constraint_forces)).tocsr()
    return A


def diaphragm_geometric_stiffness(fe: FEModel, constraint_forces: np.ndarray) -> sp.csr_matrix:
    """Geometric stiffness (full numbering, CSR) of the ribs' (:class:`~windflutter.structure.fem.Diaphragm`)
    in-plane constraint forces, on each rib's independent node's rotation about its normal.

    A rib is an in-plane rigid tie: the forces it exerts on its dependent nodes ``k`` (the in-plane
    part of ``constraint_forces`` = ``K u0 - F`` there) are balanced in the rib (with its
    independent node's).  Turned rigidly in its plane by ``theta`` about its normal ``n``, the rib,
    as a body carrying the opposite forces, has the initial-stress energy
    ``1/2 theta^2 (-sum_k rho_k . f_k)`` (``rho_k`` the in-plane lever from the independent node):
    the term that cancels the shell's own (complete matrix) energy of those forces in a rigid
    rotation, as :func:`windflutter.system.blade.link_geometric_stiffness` does for the hub links.
    Without it a rib that keeps the wall's Poisson contraction or the tip load's introduction
    (radial forces) stiffens a twist of the end section (on a tube in tension: +182 % of the
    trapeze term).  The rib's tilt (rotation about an in-plane axis) is not tied by the rib and gets
    no term (docs/structure.md).
    """
    cf = np.asarray(constraint_forces, dtype=float)
    if cf.shape != (fe.n_dof,) or not np.all(np.isfinite(cf)):
        raise InputError("constraint_forces", cf.shape, f"a finite ({fe.n_dof},) nodal force vector (N, N m)")
    n = fe.n_dof
    f = cf.reshape(-1, 6)[:, :3]
    X = np.asarray(fe.nodes, dtype=float)
    rows, cols, vals = [], [], []
    for d in fe.diaphragms:
        nrm = np.asarray(d.normal, dtype=float)
        nrm = nrm / np.linalg.norm(nrm)
        dep = np.asarray(d.dependent, dtype=np.int64)
        rho = X[dep] - X[int(d.independent)]
        k = -float(np.sum(rho * f[dep]) - np.sum((rho @ nrm) * (f[dep] @ nrm)))
        i0 = 6 * int(d.independent) + 3 + np.arange(3)
        rows.append(np.repeat(i0, 3))
        cols.append(np.tile(i0, 3))
        vals.append(k * np.outer(nrm, nrm).ravel())
    if not rows:
        return sp.csr_matrix((n, n))
    return sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)).tocsr()


def axial_geometric_stiffness(fe: FEModel, axial_force: np.ndarray) -> sp.csr_matrix:
    """Geometric stiffness (full numbering, CSR, symmetric) of the beams' axial forces alone.

    ``axial_force`` : (n_beams,) axial force (N, tension positive) of each beam element, e.g. the
    co-rotational beam's ``BeamTangent.resultants[:, 6]`` at a deflected equilibrium, acting on
    the elements of ``fe``'s (undeformed) geometry.
    """
    N = np.asarray(axial_force, dtype=float)
    if N.shape != (len(fe.beam_conn),) or not np.all(np.isfinite(N)):
        raise InputError("axial_force", N.shape, f"finite axial forces of the {len(fe.beam_conn)} beam elements")
    n = fe.n_dof
    if not len(N):
        return sp.csr_matrix((n, n))
    KG, d = beam_geometric_matrices(fe, N)
    k = d.shape[1]
    A = sp.coo_matrix((KG.ravel(), (np.repeat(d, k, axis=1).ravel(), np.tile(d, (1, k)).ravel())), shape=(n, n)).tocsr()
    return ((A + A.T) * 0.5).tocsr()


def _omega(omega_vec) -> np.ndarray:
    w = np.asarray(omega_vec, dtype=float).reshape(-1)
    if w.shape != (3,) or not np.all(np.isfinite(w)):
        raise InputError("omega_vec", omega_vec, "a finite 3-vector angular velocity (rad/s)")
    return w


def centrifugal_load(fe: FEModel, struct: Structural | sp.spmatrix, omega_vec, center=(0.0, 0.0, 0.0),
                     nodes: np.ndarray | None = None) -> np.ndarray:
    """Centrifugal nodal loads ``F = -M a`` with ``a = Omega x (Omega x (x - center))``.

    Parameters
    ----------
    fe : the model (node positions).
    struct : assembled structure, or directly its full-numbering mass matrix ``M``.
    omega_vec : (3,) angular velocity (rad/s), global axes.
    center : (3,) a point on the rotation axis (m).
    nodes : optional node indices that rotate (default all), e.g. ``fe.node_groups["rotor"]``.

    Returns
    -------
    F : (n_dof,) loads (N, N m) in the full numbering; the consistent mass matrix also gives
        moments where translations and rotations are coupled (offsets, consistent shell/beam mass).
    """
    w = _omega(omega_vec)
    x = np.asarray(fe.nodes, dtype=float) - np.asarray(center, dtype=float)
    acc = np.cross(w[None, :], np.cross(w[None, :], x))
    a = np.zeros((fe.n_nodes, 6))
    sel = np.arange(fe.n_nodes) if nodes is None else np.asarray(nodes, dtype=np.int64)
    a[sel, :3] = acc[sel]
    M = struct.M if hasattr(struct, "M") else struct
    if M.shape != (fe.n_dof, fe.n_dof):
        raise InputError("M", M.shape, f"a ({fe.n_dof}, {fe.n_dof}) full-numbering mass matrix")
    return -(M @ a.reshape(-1))


def spin_softening(struct: Structural, omega_vec, nodes: np.ndarray | None = None) -> sp.csr_matrix:
    """Spin-softening stiffness ``-Q^T M Q`` (full numbering), Q = blockdiag(S(Omega)) on translations.

    In the rotating frame the centrifugal force on a displacement u is ``-M Omega x (Omega x u)``;
    for translational mass blocks ``m_ij I3`` this is the stiffness ``m_ij S(Omega)^2`` (negative
    semi-definite; zero for motion along Omega).  Rotational-inertia contributions are neglected.
    """
    w = _omega(omega_vec)
    n = struct.fe.n_nodes
    sel = np.arange(n) if nodes is None else np.asarray(nodes, dtype=np.int64)
    S = _skew(w)
    r = (6 * sel[:, None, None] + np.arange(3)[None, :, None]) * np.ones((1, 1, 3), dtype=np.int64)
    c = (6 * sel[:, None, None] + np.arange(3)[None, None, :]) * np.ones((1, 3, 1), dtype=np.int64)
    v = np.broadcast_to(S, (sel.size, 3, 3))
    Q = sp.csr_matrix((v.ravel(), (r.ravel(), c.ravel())), shape=(6 * n, 6 * n))
    return (-(Q.T @ struct.M @ Q)).tocsr()


def buckling_factors(struct: Structural, K_sigma: sp.spmatrix, n: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """Linear buckling load factors ``lam`` with ``(K + lam K_sigma) phi = 0``.

    Parameters
    ----------
    struct : assembled structure.
    K_sigma : full-numbering geometric stiffness of the reference load.
    n : number of factors.

    Returns
    -------
    lam : (m,) positive load factors, ascending (the reference load times ``lam`` buckles).
    phi : (n_dof, m) buckling shapes (full numbering).
    """
    Kg = struct.reduce(sp.csr_matrix(K_sigma))
    Kr = struct.Kr
    if struct.nq < 400:
        from scipy.linalg import eigh

        mu, Q = eigh(-Kg.toarray(), Kr.toarray())
    else:
        mu, Q = spla.eigsh(-Kg, k=min(max(2 * n, n + 4), struct.nq - 2), M=Kr.tocsc(), which="LA")
    pos = mu > 1e-12 * max(np.abs(mu).max(), 1e-300)
    lam = 1.0 / mu[pos]
    Q = Q[:, pos]
    order = np.argsort(lam)[:n]
    return lam[order], struct.expand(Q[:, order])


def membrane_geometric_stiffness(fe: FEModel, resultants: np.ndarray) -> sp.csr_matrix:
    """Geometric stiffness (full numbering, CSR, symmetric) of given shell membrane resultants
    ``(Nxx, Nyy, Nxy)`` (ne, 3) (N/m, each element's material frame) on the geometry of ``fe``:
    a stress field carried with its elements to another configuration of the same mesh."""
    r, c, v = shell_membrane_kg(fe, None, resultants=resultants)
    n = fe.n_dof
    A = sp.coo_matrix((v, (r, c)), shape=(n, n)).tocsr()
    return ((A + A.T) * 0.5).tocsr()


def shell_initial_stress(fe: FEModel, forces: np.ndarray, resultants: np.ndarray) -> sp.csr_matrix:
    """The shells' complete initial-stress matrix (full numbering, CSR, symmetric) of given element
    nodal forces and moments ``forces`` (ne, 4, 6) (N, N m, global axes) and membrane resultants
    ``resultants`` (ne, 3) (N/m, material frame) on the geometry of ``fe``
    (:func:`windflutter.structure.shell_stress.shell_complete_kg`): a stress state carried with its
    elements to another configuration of the same mesh."""
    r, c, v = shell_complete_kg(fe, forces, resultants)
    n = fe.n_dof
    A = sp.coo_matrix((v, (r, c)), shape=(n, n)).tocsr()
    return ((A + A.T) * 0.5).tocsr()
