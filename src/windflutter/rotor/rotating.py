"""Rotating-frame terms of the rotor (seed ch. 3.1.2-3.1.4; docs/stability.md,
"Pipeline (modules)").

For the translational DOFs ``u`` of the rotating part with (consistent or lumped) mass matrix
``Mt`` and constant rotor speed vector ``Omega``, the kinetic energy
``T = 1/2 (u' + S (R + u))^T Mt (u' + S (R + u))`` with ``S = I (x) skew(Omega)`` gives

* gyroscopic (Coriolis) matrix ``G = Mt S + S Mt`` (``= 2 m skew(Omega)`` for a point mass),
  acting on velocities;
* spin softening ``Kr = S^T Mt S`` (``= m (|Omega|^2 I - Omega Omega^T)``), subtracted from K;
* centrifugal load ``Fr = Kr R`` (``= -m Omega x (Omega x R)``), R from the hub centre;

so that ``Ms u'' + (Ds + G) u' + (Ks - Kr + Ksigma) u = F``.  ``Ksigma`` is the geometric
(stress) stiffness of the static centrifugal prestress ``Ks u0 = Fr`` (a departure from the
seed, which leaves it out; switch it off with ``prestress=False`` / ``thesis=True``).
All three scale with Omega: G ~ Omega, Kr and Ksigma ~ Omega^2, which :class:`RotorTerms` uses
to build them once per model.
Rotary-inertia gyroscopic terms of the rotational DOFs are neglected (as in the seed).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.aero_types import RotorGeometry
from windflutter.errors import InputError, ModelError
from windflutter.rotor.spin import spin_terms
from windflutter.rotor.translational import coriolis_and_softening, spin_operator
from windflutter.structure.fem import FEModel
from windflutter.structure.prestress import geometric_stiffness, static_solve


def rotating_nodes(fe: FEModel, group: str = "rotor") -> np.ndarray:
    """Node indices of the rotating part (``fe.node_groups[group]``)."""
    if group not in fe.node_groups:
        raise InputError("fe.node_groups", sorted(fe.node_groups), f"a '{group}' node group (the rotating part)")
    return np.unique(np.asarray(fe.node_groups[group], dtype=np.int64))


def translational_dofs(nodes: np.ndarray) -> np.ndarray:
    """Global DOF indices (ux, uy, uz) of ``nodes``, node-major."""
    return (6 * np.asarray(nodes)[:, None] + np.arange(3)[None, :]).ravel()


def relative_to_reference(n_dof: int, dofs: np.ndarray, reference_node: int, n_comp: int = 3) -> sp.csr_matrix:
    """Sparse ``L`` (n_dof x n_dof) giving the rotor's motion relative to a reference node.

    ``(L u)[d] = u[d] - u[ref, c(d)]`` for the DOFs ``d`` of the rotating part, ``n_comp`` per node
    (3: the translations, 6: translations and rotations; component ``c(d)``), zero for every other
    DOF, and zero for the reference node itself.
    """
    dofs = np.asarray(dofs, dtype=np.int64)
    comp = np.tile(np.arange(n_comp), dofs.size // n_comp)
    ref = 6 * int(reference_node) + comp
    keep = dofs != ref
    d, r = dofs[keep], ref[keep]
    rows = np.concatenate([d, d])
    cols = np.concatenate([d, r])
    vals = np.concatenate([np.ones(d.size), -np.ones(d.size)])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n_dof, n_dof))


def centrifugal_load(M: sp.spmatrix, fe: FEModel, nodes: np.ndarray, omega_vec: np.ndarray,
                     center: np.ndarray) -> np.ndarray:
    """Centrifugal nodal forces ``Fr = S^T Mt S R`` (N), full DOF vector, R = x - center."""
    dofs = translational_dofs(nodes)
    Mt = sp.csr_matrix(M)[dofs][:, dofs]
    S = spin_operator(nodes.size, np.asarray(omega_vec, float))
    R = (np.asarray(fe.nodes, float)[nodes] - np.asarray(center, float)).ravel()
    f = np.zeros(M.shape[0])
    f[dofs] = S.T @ (Mt @ (S @ R))
    return f


@dataclass
class RotorTerms:
    """Rotating-frame matrices per unit rotor speed, so that at speed ``omega`` (rad/s)
    ``G = omega G1``, ``Kr = omega^2 Kr1``, ``Ksigma = omega^2 Ks1`` (unconstrained numbering).
    """

    G1: sp.csr_matrix
    Kr1: sp.csr_matrix
    Ksigma1: sp.csr_matrix | None

    def at(self, omega: float):
        """(G, Kr, Ksigma) at rotor speed ``omega`` (rad/s); Ksigma is zero without prestress."""
        Ks = self.Ksigma1 * omega**2 if self.Ksigma1 is not None else sp.csr_matrix(self.Kr1.shape)
        return self.G1 * omega, self.Kr1 * omega**2, Ks


def _prestress(fe: FEModel, struct, Fr: np.ndarray, u0_solver=None, moments: bool = False) -> sp.csr_matrix:
    """Geometric stiffness of the static solution of ``Ks u0 = Fr`` (structural engineer's API);
    ``moments``: of every stress resultant of the beams (not the axial force's alone); shells:
    the complete initial stress with the ribs' term of their constraint forces ``K u0 - Fr``."""
    u0 = static_solve(struct, Fr) if u0_solver is None else u0_solver(struct, Fr)
    Kg = geometric_stiffness(fe, u0, moments=moments, constraint_forces=struct.K @ u0 - Fr)
    return sp.csr_matrix(Kg)


def rotor_terms(fe: FEModel, struct, rotor_geometry: RotorGeometry, prestress: bool = True,
                group: str = "rotor", reference_group: str | None = "hub",
                rigid_sections: bool = False) -> RotorTerms:
    """Build :class:`RotorTerms` once for a model (unit rotor speed).

    ``rigid_sections=False`` (the seed's): Coriolis, spin softening and centrifugal load of the
    translational mass, the axial force's initial stress.  ``True``: beam sections and lumped
    masses as rigid bodies (:func:`windflutter.rotor.spin.spin_terms`: mass-centre offsets and
    rotary inertia) and the initial stress of every stress resultant of the beams
    (``geometric_stiffness(moments=True)``).  Only the second is independent of where a beam's
    reference axis lies in its sections: with the seed's terms, a blade whose 6x6 refer to a line
    away from the mass and tension centres (a HAWC2 c2 line) gets an axial force acting on that
    line, not where it acts (docs/verification.md, "Not verified, or known to disagree", "The seed's
    frozen-azimuth terms depend on the beam reference axis").

    Mixed frames: in a whole-turbine model the tower is in the fixed frame and the rotor is tied
    to it at the hub.  A rigid translation of the whole rotor with the hub changes neither the
    centrifugal nor the Coriolis forces in the fixed frame, so G and Kr act on the rotor's
    translations *relative to the hub node* (``reference_group``, when the model has one);
    applied to absolute translations they would soften the tower top by ``M_rotor Omega^2`` and
    produce a spurious low-frequency instability of the tower modes (seen on the NREL 5 MW:
    "divergence" of the side-side mode at ~26 RPM).  For a rotor with a clamped hub the two are
    the same.
    """
    axis = np.asarray(rotor_geometry.shaft_axis, float)
    if not np.isclose(np.linalg.norm(axis), 1.0, atol=1e-6):
        raise InputError("rotor.shaft_axis", axis.tolist(), "a unit vector")
    nodes = rotating_nodes(fe, group)
    M = struct.M
    dofs = translational_dofs(nodes)
    if rigid_sections:
        G1, Kr1, f1 = spin_terms(fe, M, nodes, axis, np.asarray(rotor_geometry.hub_center, float))
    else:
        G1, Kr1 = coriolis_and_softening(M, dofs, axis)
    ref = fe.node_groups.get(reference_group) if reference_group else None
    if ref is not None and len(ref) == 1:
        # rigid sections: their rotations carry terms too (rotary inertia, offsets), relative to the hub's
        rel = (6 * nodes[:, None] + np.arange(6)[None, :]).ravel() if rigid_sections else dofs
        L = relative_to_reference(M.shape[0], rel, int(np.asarray(ref)[0]), 6 if rigid_sections else 3)
        G1 = L.T @ G1 @ L
        Kr1 = L.T @ Kr1 @ L
    Ks1 = None
    if prestress:
        Fr = f1 if rigid_sections else centrifugal_load(M, fe, nodes, axis, rotor_geometry.hub_center)
        Ks1 = _prestress(fe, struct, Fr, moments=rigid_sections)
    return RotorTerms(G1=G1.tocsr(), Kr1=Kr1.tocsr(), Ksigma1=Ks1)


def rotor_matrices(fe: FEModel, struct, omega: float, rotor_geometry: RotorGeometry, prestress: bool = True,
                   group: str = "rotor"):
    """``(G, Kr, Ksigma)`` at rotor speed ``omega`` (rad/s), sparse (n_dof, n_dof), unconstrained.

    ``struct`` is the assembled :class:`~windflutter.structure.assembly.Structural` (its ``M``
    in the unconstrained numbering).  ``Ksigma`` is zero when ``prestress`` is False (the seed).
    """
    if not np.isfinite(omega):
        raise InputError("omega", omega, "a finite rotor speed (rad/s)")
    try:
        terms = rotor_terms(fe, struct, rotor_geometry, prestress, group)
    except ModelError:
        raise
    return terms.at(omega)
