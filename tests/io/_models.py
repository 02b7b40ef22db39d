"""Small FE models shared by the I/O tests (built here, independent of the writers)."""

from __future__ import annotations

import numpy as np

from windflutter.structure.fem import (
    BeamSection,
    FEModel,
    IsotropicMaterial,
    LumpedMass,
    OrthotropicMaterial,
    Ply,
    RigidLink,
    ShellProperty,
    Spring,
)

GFRP = OrthotropicMaterial(E1=41.6e9, E2=14.9e9, nu12=0.24, G12=5.05e9, G13=5.05e9, G23=4.0e9, rho=1915.5,
                           name="glass UD")
ALU = IsotropicMaterial(E=70e9, nu=0.33, rho=2700.0, name="aluminium")
FOAM = IsotropicMaterial(E=0.256e9, nu=0.3, rho=200.0, name="foam")


def consistent_section(name: str = "consistent") -> BeamSection:
    """Section whose mass matrix is a line mass at a CG offset plus torsional inertia about it
    (exactly what PBEAM's NSM, M1, M2, NSI describe), built from first principles here;
    stiffness with an I12-type EIyz coupling (also PBEAM-able)."""
    K = np.diag([2e8, 4e7, 3e7, 1e5, 3e5, 5e5])
    K[4, 5] = K[5, 4] = 2e4
    m, i_cg = 12.0, 0.4
    c = np.array([0.0, 0.02, -0.01])
    Sc = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
    M = np.zeros((6, 6))
    M[:3, :3] = m * np.eye(3)
    M[3:, :3] = m * Sc
    M[:3, 3:] = (m * Sc).T
    M[3:, 3:] = m * (c @ c * np.eye(3) - np.outer(c, c))  # parallel-axis terms of the line mass
    M[3, 3] += i_cg
    return BeamSection(stiffness=K, mass=M, name=name)


def mixed_model(coupled_section: bool = False, flat: bool = False) -> FEModel:
    """A 2 x 3 quad strip (two laminates, twisted material axes) + a 3-element beam + masses.

    The plate lies in a slightly warped surface in z = 0.02 x y (so nothing is axis-aligned), the
    beam continues from the plate's tip edge through a RBE2 and carries a CONM2 with offset and
    full inertia; the root edge is clamped with SPC1 and one node is on a grounded spring.
    """
    nx, ny = 3, 2
    xs = np.linspace(0.0, 1.5, nx + 1)
    ys = np.linspace(0.0, 0.6, ny + 1)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    pts = np.column_stack([X.ravel(), Y.ravel(), (0.0 if flat else 0.02) * X.ravel() * Y.ravel()])
    nid = lambda i, j: i * (ny + 1) + j  # noqa: E731
    conn = np.array([[nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)]
                     for i in range(nx) for j in range(ny)], dtype=np.int64)
    n_plate = len(pts)
    beam_pts = np.array([[1.5 + 0.4 * k, 0.3, 0.0] for k in range(4)])
    nodes = np.vstack([pts, beam_pts])
    b0 = n_plate
    beam_conn = np.array([[b0, b0 + 1], [b0 + 1, b0 + 2], [b0 + 2, b0 + 3]], dtype=np.int64)

    lam_a = ShellProperty(plies=(Ply(GFRP, 1.0e-3, np.radians(45.0)), Ply(FOAM, 5.0e-3, 0.0),
                                 Ply(GFRP, 1.0e-3, np.radians(-45.0))), name="skin", offset=0.0)
    lam_b = ShellProperty(plies=(Ply(GFRP, 2.0e-3, 0.0), Ply(GFRP, 2.0e-3, np.radians(30.0))), name="spar cap",
                          offset=1.5e-3)
    iso = ShellProperty(plies=(Ply(ALU, 2.0e-3, 0.0),), name="alu plate")
    shell_prop = np.array([0, 1, 2, 0, 1, 0], dtype=np.int64)
    ang = np.radians(np.array([0.0, 10.0, 20.0, 30.0, 0.0, 10.0]))
    matdir = np.column_stack([np.cos(ang), np.sin(ang), np.zeros(6)])

    sec1 = consistent_section("tip beam")
    if coupled_section:
        K = sec1.stiffness.copy()
        K[3, 4] = K[4, 3] = 0.3 * np.sqrt(K[3, 3] * K[4, 4])  # bend-twist coupling (not PBEAM-able)
        M = sec1.mass.copy()
        M[4, 4] += 0.05
        M[5, 5] += 0.07
        sec1 = BeamSection(stiffness=K, mass=M, name="coupled")
    sec2 = BeamSection.from_properties(EA=1e8, EIy=1e5, EIz=2e5, GJ=5e4, mass_per_length=8.0, name="rigid-shear")
    J = np.array([[2.0, 0.1, -0.2], [0.1, 3.0, 0.3], [-0.2, 0.3, 4.0]])
    masses = [LumpedMass(node=b0 + 3, mass=25.0, inertia=J, offset=np.array([0.1, -0.05, 0.2]), name="tip mass"),
              LumpedMass(node=nid(nx, 0), mass=1.5, name="sensor")]
    tip_edge = np.array([nid(nx, j) for j in range(ny + 1) if nid(nx, j) != nid(nx, 1)], dtype=np.int64)
    rigid = [RigidLink(independent=nid(nx, 1), dependent=np.concatenate([tip_edge, [b0]]), name="tip tie"),
             RigidLink(independent=b0 + 2, dependent=np.array([b0 + 3]), dofs=(0, 1, 2), name="pin")]
    springs = [Spring(node_a=nid(1, 0), stiffness=np.diag([0.0, 0.0, 2.0e4, 0.0, 0.0, 0.0]), name="support"),
               Spring(node_a=nid(2, 2), node_b=b0 + 1, stiffness=np.diag([1e5, 0.0, 3e4, 0.0, 50.0, 0.0]),
                      name="strut")]
    spc = {nid(0, j): (0, 1, 2, 3, 4, 5) for j in range(ny + 1)}
    spc[nid(1, 2)] = (2,)
    fe = FEModel(
        nodes=nodes, shell_conn=conn, shell_prop=shell_prop, shell_matdir=matdir,
        shell_properties=[lam_a, lam_b, iso], beam_conn=beam_conn, beam_section=np.array([0, 1, 0]),
        beam_orient=np.array([[0.0, 1.0, 0.2], [0.0, 1.0, 0.2], [0.0, 0.8, 0.6]]),
        beam_sections=[sec1, sec2], masses=masses, rigid_links=rigid, springs=springs, spc=spc,
        node_groups={"plate": np.arange(n_plate), "beam": np.arange(b0, b0 + 4)},
        element_regions={"shell": np.array([0, 0, 1, 1, 0, 0]), "beam": np.array([2, 2, 2])},
        region_names=["skin", "cap", "tip beam"],
    )
    fe.check()
    return fe
