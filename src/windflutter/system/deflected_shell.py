"""The shell blade linearized about its deflected steady state (``OperationalOptions(structure="deflected")``).

The beam blade is re-equilibrated on the co-rotational beam and linearized about it
(:mod:`windflutter.system.deflected`).  A shell blade has no co-rotational form here; it is
linearized about the deflected shape in three steps (docs/steady_state.md, "Shell blades"):

1. **The deflected shape** is the shell's own steady state (:func:`windflutter.steady.steady_state`:
   the linear shell under centrifugal and BEM strip loads, its strip motions composed into
   moderate rotations along the span, the deformed-configuration moments of the aerodynamic
   loads).  Its strip chain gives a rigid frame -- a point and a finite rotation -- at every
   station between strips (:func:`station_frames`).  Each shell node is carried rigidly with the
   frame of its span position, interpolated between the two stations on either side of it
   (:func:`carried_nodes`): ``x' = P'(s) + R(s) (x - P(s))``.  The material directions, the
   diaphragms' normals and any lumped mass turn with their nodes.  The section's own in-plane
   deformation (a few mm) is left out of the geometry; the span's bending, shortening and
   elastic twist are in it.
2. **The deformed structure**: each shell element's stiffness and consistent mass carried rigidly
   with the element -- the undeformed element's blocks turned by its rotation (the mean of its
   nodes' rotations, the one that carries its stress in step 3), ``K_e' = Q_e K_e Q_e^T``: the
   material part of a co-rotational element, whose strains enter through its stress alone, as for
   the co-rotational beam (:mod:`windflutter.structure.corotational`: ``K_loc`` in the turned
   frame) -- and assembled on the carried nodes with the ribs, lumped masses and links there; the
   mass is that of the undeformed blade exactly.  Mass, Coriolis and spin softening of the
   deformed blade; the files' damping, the undeformed blade's modal damping turned with the nodes;
   the strips' motion map with its lever arms turned by the nodal rotations.  (Until 6 Dec 2026
   the elements were computed again by pyfe3d on the carried nodes, ``reassemble=True``: that
   differs at the order of the strains -- the carried elements are stretched and sheared by up to
   3e-3 on the NREL 5 MW at 19 RPM, their mass grows with their area -- and costs a pyfe3d pass per
   point; docs/steady_state.md, "Shell blades".)
3. **The steady stress** is the shell's own, that of its steady state: each element's nodal forces
   and moments ``K_e u_e`` and its membrane resultants ``(Nxx, Nyy, Nxy)``, carried with the
   element to the deformed geometry, give the complete initial-stress matrix there
   (:func:`steady_stress_stiffness`: the flat facets' co-rotational matrix,
   :mod:`windflutter.structure.shell_stress`, and the ribs' term of their constraint forces); the root reaction,
   turned with its nodes, the hub links' tensioned-bar term.
4. **The stress balanced on the bent geometry** (:func:`balanced_stress`): forces carried with
   their elements no longer balance loads whose directions did not turn with them -- the
   centrifugal force on the bent blade, a dead load; in a bent cantilever their component along
   the turned span is an axial force the linear stress does not have, and it is what raises the
   bent tube's lateral-torsional buckling load (docs/scripts/bent_tube_routes.py: the beam's exact
   Hessian 1.21 x its classical load, 0.99 x without that axial force).  One linear correction on
   the deformed geometry, ``K_d du = load_d - sum_e f_e`` with the loads at the deformed
   configuration (the centrifugal force at the moved nodes, the strips' loads through the turned
   lever arms), adds ``K_e du_e`` to each element; the blade being statically determinate, its
   section resultants are then those of equilibrium on the bent geometry.  (A linear solution of
   the deformed blade under its whole loads, tried earlier, was rejected: it deflects the blade a
   second time and crushed the thin tip panels of the IEA 22 MW -- docs/steady_state.md; the
   correction here carries only the residual.)

``K_d + K_sigma - Omega^2 K_r`` then plays the role that the co-rotational beam's Hessian plays
for beam blades.  The aerodynamic operator acts on the deflected strips, as for beams.

Units: SI (m, rad, N).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.steady.exact import deformed_motion_map
from windflutter.steady.geometry import (Deflection, blade_strips, deflection, rotation_matrices, rotation_vectors,
                                         strip_motion)
from windflutter.structure.assembly import assemble
from windflutter.structure.prestress import (diaphragm_geometric_stiffness, membrane_geometric_stiffness,
                                             shell_initial_stress, static_solve)
from windflutter.structure.shell import shell_membrane_resultants, turned_blocks
from windflutter.structure.shell_stress import rotate_element_forces, shell_element_forces
from windflutter.system.blade import RotorBlade, link_geometric_stiffness
from windflutter.system.damping import ModalDamping, shell_modal_damping

__all__ = ["DeflectedShell", "station_frames", "carried_nodes", "deflected_shell_blade", "steady_stress_stiffness",
           "carried_stress", "balanced_stress"]


@dataclass
class DeflectedShell:
    """The shell blade substructure linearized about its deflected shape.

    Attributes
    ----------
    blade : :class:`~windflutter.system.blade.RotorBlade` on the deformed geometry.
    steady : the steady state with the deformed blade's strip motion map and ``Ksigma = ksigma``
        (None without one).
    ksigma : (n_dof, n_dof) CSR initial-stress matrix of the steady stress (complete).
    klink : (3, 3) hub-link geometric stiffness of the root reaction (N m/rad).
    nodes : (n, 3) deformed node positions (m); ``rotations`` (n, 3, 3) the nodes' finite rotations.
    """

    blade: RotorBlade
    steady: object
    ksigma: sp.csr_matrix
    klink: np.ndarray
    nodes: np.ndarray
    rotations: np.ndarray


def station_frames(sections, defl: Deflection):
    """Rigid frames at the ``ns + 1`` stations of a one-blade strip chain (root edge, the edges
    between strips, tip edge): ``(P0 (ns+1, 3) undeformed points, P (ns+1, 3) deflected points,
    R (ns+1, 3, 3) rotations, t (ns+1, 3) undeformed span directions)``, root to tip."""
    chains = blade_strips(sections)
    if len(chains) != 1:
        raise InputError("sections.blade", len(chains), "the strips of one blade (part rotor_blade)")
    idx = chains[0]
    p = np.asarray(sections.origin, float)[idx]
    t = np.asarray(sections.e_span, float)[idx]
    t = t / np.linalg.norm(t, axis=1, keepdims=True)
    w = np.asarray(sections.width, float)[idx]
    R, R_cut = defl.R[idx], defl.R_cut[idx]
    tip0 = p[-1] + 0.5 * w[-1] * t[-1]
    P0 = np.vstack([defl.cut0[idx], tip0])
    P = np.vstack([defl.cut[idx], defl.origin[idx][-1] + R[-1] @ (tip0 - p[-1])])
    # the tip edge turns on from the last strip as much as the last strip from its inner edge
    Rs = np.concatenate([R_cut, (R[-1] @ R_cut[-1].T @ R[-1])[None]])
    ts = np.vstack([t[:1], 0.5 * (t[1:] + t[:-1]), t[-1:]])
    ts /= np.linalg.norm(ts, axis=1, keepdims=True)
    return P0, P, Rs, ts


def carried_nodes(X: np.ndarray, frames, fixed: np.ndarray | None = None):
    """Nodes ``X`` (n, 3) carried rigidly by the station frames (:func:`station_frames`): each node
    between stations ``k`` and ``k + 1`` (signed distances to their planes ``d_k >= 0 > d_(k+1)``)
    follows the frame interpolated at ``s = d_k / (d_k - d_(k+1))`` (points linearly, rotations
    along the geodesic ``R_k exp(s log(R_k^T R_(k+1)))``); nodes inboard of the root or outboard
    of the tip the end frames.  ``fixed`` node indices (clamped) stay.  Returns ``(x' (n, 3), R
    (n, 3, 3))``."""
    P0, P, Rs, ts = frames
    X = np.asarray(X, float)
    D = np.einsum("nsi,si->ns", X[:, None, :] - P0[None], ts)  # (n, n_st) signed distances
    scale = 1e-9 * max(float(np.linalg.norm(P0[-1] - P0[0])), 1.0)
    k = np.clip(np.sum(D >= -scale, axis=1) - 1, 0, len(P0) - 2)
    rows = np.arange(len(X))
    da, db = D[rows, k], D[rows, k + 1]
    s = np.clip(np.where(np.abs(da - db) > 0, da / np.where(np.abs(da - db) > 0, da - db, 1.0), 0.0), 0.0, 1.0)
    Ra, Rb = Rs[k], Rs[k + 1]
    rel = rotation_vectors(np.einsum("nji,njk->nik", Ra, Rb))
    Rn = Ra @ rotation_matrices(s[:, None] * rel)
    p0 = (1 - s)[:, None] * P0[k] + s[:, None] * P0[k + 1]
    p1 = (1 - s)[:, None] * P[k] + s[:, None] * P[k + 1]
    x = p1 + np.einsum("nab,nb->na", Rn, X - p0)
    if fixed is not None and len(fixed):
        x[fixed], Rn[fixed] = X[fixed], np.eye(3)
    return x, Rn


def _turned(f: np.ndarray, Rn: np.ndarray) -> np.ndarray:
    """Nodal vectors (n_dof,) turned with their nodes' rotations."""
    f = np.asarray(f, float).reshape(-1, 2, 3)
    return np.einsum("nab,nkb->nka", Rn, f).reshape(-1)


def _element_rotations(fe, Rn: np.ndarray) -> np.ndarray:
    """(ne, 3, 3) each shell element's carried rotation: the mean of its nodes' rotation vectors."""
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    return rotation_matrices(np.mean(rotation_vectors(Rn.reshape(-1, 3, 3))[conn], axis=1)) if len(conn) else Rn[:0]


def _deformed_fe(fe, x: np.ndarray, Rn: np.ndarray):
    """``fe`` on the carried nodes: material directions, diaphragm normals and lumped masses turned."""
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    Re = _element_rotations(fe, Rn)
    matdir = np.einsum("eab,eb->ea", Re, np.asarray(fe.shell_matdir, float)) if len(conn) else fe.shell_matdir
    dia = [dataclasses.replace(d, normal=Rn[int(d.independent)] @ np.asarray(d.normal, float)) for d in fe.diaphragms]
    masses = [dataclasses.replace(m, inertia=Rn[m.node] @ np.asarray(m.inertia, float) @ Rn[m.node].T,
                                  offset=Rn[m.node] @ np.asarray(m.offset, float)) for m in fe.masses]
    return dataclasses.replace(fe, nodes=x, shell_matdir=matdir, diaphragms=dia, masses=masses)


def _carried_damping(rb: RotorBlade, mu, Rn: np.ndarray):
    """The blade's structural damping carried with its nodes to the deflected shape: the undeformed
    blade's modal damping (:func:`windflutter.system.damping.shell_modal_damping`, built for ``rb``
    if it has none of that form) turned by the nodal rotations ``Rn``; None without ``mu``."""
    if mu is None:
        return None
    D = rb.damping if isinstance(rb.damping, ModalDamping) else shell_modal_damping(rb.fe, rb.struct, rb.sections, mu)
    return D.rotated(Rn)


def carried_stress(fe, u: np.ndarray, Rn: np.ndarray):
    """The steady stress of the undeformed shell blade ``fe`` under its steady displacement ``u``,
    carried with the elements to the deformed geometry (nodal rotations ``Rn``): ``(forces (ne, 4, 6)
    each element's nodal forces and moments K_e u_e turned by the element's rotation, N (ne, 3) its
    membrane resultants in its own -- turned -- frame)``."""
    forces = rotate_element_forces(shell_element_forces(fe, u), _element_rotations(fe, Rn))
    return forces, shell_membrane_resultants(fe, u)


def _nodal(fe, forces: np.ndarray) -> np.ndarray:
    """The shell elements' nodal forces ``forces`` (ne, 4, 6) summed at the nodes (n_dof,)."""
    F = np.zeros((fe.n_nodes, 6))
    np.add.at(F, np.asarray(fe.shell_conn, dtype=np.int64), forces)
    return F.reshape(-1)


def balanced_stress(fe, fe_d, st_d, Rn: np.ndarray, forces: np.ndarray, N: np.ndarray, load: np.ndarray):
    """The carried stress ``(forces, N)`` brought into equilibrium with the loads ``load`` (n_dof,) on
    the deformed geometry ``fe_d`` (assembled ``st_d``): the carried element forces, turned with
    their elements, no longer balance loads whose directions did not turn with them (a dead load, the
    centrifugal force on the bent blade: in a bent cantilever its component along the turned span
    is an axial force the linear stress does not have); the linear correction ``K_d du = r`` of the
    residual ``r = load - sum_e f_e`` on the deformed geometry adds ``K_e du_e`` to every element
    (for a statically determinate blade its section resultants are then those of equilibrium).
    ``K_e du_e`` is that of the undeformed element ``fe`` turned by its carried rotation (from the
    nodal rotations ``Rn``; the element's shape is carried rigidly, and its stiffness, kept by
    :func:`~windflutter.structure.shell_stress.shell_element_forces`, is not computed again).
    Returns ``(forces, N, constraint forces sum_e f_e - load (n_dof,))``.  Shell elements only: a
    model with beams or springs gets its carried stress back unchanged (constraint forces None)."""
    if len(fe_d.beam_conn) or fe_d.springs:
        return forces, N, None
    du = static_solve(st_d, load - _nodal(fe_d, forces))
    forces = forces + shell_element_forces(fe, du, turned=_element_rotations(fe, Rn))
    N = N + shell_membrane_resultants(fe_d, du)
    return forces, N, _nodal(fe_d, forces) - load


def steady_stress_stiffness(fe, fe_d, u: np.ndarray, Rn: np.ndarray, constraint_forces: np.ndarray | None = None,
                            complete: bool = True, stress=None) -> sp.csr_matrix:
    """The initial-stress matrix (n_dof, n_dof) CSR of the steady displacement ``u`` of the undeformed
    shell blade ``fe``, its stress carried with the elements to the deformed model ``fe_d`` (nodal
    rotations ``Rn``, :func:`carried_stress`) or ``stress`` ``(forces, N)`` given (e.g. the
    :func:`balanced_stress`); the complete matrix
    (:func:`windflutter.structure.prestress.shell_initial_stress`) with the ribs' term of the
    ``constraint_forces``, or (``complete=False``) the membrane initial stress alone, for comparison."""
    forces, N = stress if stress is not None else carried_stress(fe, u, Rn)
    if not complete:
        return membrane_geometric_stiffness(fe_d, N)
    K = shell_initial_stress(fe_d, forces, N)
    if constraint_forces is not None and fe_d.diaphragms:
        K = (K + diaphragm_geometric_stiffness(fe_d, constraint_forces)).tocsr()
    return K


def deflected_shell_blade(rb: RotorBlade, steady, omega: float, mu: np.ndarray | None = None,
                          balance: bool = True, reassemble: bool = False) -> DeflectedShell:
    """The shell blade ``rb`` linearized about its deflected steady state (module docstring).

    Parameters
    ----------
    rb : the undeformed shell blade substructure (at its pitch).
    steady : its :class:`~windflutter.steady.SteadyState` (deflected), or None for the centrifugal
        state alone (the linear centrifugal displacement carries the mesh).
    omega : rotor speed (rad/s) about ``rb.axis``.
    mu : the blade's damping coefficients (None: no damping).
    balance : the carried stress brought into equilibrium with the loads on the deformed geometry
        (:func:`balanced_stress`, the default); False: the carried linear stress alone (the route
        before 5 Dec 2026, for comparison).
    reassemble : the deformed blade's elements computed again by pyfe3d on the carried nodes (the
        route before 6 Dec 2026, for comparison); the default carries each undeformed element's
        stiffness and mass rigidly with its element (:func:`~windflutter.structure.shell.
        turned_blocks`, the co-rotational element's material part).
    """

    fe = rb.fe
    if not len(fe.shell_conn):
        raise InputError("model", "beam", "a shell blade (beam blades: windflutter.system.deflected)")
    omega = float(omega)
    if steady is not None:
        u, sections = np.asarray(steady.u, float), steady.sections
    else:
        u, sections = rb.unit_prestress()[2] * omega**2, rb.sections
    defl = deflection(rb.sections, strip_motion(rb.sections, u), finite=True)
    fixed = np.array(sorted(n for n, c in fe.spc.items() if len(c) == 6), dtype=np.int64)
    x, Rn = carried_nodes(fe.nodes, station_frames(rb.sections, defl), fixed)
    fe_d = _deformed_fe(fe, x, Rn)
    if reassemble:
        st_d = assemble(fe_d, check=False)
    else:
        Re = _element_rotations(fe, Rn)
        st_d = assemble(fe_d, check=False, shell_blocks=[turned_blocks(B, Re) for B in rb.shell_blocks()])
    blade = RotorBlade(fe_d, st_d, sections, rb.apex, rb.axis, damping=_carried_damping(rb, mu, Rn))
    mm = deformed_motion_map(rb.sections.motion_map, Rn)
    # the steady stress: the membrane resultants of the shell's own steady state, carried with their
    # elements; the root reaction turned with its nodes for the hub links
    reaction = steady.f_internal - steady.load if steady is not None else rb.struct.K @ u - rb.centrifugal_load(omega)
    reaction = _turned(reaction, Rn)
    stress = carried_stress(fe, u, Rn)
    if balance:  # the loads on the deformed geometry: the strips' through the turned lever arms
        load = blade.centrifugal_load(omega)
        if steady is not None:
            load = load + mm.T @ np.asarray(steady.strip_loads, float).reshape(-1)
        forces, N, cf = balanced_stress(fe, fe_d, st_d, Rn, *stress, load)
        if cf is not None:
            stress, reaction = (forces, N), cf
    ksigma = steady_stress_stiffness(fe, fe_d, u, Rn, reaction, stress=stress)
    klink = link_geometric_stiffness(fe_d, reaction, blade.hub_node)
    blade.sections = dataclasses.replace(sections, motion_map=mm)
    st_out = dataclasses.replace(steady, sections=blade.sections, Ksigma=ksigma) if steady is not None else None
    return DeflectedShell(blade=blade, steady=st_out, ksigma=ksigma, klink=klink, nodes=x, rotations=Rn)
