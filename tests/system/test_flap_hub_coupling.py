"""Elastic blades on a tilting, yawing hub: the multi-blade system against the whole rotor as ONE
finite-element model in the rotating frame.

The Floquet test of test_multiblade.py checks the multi-blade transformation on the solver's own blade
matrices, and the rigid rotor's gyroscopic whirl the hub's rigid-body terms; neither checks how the
ELASTIC blade couples to the hub's tilt and yaw (``w = Gamma h + Phi eta`` in
:mod:`windflutter.system.blade`, the blade seen from the hub ``J_b(psi)`` and the hub-link terms of
:mod:`windflutter.system.multiblade`).  A rotor of three identical blades on a hub whose supports are
isotropic about the shaft (equal tilt and yaw springs, no inertia of their own) is time-invariant in
the rotating frame too, so it can be analysed there as one structure: the hub a node on grounded
springs, the three blades beams from it, the rotating-frame terms (Coriolis, spin softening, the
geometric stiffness of the centrifugal prestress) on the whole model.  That shares the element and
rotating-frame terms with the solver but none of the substructure, hub-kinematics or multi-blade
code.  Its eigenvalues are the multi-blade system's modulo ``i Omega`` (the cyclic modes seen from the
rotating frame), as the Floquet exponents are.
"""

from __future__ import annotations

import numpy as np
import pytest

from windflutter.aero_types import RotorGeometry
from windflutter.rotor.rotating import rotor_terms
from windflutter.structure.assembly import assemble
from windflutter.structure.fem import BeamSection, FEModel, Spring
from windflutter.system.blade import RotorBlade
from windflutter.system.multiblade import BladeSystem, multiblade_system
from windflutter.system.support import Drivetrain, fixed_frame, support_model

AXIS = np.array([1.0, 0.0, 0.0])
LENGTH, N_EL, N_BLADES = 30.0, 10, 3
SECTION = BeamSection.from_properties(EA=5e9, EIy=2e8, EIz=4e6, GJ=1e6, mass_per_length=100.0,
                                      Iyy_mass=1.0, Izz_mass=1.0)  # EIz: flapwise (along the shaft)
STIFF = 1e12


def _blade_nodes(psi: float) -> np.ndarray:
    """Nodes of a straight blade from the apex at azimuth ``psi`` (rotation about the shaft, x)."""
    e_r = np.array([0.0, -np.sin(psi), np.cos(psi)])
    return np.linspace(0.0, LENGTH, N_EL + 1)[1:, None] * e_r


def _hub_spring(k_hub: float) -> np.ndarray:
    return np.diag([STIFF, STIFF, STIFF, STIFF, k_hub, k_hub])


def multiblade_eigenvalues(omega: float, k_hub: float) -> np.ndarray:
    """One blade on a clamped hub node (``RotorBlade``, full order), three of them on the hub's
    springs through the multi-blade system, the rotor locked to the nacelle."""
    nodes = np.vstack([np.zeros((1, 3)), _blade_nodes(0.0)])
    fe = FEModel(nodes=nodes, beam_conn=np.column_stack([np.arange(N_EL), np.arange(1, N_EL + 1)]),
                 beam_section=np.zeros(N_EL, int), beam_orient=np.tile(AXIS, (N_EL, 1)), beam_sections=[SECTION],
                 spc={0: (0, 1, 2, 3, 4, 5)}, node_groups={"hub": np.array([0]), "blade0": np.arange(N_EL + 1)})
    rb = RotorBlade(fe, assemble(fe), None, np.zeros(3), AXIS)
    M, C, K = rb.matrices(None).at(omega)
    hub = FEModel(nodes=np.zeros((1, 3)), springs=[Spring(0, _hub_spring(k_hub))], node_groups={"hub": np.array([0])})
    ff = fixed_frame(support_model(hub, assemble(hub)), np.zeros((6, 6)), AXIS, Drivetrain(mode="locked"))
    return np.linalg.eigvals(multiblade_system(ff, BladeSystem(M, C, K), N_BLADES, omega, AXIS).state_matrix())


def rotating_frame_eigenvalues(omega: float, k_hub: float) -> np.ndarray:
    """The whole rotor as one model in the rotating frame (the module docstring)."""
    nodes = np.vstack([np.zeros((1, 3))] + [_blade_nodes(2 * np.pi * b / N_BLADES) for b in range(N_BLADES)])
    conn = []
    for b in range(N_BLADES):
        ids = [0] + list(1 + b * N_EL + np.arange(N_EL))
        conn += list(zip(ids[:-1], ids[1:]))
    n_el = len(conn)
    fe = FEModel(nodes=nodes, beam_conn=np.array(conn), beam_section=np.zeros(n_el, int),
                 beam_orient=np.tile(AXIS, (n_el, 1)), beam_sections=[SECTION],
                 springs=[Spring(0, _hub_spring(k_hub))], node_groups={"rotor": np.arange(len(nodes))})
    st = assemble(fe)
    terms = rotor_terms(fe, st, RotorGeometry(np.zeros(3), AXIS), prestress=True, group="rotor",
                        reference_group=None, rigid_sections=True)
    G, Kr, Ks = terms.at(omega)
    T = st.T
    Mq = (T.T @ st.M @ T).toarray()
    Cq = (T.T @ G @ T).toarray()
    Kq = (T.T @ (st.K - Kr + Ks) @ T).toarray()
    n = Mq.shape[0]
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:] = -np.linalg.solve(Mq, np.hstack([Kq, Cq]))
    return np.linalg.eigvals(A)


@pytest.mark.parametrize("omega, f_hub", [(1.0, 0.35), (1.5, 0.2)])
def test_elastic_blades_on_a_tilting_hub_as_one_rotating_structure(omega, f_hub):
    """Every eigenvalue of the rotating-frame model below 20 rad/s (hub tilt / yaw, 1st-2nd flap, 1st
    edge, ...) is an eigenvalue of the multi-blade system modulo i Omega, within 1e-6 relative (both
    exact for the same FE discretization: round-off of the eigen-solves and the 1e12 hub springs).
    The hub's tilt frequency near the rotor speed and the 1st flap (0.5 Hz without rotation) make
    the cyclic flap and the hub's whirl couple strongly."""
    J = N_BLADES * SECTION.mass[0, 0] * LENGTH**3 / 3
    k_hub = 0.5 * J * (2 * np.pi * f_hub) ** 2
    lam = multiblade_eigenvalues(omega, k_hub)
    ref = rotating_frame_eigenvalues(omega, k_hub)
    ref = ref[(np.abs(ref) < 20.0) & (ref.imag >= 0)]
    assert ref.size >= 10
    for x in ref:
        di = (lam - x).imag
        d = np.hypot((lam - x).real, di - omega * np.round(di / omega))
        assert d.min() < 1e-6 * max(abs(x), 1.0), (x, lam[np.argmin(d)], d.min())
