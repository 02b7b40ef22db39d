"""The blade linearized about its deflected steady state (``OperationalOptions(structure="deflected")``).

The default operating-point model linearizes the blade on its undeformed reference axis: the
strips follow the deflected steady state, but the beam keeps its straight-line frames and only the
axial-force geometric stiffness of the steady stress.  The edge--torsion coupling that a
flapwise-deflected blade has (Kallesoe 2011, *Wind Energy* 14:209; docs/notes/edgewise_damping.md) is then
missing.  HAWCStab2 linearizes its co-rotational beam about the deflected state; so does this
module:

1. **Equilibrium.**  The steady state (:func:`windflutter.steady.steady_state`) is, for beam
   blades, already an equilibrium of the co-rotational beam (:mod:`windflutter.steady.exact`); a
   Newton iteration (:mod:`windflutter.structure.corotational`) from it under its aerodynamic
   nodal loads (held fixed) and the centrifugal loads of the deformed blade
   (:func:`windflutter.steady.exact.centrifugal_loads`: the sections' offsets and rotary inertia
   included; their derivative the spin softening ``Omega^2 K_r``) confirms it in one step; from a
   linear steady state (``SteadyOptions(corotational=False)``) it finds that equilibrium.
2. **The deformed structure.**  The FE model rebuilt on it (:func:`~windflutter.structure.
   corotational.deformed_model`: nodes moved, section axes turned by the nodal rotations -- the
   bending slopes and the elastic twist); its mass matrix, Coriolis and spin softening, structural
   damping (the files' ``mu``) and rigid-body modes; the elastic stiffness ``K_mat`` of the
   deformed geometry; the strips' motion map with its lever arms turned by the nodal rotations.
3. **The initial-stress matrix** ``K_geo`` of the total steady stress resultants (axial force,
   shear, torsion, bending moments) in place of ``SteadyState.Ksigma``, acting (like it) on the
   total rotating-frame motion; the hub link's tensioned-bar term of the root reaction.

``K_mat + K_geo - Omega^2 K_r`` is then the Hessian of the beam's potential at its equilibrium:
the linearized structure of the nonlinear one (tests/structure/test_deflected_beam.py checks it
against a geometrically exact rod).  The aerodynamic loads' own dependence on the motion stays the
strip operator's (:mod:`windflutter.aero.operators`), as for the undeformed blade; the steady
aerodynamic loads are dead nodal loads in the equilibrium (their follower part is left out, as
before).  Beam blades only.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.steady.exact import centrifugal_loads, deformed_motion_map
from windflutter.steady.geometry import rotation_vectors
from windflutter.structure.assembly import Structural, assemble_matrices
from windflutter.structure.constraints import constraint_map
from windflutter.structure.corotational import (Equilibrium, chained_configuration, deformed_model,
                                                 internal_forces, reference_configuration, solve_equilibrium)
from windflutter.system.blade import RotorBlade, link_geometric_stiffness
from windflutter.system.damping import blade_damping_matrix

__all__ = ["DeflectedBlade", "deflected_blade"]

#: Newton tolerance of the equilibrium (largest increment: m over the blade size, rad)
EQUILIBRIUM_TOL = 1e-10


@dataclass
class DeflectedBlade:
    """The blade substructure linearized about its deflected equilibrium.

    Attributes
    ----------
    blade : :class:`~windflutter.system.blade.RotorBlade` on the deformed geometry (its ``struct.K``
        the elastic stiffness of that geometry).
    steady : the steady state with the deformed blade's strip motion map and ``Ksigma = ksigma``
        (None without one).
    ksigma : (n_dof, n_dof) CSR initial-stress matrix of the steady stress (full numbering).
    klink : (3, 3) hub-link geometric stiffness of the root reaction (N m/rad).
    equilibrium : the co-rotational equilibrium (configuration, tangent, loads).
    """

    blade: RotorBlade
    steady: object
    ksigma: sp.csr_matrix
    klink: np.ndarray
    equilibrium: Equilibrium

    reference: np.ndarray = None

    def displacement(self) -> np.ndarray:
        """(n_nodes, 6) node translations (m) from the undeformed blade and rotation vectors (rad)
        of the equilibrium, global axes."""
        c = self.equilibrium.config
        return np.hstack([c.x - self.reference, rotation_vectors(c.R)])


def deflected_blade(rb: RotorBlade, steady, omega: float, mu: np.ndarray | None = None,
                    tol: float = EQUILIBRIUM_TOL) -> DeflectedBlade:
    """The blade ``rb`` linearized about its deflected equilibrium at rotor speed ``omega`` (rad/s).

    Parameters
    ----------
    rb : the undeformed blade substructure (at its pitch).
    steady : its :class:`~windflutter.steady.SteadyState` (deflected; its aerodynamic nodal loads
        and displacement are used), or None for the centrifugal state alone.
    omega : rotor speed (rad/s) about ``rb.axis``.
    mu : the blade's stiffness-proportional damping coefficients (None: no damping).
    tol : Newton tolerance (module constant).
    """
    fe, struct = rb.fe, rb.struct
    if len(fe.shell_conn):
        raise InputError("structure", "deflected", "beam blades here (shell blades: windflutter.system.deflected_shell)")
    omega = float(omega)
    if steady is not None:
        f_aero, u0 = np.asarray(steady.load_aero, float), np.asarray(steady.u, float)
    else:
        f_aero = np.zeros(fe.n_dof)
        u0 = rb.unit_prestress()[2] * omega**2 if omega != 0.0 else np.zeros(fe.n_dof)
    centrifugal = centrifugal_loads(fe, omega, rb.apex, rb.axis)

    def external(config, factor):
        f, K = centrifugal(config)
        return factor * (f + f_aero), (None if K is None else factor * K)

    if steady is not None and getattr(steady, "configuration", None) is not None:
        start = steady.configuration  # the co-rotational steady state: already this equilibrium
    else:
        start = chained_configuration(fe, u0) if np.any(u0) else reference_configuration(fe)
    eq = solve_equilibrium(fe, struct.T, external, start=start, tol=tol)
    return _linearized(rb, steady, eq, mu)


def _linearized(rb: RotorBlade, steady, eq: Equilibrium, mu) -> DeflectedBlade:
    """The deformed blade's substructure and stress terms at the equilibrium ``eq``."""
    fe, struct = rb.fe, rb.struct
    fe_d = deformed_model(fe, eq.config)
    M_d, _ = assemble_matrices(fe_d)
    T_d, free = constraint_map(fe_d, extra_fixed=struct.auto_spc) if struct.auto_spc.size else constraint_map(fe_d)
    st_d = Structural(fe=fe_d, M=M_d, K=eq.tangent.K_mat, T=T_d, free_dofs=free, auto_spc=struct.auto_spc)
    mm = deformed_motion_map(rb.sections.motion_map, eq.config.R)
    if steady is not None:
        sections = dataclasses.replace(steady.sections, motion_map=mm)
    else:
        sections = dataclasses.replace(rb.sections, motion_map=mm)
    blade = RotorBlade(fe_d, st_d, sections, rb.apex, rb.axis, damping=blade_damping_matrix(fe_d, mu))
    klink = link_geometric_stiffness(fe_d, internal_forces(fe, eq.config, eq.tangent) - eq.f_ext, rb.hub_node)
    ksigma = eq.tangent.K_geo
    st_out = dataclasses.replace(steady, sections=sections, Ksigma=ksigma) if steady is not None else None
    return DeflectedBlade(blade=blade, steady=st_out, ksigma=ksigma, klink=klink, equilibrium=eq,
                          reference=np.asarray(fe.nodes, float))
