"""The shells' complete initial-stress matrix: the flat facet's co-rotational (EICR) geometric stiffness.

Why.  The membrane initial stress of :func:`windflutter.structure.shell.shell_membrane_kg` puts the
membrane resultants ``(Nxx, Nyy, Nxy)`` on the translations' in-plane gradients.  On a faceted
curved wall a hoop resultant is carried round the kinks between facets by the elements' transverse
shear and bending, which that matrix leaves out: a rigid rotation of the wall then gets the energy
``Nyy theta^2`` per area that the complete tangent cancels (docs/structure.md, "Initial stress of
shells").  For a body in equilibrium under dead loads, the initial-stress energy of a rigid motion
must equal the second-order work of the external loads alone (the "virial" below).

Route: the element-independent co-rotational formulation (Rankin & Nour-Omidi 1988; Felippa &
Haugen 2005, CMAME 194, "A unified formulation of small-strain corotational finite elements"),
linearized about a stressed state on the reference geometry.  Our derivation, per element:

* ``d`` (24,) the element's global DOFs (4 nodes x (u, theta)), ``r_i = X_i - c`` the nodes about the
  centroid, ``S(a) b = a x b``.
* The element's rigid spin fitted to its translations by least squares,
  ``omega = G d``, ``G_i = J^-1 S(r_i)`` on node ``i``'s translations (zero on rotations),
  ``J = sum_i (|r_i|^2 I - r_i r_i^T)``: exact for a rigid rotation (``G (omega x r) = omega``) and
  zero for a translation (``sum r_i = 0``).
* ``Psi`` (24, 3): the rigid motion of a spin, ``-S(r_i)`` on translations, ``I`` on rotations;
  ``P = I - T - Psi G`` with ``T`` the mean translation: the projector onto deformational motion
  (``G Psi = I``, ``G T = 0``, ``T Psi = 0``; ``P v = 0`` for every rigid motion ``v``).
* The internal forces of the co-rotated element, ``f(d) = P(d)^T R(d) f_l(P d)``, with
  ``f_e = (f_i, m_i)`` (the element's linear stiffness on its steady displacement, global frame;
  self-equilibrated: ``sum f_i = 0``, ``sum r_i x f_i + m_i = 0`` for an element whose stiffness
  has no rigid-motion energy).  Its variation about the stressed reference has three geometric parts:

  - the frame's spin turns every nodal force and moment: ``dR f = omega x f = -S(f) omega``, i.e.
    ``K_GR = -F_nm G`` with ``F_nm`` (24, 3) stacking ``S(f_i)`` and ``S(m_i)``;
  - the projector moves with the nodes: ``Psi^T f = sum r_i x f_i + m_i`` varies by
    ``sum dr_i x f_i = F_n^T dd`` (``F_n``: ``S(f_i)`` on translations, zero on rotations; the
    centroid's motion drops out by ``sum f_i = 0``), so ``dP^T f = -G^T F_n^T dd``; taken on the
    deformational motion (Felippa & Haugen: the projector is built on the rotated reference),
    ``K_GP = -G^T F_n^T P``;
  - the co-rotated element's own initial stress on its deformational motion: ``P^T K_G,m P`` with
    ``K_G,m`` the membrane matrix of the element's resultants.

  ``K_sigma,e = P^T K_G,m P + sym(K_GR + K_GP)`` (symmetrized: the non-symmetric remainder is the
  moment of the unbalanced forces, zero at equilibrium).

Properties (verified in tests/structure/test_shell_stress.py and tests/system/test_shell_torsion_prestress.py):

* Rigid translation ``v``: ``K_sigma,e v = 0`` exactly (``G v = 0``, ``P v = 0``, ``F_n^T`` and
  ``F_nm^T`` of a uniform vector are ``S(sum f_i) = 0``).
* Rigid rotation ``v = Psi omega``: ``P v = 0`` and ``G v = omega``, so
  ``v^T K_sigma,e v = -v^T F_nm omega = sum_i (omega x r_i) . (omega x f_i)`` (the moments give
  ``omega . (m x omega) = 0``).  Summed over elements the internal forces cancel at shared nodes
  (their element forces add up to the external loads and reactions), and ``sum f_i = 0`` makes the
  element's centroid irrelevant: ``v^T K_sigma v = sum_k (omega x X_k) . (omega x F_k)`` over the
  external nodal loads ``F_k``, the dead loads' second-order work
  ``-sum F_k . (omega x (omega x X_k))`` -- zero for a twist about the axis of a tube in axial
  tension, ``T L`` for a transverse rotation.
* Rigid rotation against deformational ``w`` (``P w = w``, ``G w = 0``): ``-w^T (F_nm + F_n) omega``,
  on the translations ``2 sum_i w_i . (omega x f_i)``, for membrane nodal forces the continuum's
  cross term ``2 int N_ab (omega x e_a) . w_,b dA``.
* Deformational against deformational: ``P^T K_G,m P`` alone; on a flat plate under in-plane
  stress the membrane matrix's, up to its rigid parts (which the membrane matrix gets right there).

Units: SI (N, m).
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.linalg_tools import skew
from windflutter.structure.fem import FEModel
from windflutter.structure.shell import (check_quads, element_blocks, membrane_element_matrices, shell_frames,
                                         shell_kc0_coo, turned_blocks)

__all__ = ["shell_element_forces", "shell_complete_kg", "rotate_element_forces"]


def shell_element_forces(fe: FEModel, u: np.ndarray, cache: bool = True, turned: np.ndarray | None = None) -> np.ndarray:
    """Each shell element's nodal forces and moments ``K_e u_e`` (ne, 4, 6) (N, N m), global axes:
    the pyfe3d Quad4 stiffness of the element on the displacement ``u`` (n_dof,) (m, rad), node
    order of ``fe.shell_conn``.

    ``turned`` (ne, 3, 3): each element carried rigidly by that rotation to another configuration:
    the forces of the turned element ``Re K_e Re^T`` on ``u`` (``u`` taken back by the element's
    rotation, the forces turned forward), without computing the turned elements' stiffness.

    The element stiffnesses are kept in each element's own frame (:func:`windflutter.structure.shell.
    shell_frames`) for the last two meshes by their shape (``cache``): a rigidly turned copy of a mesh
    (a pitched blade) reuses them (the pyfe3d element loop is 0.5 s on the IEA 22 MW blade).
    """
    u = np.asarray(u, dtype=float)
    if u.shape != (fe.n_dof,) or not np.all(np.isfinite(u)):
        raise InputError("u", u.shape, f"a finite ({fe.n_dof},) displacement vector")
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    if not conn.shape[0]:
        return np.zeros((0, 4, 6))
    Rf, _, X = shell_frames(fe)
    Kloc = _local_stiffness(fe, Rf, X, cache)
    U = u.reshape(-1, 2, 3)[conn]
    if turned is not None:
        U = np.einsum("eba,enkb->enka", turned, U)
    ue = np.einsum("eab,enkb->enka", Rf, U).reshape(-1, 24)
    fl = np.einsum("eij,ej->ei", Kloc, ue).reshape(-1, 4, 2, 3)
    f = np.einsum("eba,enkb->enka", Rf, fl)
    return (f if turned is None else np.einsum("eab,enkb->enka", turned, f)).reshape(-1, 4, 6)


_KLOC: list = []  # [(key, local node coordinates, stiffness)], the last two meshes


def _local_stiffness(fe: FEModel, Rf: np.ndarray, X: np.ndarray, cache: bool) -> np.ndarray:
    """(ne, 24, 24) each element's stiffness in its frame ``Rf`` (rows local x, y, z), kept by the
    elements' shape: connectivity, laminates and the local node coordinates (equal within 1e-9 of
    the largest)."""
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    local = np.einsum("eij,enj->eni", Rf, X - X.mean(axis=1, keepdims=True))
    key = (conn.tobytes(), np.asarray(fe.shell_prop, dtype=np.int64).tobytes(), tuple(fe.shell_properties),
           fe.shell_shear)
    tol = 1e-9 * max(float(np.abs(local).max()), 1e-300)
    for k, loc, K in _KLOC if cache else ():
        if k == key and np.abs(loc - local).max() <= tol:
            return K
    K = turned_blocks(element_blocks(shell_kc0_coo(fe), conn), Rf)  # global axes -> each element's frame
    if cache:
        del _KLOC[:-1]
        _KLOC.append((key, local, K))
    return K


def rotate_element_forces(forces: np.ndarray, Re: np.ndarray) -> np.ndarray:
    """Element nodal forces and moments (ne, 4, 6) turned by each element's rotation ``Re`` (ne, 3, 3)
    (a stress state carried with its elements to another configuration of the same mesh)."""
    F = np.asarray(forces, dtype=float).reshape(-1, 4, 2, 3)
    return np.einsum("eab,enkb->enka", np.asarray(Re, dtype=float), F).reshape(-1, 4, 6)


def _projector(r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(G (ne, 3, 24) the least-squares spin of the translations, P (ne, 24, 24) the projector onto
    deformational motion) of elements with nodes ``r`` (ne, 4, 3) about their centroids."""
    ne = r.shape[0]
    S = skew(r)  # (ne, 4, 3, 3)
    J = np.einsum("eni,eni->e", r, r)[:, None, None] * np.eye(3) - np.einsum("eni,enj->eij", r, r)
    JS = np.linalg.solve(J[:, None], S)  # (ne, 4, 3, 3): J^-1 S(r_i)
    G = np.zeros((ne, 3, 4, 6))
    G[:, :, :, :3] = JS.transpose(0, 2, 1, 3)
    G = G.reshape(ne, 3, 24)
    Psi = np.zeros((ne, 4, 6, 3))
    Psi[:, :, :3, :] = -S
    Psi[:, :, 3:, :] = np.eye(3)
    Psi = Psi.reshape(ne, 24, 3)
    T = np.zeros((4, 6, 4, 6))
    T[:, :3, :, :3] = 0.25 * np.eye(3)[None, :, None, :]
    P = np.eye(24) - T.reshape(24, 24) - Psi @ G
    return G, P


def shell_complete_kg(fe: FEModel, forces: np.ndarray, resultants: np.ndarray):
    """COO triplets (rows, cols, values) of the complete initial-stress matrix of all shells
    (module docstring), on the geometry of ``fe``.

    Parameters
    ----------
    fe : the model (its node positions are the configuration the stress acts on).
    forces : (ne, 4, 6) each element's nodal forces and moments (N, N m), global axes
        (:func:`shell_element_forces`, or carried with the elements: :func:`rotate_element_forces`).
    resultants : (ne, 3) the elements' membrane resultants ``(Nxx, Nyy, Nxy)`` (N/m), material frame
        (:func:`windflutter.structure.shell.shell_membrane_resultants`).
    """
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    ne = conn.shape[0]
    F = np.asarray(forces, dtype=float)
    if F.shape != (ne, 4, 6) or not np.all(np.isfinite(F)):
        raise InputError("forces", F.shape, f"finite ({ne}, 4, 6) element nodal forces and moments (N, N m)")
    check_quads(fe)
    Ge = membrane_element_matrices(fe, resultants)  # (ne, 4, 4)
    X = np.asarray(fe.nodes, dtype=float)[conn]
    G, P = _projector(X - X.mean(axis=1, keepdims=True))
    Kgm = np.zeros((ne, 4, 6, 4, 6))
    for a in range(3):
        Kgm[:, :, a, :, a] = Ge
    Kgm = Kgm.reshape(ne, 24, 24)
    Sf = skew(F[:, :, :3])  # (ne, 4, 3, 3)
    Fnm = np.concatenate([Sf, skew(F[:, :, 3:])], axis=2).reshape(ne, 24, 3)
    Fn = np.concatenate([Sf, np.zeros_like(Sf)], axis=2).reshape(ne, 24, 3)
    Gt = G.transpose(0, 2, 1)
    A = -Fnm @ G - Gt @ (Fn.transpose(0, 2, 1) @ P)
    K = P.transpose(0, 2, 1) @ Kgm @ P + 0.5 * (A + A.transpose(0, 2, 1))
    dofs = (6 * conn[:, :, None] + np.arange(6)).reshape(ne, 24)
    rows = np.repeat(dofs, 24, axis=1)
    cols = np.tile(dofs, (1, 24))
    return rows.ravel(), cols.ravel(), K.reshape(ne, 576).ravel()
