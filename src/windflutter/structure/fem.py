"""The finite-element model container: plain data, no assembly.

This is the contract between ``mesh/`` (which builds an :class:`FEModel` from a turbine),
``structure/`` (which assembles it into sparse matrices), the BDF/VTK exporters and the
aeroelastic solver.  Everything is SI (m, kg, N, rad).

Conventions
-----------
* 6 DOF per node, global ordering ``6*node + c`` with ``c = 0..5`` for
  ``ux, uy, uz, rx, ry, rz``.
* Element connectivity arrays hold 0-based node indices.
* Shell elements are 4-node quads, nodes counter-clockwise seen from the outward normal.
  The laminate's ply angles are measured from the element's *material axis* (a global vector,
  projected onto the element plane), positive about the element normal.
* Beam elements are 2-node; the section frame has x along the beam (node 0 -> node 1),
  y along ``orientation`` projected normal to x, z = x cross y.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from windflutter.errors import InputError

DOF_PER_NODE = 6
DOF_NAMES = ("ux", "uy", "uz", "rx", "ry", "rz")


@dataclass(frozen=True)
class IsotropicMaterial:
    """Isotropic linear-elastic material.

    Parameters
    ----------
    E : Young's modulus (Pa).
    nu : Poisson's ratio (-).
    rho : density (kg/m^3).
    """

    E: float
    nu: float
    rho: float
    name: str = ""

    @property
    def G(self) -> float:
        """Shear modulus (Pa)."""
        return self.E / (2.0 * (1.0 + self.nu))


@dataclass(frozen=True)
class OrthotropicMaterial:
    """Orthotropic ply material in its principal axes (1 = fibre).

    Parameters
    ----------
    E1, E2 : Young's moduli along and across the fibre (Pa).
    nu12 : major Poisson's ratio (-).
    G12, G13, G23 : shear moduli (Pa).
    rho : density (kg/m^3).
    """

    E1: float
    E2: float
    nu12: float
    G12: float
    G13: float
    G23: float
    rho: float
    name: str = ""


Material = IsotropicMaterial | OrthotropicMaterial


@dataclass(frozen=True)
class Ply:
    """One ply of a laminate: material, thickness (m), angle (rad) from the material axis."""

    material: Material
    thickness: float
    angle: float = 0.0


@dataclass(frozen=True)
class ShellProperty:
    """Laminate (bottom to top) of a shell property region.

    An isotropic shell is a single ply of an :class:`IsotropicMaterial`.
    ``offset`` is the reference-surface offset along the element normal (m); 0 = mid-plane.
    """

    plies: tuple[Ply, ...]
    name: str = ""
    offset: float = 0.0

    @property
    def thickness(self) -> float:
        return float(sum(p.thickness for p in self.plies))

    @property
    def mass_per_area(self) -> float:
        """Areal mass (kg/m^2)."""
        return float(sum(p.thickness * p.material.rho for p in self.plies))


@dataclass(frozen=True)
class BeamSection:
    """Cross-section of a 3D Timoshenko beam, referred to the beam's reference axis.

    Parameters
    ----------
    stiffness : (6, 6) array
        Section stiffness relating generalized forces (N, Vy, Vz, T, My, Mz) to strains
        (axial strain, shear strains gamma_xy, gamma_xz, twist rate, curvatures kappa_y,
        kappa_z) in the section frame (x along the beam).  Offsets of tension and shear
        centres appear as off-diagonal terms.  Units N, N·m, N·m².
    mass : (6, 6) array
        Section mass matrix per unit length relating (translational, rotational) velocities
        to momentum: ``[[m I, m S(c)^T], [m S(c), J]]`` with mass centre offset ``c`` in
        the section plane and mass-moment tensor ``J`` (kg/m, kg·m/m, kg·m²/m).
    """

    stiffness: np.ndarray
    mass: np.ndarray
    name: str = ""

    @staticmethod
    def from_properties(
        EA: float,
        EIy: float,
        EIz: float,
        GJ: float,
        mass_per_length: float,
        GAy: float | None = None,
        GAz: float | None = None,
        Ixx_mass: float | None = None,
        Iyy_mass: float = 0.0,
        Izz_mass: float = 0.0,
        cg: tuple[float, float] = (0.0, 0.0),
        name: str = "",
    ) -> "BeamSection":
        """Uncoupled section from classic properties; shear-rigid if GA not given.

        ``Ixx_mass``, ``Iyy_mass``, ``Izz_mass`` are mass moments of inertia per length about the
        reference axis (kg·m²/m), not about the mass centre; ``Ixx_mass`` defaults to
        ``Iyy_mass + Izz_mass``.  A set that makes the section mass indefinite is rejected.  ``cg`` is the mass-centre offset
        (y, z) in the section frame (m).
        """
        big = 1e3 * max(EA, 1.0)
        Ks = np.diag([EA, GAy or big, GAz or big, GJ, EIy, EIz]).astype(float)
        m = float(mass_per_length)
        cy, cz = cg
        J = np.diag([Ixx_mass if Ixx_mass is not None else Iyy_mass + Izz_mass, Iyy_mass, Izz_mass])
        S = np.array([[0.0, -cz, cy], [cz, 0.0, 0.0], [-cy, 0.0, 0.0]])
        Ms = np.zeros((6, 6))
        Ms[:3, :3] = m * np.eye(3)
        Ms[3:, :3] = m * S
        Ms[:3, 3:] = (m * S).T
        Ms[3:, 3:] = J
        ev = np.linalg.eigvalsh(0.5 * (Ms + Ms.T))
        if ev.min() < -1e-10 * max(ev.max(), 1e-300):
            raise InputError(
                "BeamSection.mass",
                f"min eigenvalue {ev.min():.3g}",
                "a positive semi-definite section mass: all mass moments are about the reference "
                "axis, so with a mass-centre offset (cy, cz) need Iyy_mass >= m*cz**2, "
                "Izz_mass >= m*cy**2 and Ixx_mass >= m*(cy**2 + cz**2)",
            )
        return BeamSection(stiffness=Ks, mass=Ms, name=name)


@dataclass(frozen=True)
class LumpedMass:
    """Concentrated mass at a node (NASTRAN CONM2-like).

    Parameters
    ----------
    node : node index.
    mass : kg.
    inertia : (3, 3) mass moment of inertia about the mass's own centre (kg·m²), global axes.
    offset : (3,) position of the centre of mass relative to the node, global axes (m).
    """

    node: int
    mass: float
    inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))
    offset: np.ndarray = field(default_factory=lambda: np.zeros(3))
    name: str = ""


@dataclass(frozen=True)
class RigidLink:
    """Rigid tie (NASTRAN RBE2-like): the dependent nodes follow the independent node rigidly.

    ``dofs`` lists which of the dependent nodes' components (0..5) are tied; all six by default.
    """

    independent: int
    dependent: np.ndarray
    dofs: tuple[int, ...] = (0, 1, 2, 3, 4, 5)
    name: str = ""


@dataclass(frozen=True)
class Diaphragm:
    """In-plane rigid tie (a rib): the dependent nodes follow the independent node's rigid motion
    *in the plane normal to* ``normal`` -- the two in-plane translations and the rotation about
    ``normal`` -- and keep their out-of-plane translation and rotations free.

    This is the assumption of thin-walled beam theory for a cross-section (its shape is kept in its
    plane, warping is free), imposed on a shell blade's end section as a thin closing rib would.
    """

    independent: int
    dependent: np.ndarray
    normal: np.ndarray
    name: str = ""


@dataclass(frozen=True)
class Spring:
    """Linear spring (6x6 stiffness) between two nodes, or from a node to ground (node_b None)."""

    node_a: int
    stiffness: np.ndarray
    node_b: int | None = None
    name: str = ""


@dataclass
class FEModel:
    """A complete structural model.

    Attributes
    ----------
    nodes : (n, 3) float, node coordinates (m), global frame.
    shell_conn : (ns, 4) int, quad connectivity.
    shell_prop : (ns,) int, index into ``shell_properties``.
    shell_matdir : (ns, 3) float, material axis per element (global vector).
    shell_properties : list of :class:`ShellProperty`.
    beam_conn : (nb, 2) int.
    beam_section : (nb,) int, index into ``beam_sections``.
    beam_orient : (nb, 3) float, section y-axis reference vector per element.
    beam_sections : list of :class:`BeamSection`.
    masses, rigid_links, diaphragms, springs : lists of the corresponding items.
    spc : dict node -> tuple of constrained components (0..5), value 0.
    node_groups : named node sets, e.g. ``"blade1"``, ``"tower"``, ``"rotor"`` (the rotating
        part, used for Coriolis/centrifugal terms).
    element_regions : named region id per element kind for plotting/exports, e.g.
        ``{"shell": (ns,) int}`` with names in ``region_names``.
    shell_shear : the shells' transverse shear, ``"mitc4"`` (assumed covariant strains, default) or
        ``"one-point"`` (pyfe3d's Quad4 as it is: one-point shear, with its hourglass mode);
        :mod:`windflutter.structure.shell_shear`.
    """

    nodes: np.ndarray
    shell_conn: np.ndarray = field(default_factory=lambda: np.zeros((0, 4), dtype=np.int64))
    shell_prop: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    shell_matdir: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    shell_properties: list[ShellProperty] = field(default_factory=list)
    beam_conn: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64))
    beam_section: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    beam_orient: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    beam_sections: list[BeamSection] = field(default_factory=list)
    masses: list[LumpedMass] = field(default_factory=list)
    rigid_links: list[RigidLink] = field(default_factory=list)
    diaphragms: list[Diaphragm] = field(default_factory=list)
    springs: list[Spring] = field(default_factory=list)
    spc: dict[int, tuple[int, ...]] = field(default_factory=dict)
    node_groups: dict[str, np.ndarray] = field(default_factory=dict)
    element_regions: dict[str, np.ndarray] = field(default_factory=dict)
    region_names: list[str] = field(default_factory=list)
    shell_shear: str = "mitc4"

    @property
    def n_nodes(self) -> int:
        return int(self.nodes.shape[0])

    def with_beam_stiffness_scaled(self, r: np.ndarray) -> FEModel:
        """A copy whose beam sections' 6x6 stiffness ``C`` becomes ``diag(r) C diag(r)`` (``r`` (6,),
        BeamSection order), masses, lumped masses and springs removed: the elements' stiffness
        scaled per direction (stiffness-proportional damping with one coefficient per direction)."""
        r = np.asarray(r, float)
        secs = [BeamSection(stiffness=r[:, None] * s.stiffness * r[None, :], mass=s.mass, name=s.name)
                for s in self.beam_sections]
        return replace(self, beam_sections=secs, masses=[], springs=[])

    def shell_part(self, keep: np.ndarray) -> tuple[FEModel, np.ndarray]:
        """``(part, new)``: the shell elements selected by the boolean mask ``keep`` as a model of their
        own (their properties and material directions; nothing else), and ``new`` (n_nodes,) each
        node's index in it (-1: not in it)."""
        keep = np.asarray(keep, bool)
        conn = np.asarray(self.shell_conn)
        used = np.unique(conn[keep])
        new = np.full(self.n_nodes, -1, dtype=np.int64)
        new[used] = np.arange(len(used))
        part = FEModel(nodes=np.asarray(self.nodes, float)[used], shell_conn=new[conn[keep]],
                       shell_prop=np.asarray(self.shell_prop)[keep], shell_matdir=np.asarray(self.shell_matdir)[keep],
                       shell_properties=list(self.shell_properties), shell_shear=self.shell_shear)
        return part, new

    @property
    def n_dof(self) -> int:
        return DOF_PER_NODE * self.n_nodes

    def check(self) -> None:
        """Validate array shapes and index ranges; raise :class:`InputError` on the first problem."""
        nodes = np.asarray(self.nodes, dtype=float)
        if nodes.ndim != 2 or nodes.shape[1] != 3:
            raise InputError("nodes", nodes.shape, "an (n, 3) array of coordinates (m)")
        if not np.all(np.isfinite(nodes)):
            raise InputError("nodes", "non-finite coordinate", "finite coordinates (m)")
        n = nodes.shape[0]
        for name, conn, width in (("shell_conn", self.shell_conn, 4), ("beam_conn", self.beam_conn, 2)):
            conn = np.asarray(conn)
            if conn.size and (conn.ndim != 2 or conn.shape[1] != width):
                raise InputError(name, conn.shape, f"an (ne, {width}) integer array")
            if conn.size and (conn.min() < 0 or conn.max() >= n):
                raise InputError(name, int(conn.max()), f"node indices in 0..{n - 1}")
        if len(self.shell_conn) and (
            len(self.shell_prop) != len(self.shell_conn) or len(self.shell_matdir) != len(self.shell_conn)
        ):
            raise InputError("shell_prop/shell_matdir", len(self.shell_prop), f"{len(self.shell_conn)} entries")
        if len(self.shell_prop) and (self.shell_prop.max() >= len(self.shell_properties) or self.shell_prop.min() < 0):
            raise InputError("shell_prop", int(self.shell_prop.max()), f"indices < {len(self.shell_properties)}")
        if len(self.beam_conn) and (
            len(self.beam_section) != len(self.beam_conn) or len(self.beam_orient) != len(self.beam_conn)
        ):
            raise InputError("beam_section/beam_orient", len(self.beam_section), f"{len(self.beam_conn)} entries")
        if len(self.beam_section) and (self.beam_section.max() >= len(self.beam_sections) or self.beam_section.min() < 0):
            raise InputError("beam_section", int(self.beam_section.max()), f"indices < {len(self.beam_sections)}")
        for i, m in enumerate(self.masses):
            if not 0 <= m.node < n:
                raise InputError(f"masses[{i}].node", m.node, f"a node index in 0..{n - 1}")
            if not (np.isfinite(m.mass) and m.mass >= 0):
                raise InputError(f"masses[{i}].mass", m.mass, "a non-negative mass (kg)")
        for kind, ties in (("rigid_links", self.rigid_links), ("diaphragms", self.diaphragms)):
            for i, r in enumerate(ties):
                dep = np.asarray(r.dependent)
                if not 0 <= r.independent < n or (dep.size and (dep.min() < 0 or dep.max() >= n)):
                    raise InputError(f"{kind}[{i}]", r.name or i, f"node indices in 0..{n - 1}")
        for i, r in enumerate(self.diaphragms):
            nv = np.asarray(r.normal, float)
            if nv.shape != (3,) or not np.all(np.isfinite(nv)) or np.linalg.norm(nv) == 0:
                raise InputError(f"diaphragms[{i}].normal", r.normal, "a non-zero 3-vector")
        for node in self.spc:
            if not 0 <= node < n:
                raise InputError("spc", node, f"a node index in 0..{n - 1}")
