"""Multi-blade coordinates of an isotropic rotor: exact against the rotating frame, analytic rigid
rotors (gyroscopic whirl, drivetrain), and Floquet exponents of the periodic system by time
integration (an implementation in this file that shares nothing with the solver's assembly)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from windflutter.structure.assembly import assemble
from windflutter.structure.fem import FEModel, LumpedMass, RigidLink, Spring
from windflutter.system.blade import RotorBlade
from windflutter.system.multiblade import BladeSystem, multiblade_system
from windflutter.system.support import Drivetrain, fixed_frame, rigid_body_mass, support_model

AXIS = np.array([1.0, 0.0, 0.0])


def point_mass_blade(r_hub=2.0, length=40.0, n=8, m_node=300.0):
    """A rigid blade: point masses on a straight radial line, all tied rigidly to a clamped hub node
    at the origin (the ``rotor_blade`` layout with no elastic freedom)."""
    s = np.linspace(r_hub, r_hub + length, n + 1)[1:]
    nodes = np.vstack([np.column_stack([np.zeros(n), np.zeros(n), s]), np.zeros((1, 3))])
    hub = n
    fe = FEModel(nodes=nodes, masses=[LumpedMass(i, m_node) for i in range(n)],
                 rigid_links=[RigidLink(hub, np.arange(n))], spc={hub: (0, 1, 2, 3, 4, 5)},
                 node_groups={"hub": np.array([hub]), "blade0": np.arange(n + 1)})
    return fe, s, m_node


def spring_support(k_rot: float, k_trans: float = 1e14):
    """A massless hub node on a grounded spring (stiff in translation and shaft rotation)."""
    K = np.diag([k_trans, k_trans, k_trans, 1e14, k_rot, k_rot])
    fe = FEModel(nodes=np.zeros((1, 3)), springs=[Spring(0, K)], node_groups={"hub": np.array([0])})
    return fe


def first_order_eigs(mb):
    lam = np.linalg.eigvals(mb.state_matrix())
    return lam[np.argsort(np.abs(lam))]


def test_fixed_hub_cyclic_modes_are_shifted_by_rotor_speed(nrel_rotor_blade):
    """Hub fixed, rotor locked: the blades are independent, so the multi-blade eigenvalues are the
    rotating-frame ones (collective) and the same shifted by +-i Omega (cyclic) -- exactly."""
    rb = nrel_rotor_blade
    om = 12.1 * np.pi / 30
    M, C, K = rb.matrices(None).at(om)
    e = slice(6, None)
    n = M.shape[0] - 6
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M[e, e], K[e, e]), -np.linalg.solve(M[e, e], C[e, e])]])
    lr = np.linalg.eigvals(A)
    ff = fixed_frame(None, np.zeros((6, 6)), rb.axis, Drivetrain(mode="locked"))
    lam = first_order_eigs(multiblade_system(ff, BladeSystem(M, C, K), 3, om, rb.axis))
    expected = np.concatenate([lr, lr + 1j * om, lr - 1j * om])
    assert lam.size == expected.size
    dist = np.array([np.min(np.abs(expected - x)) for x in lam]) / np.maximum(np.abs(lam), 1.0)
    assert dist.max() < 1e-10  # exact: round-off of a 750-state eigenproblem


def test_multiblade_matrices_do_not_depend_on_azimuth(nrel_rotor_blade, nrel_support):
    rb = nrel_rotor_blade
    om = 1.2
    M, C, K = rb.matrices(None).at(om)
    ff = fixed_frame(nrel_support, rigid_body_mass(5e4, np.diag([1e5, 5e4, 5e4]), np.zeros(3)), rb.axis,
                     Drivetrain(stiffness=5e8, generator_inertia=5e6))
    a = multiblade_system(ff, BladeSystem(M, C, K), 3, om, rb.axis, psi=0.0)
    b = multiblade_system(ff, BladeSystem(M, C, K), 3, om, rb.axis, psi=1.234)
    for x, y in ((a.M, b.M), (a.C, b.C), (a.K, b.K)):
        assert np.abs(x - y).max() <= 1e-12 * np.abs(x).max()


def _rigid_rotor(k_rot=None, drivetrain=None, n_blades=3, omega=1.3):
    fe, r, m = point_mass_blade()
    rb = RotorBlade(fe, assemble(fe, allow_rigid=True), None, np.zeros(3), AXIS)
    M, C, K = rb.matrices(None).at(omega)
    sup = None
    if k_rot is not None:
        fs = spring_support(k_rot)
        sup = support_model(fs, assemble(fs))
    ff = fixed_frame(sup, np.zeros((6, 6)), AXIS, drivetrain or Drivetrain(mode="locked"))
    mb = multiblade_system(ff, BladeSystem(M, C, K), n_blades, omega, AXIS)
    J = n_blades * m * np.sum(r**2)  # polar inertia of the point masses
    return mb, J


@pytest.mark.parametrize("n_blades", [3, 4])
def test_rigid_rotor_gyroscopic_whirl(n_blades):
    """A rigid rotor (polar J, diametral I_d = J/2 for N >= 3 blades in a plane) spinning at Omega
    on tilt and yaw springs k: whirl frequencies from (k - I_d w^2)^2 = (J Omega w)^2, i.e.
    w = (+-J Omega + sqrt(J^2 Omega^2 + 4 I_d k)) / (2 I_d) -- the textbook gyroscopic rotor, no
    centrifugal stiffness (it needs the hub-link prestress term to come out so)."""
    om = 1.3
    J0 = 3 * 300.0 * np.sum(np.linspace(2.0, 42.0, 9)[1:] ** 2)  # the rotor of point_mass_blade
    k = 0.5 * J0 * (2.0 * om) ** 2  # whirl near 2 Omega: strong gyroscopic split
    mb, J = _rigid_rotor(k_rot=k, n_blades=n_blades, omega=om)
    Id = 0.5 * J
    w_fw = (J * om + np.sqrt((J * om) ** 2 + 4 * Id * k)) / (2 * Id)
    w_bw = (-J * om + np.sqrt((J * om) ** 2 + 4 * Id * k)) / (2 * Id)
    lam = first_order_eigs(mb)
    osc = np.sort(np.abs(lam[(lam.imag > 1e-6)]))
    assert osc[0] == pytest.approx(w_bw, rel=1e-6)
    assert osc[1] == pytest.approx(w_fw, rel=1e-6)


def test_rigid_rotor_drivetrain_frequency_and_zero_mode():
    """Rotor (polar J) and generator (J_g) on a shaft spring k: one rigid-body mode lambda = 0
    and the torsion mode w^2 = k (1/J + 1/J_g)."""
    Jg, k = 2e6, 4e8
    mb, J = _rigid_rotor(drivetrain=Drivetrain(stiffness=k, generator_inertia=Jg))
    lam = first_order_eigs(mb)
    assert np.abs(lam[:2]).max() < 1e-6  # the rigid rotation of the drivetrain
    osc = np.sort(np.abs(lam[lam.imag > 1e-6]))
    assert osc[0] == pytest.approx(np.sqrt(k * (1 / J + 1 / Jg)), rel=1e-6)


# ------------------------------------------------------------------------------- Floquet
def _periodic_rhs(blade: BladeSystem, fixed, n_blades, omega, axis):
    """x' = A(t) x of the periodic system in physical coordinates [x_F, eta_0 .. eta_N-1], built
    here from scratch: y_b = J_b(t) q with the blade rotation R = cos I + sin [n] + (1 - cos) n n^T
    of the azimuth a = Omega t + 2 pi b / N, and J', J'' from the exact derivatives of R
    (dR/da = -sin I + cos [n] + sin n n^T, d2R/da2 = -cos I - sin [n] + cos n n^T). Exact
    derivatives keep A(t) smooth: finite differences put round-off noise (~eps/h^2) into A(t)
    that made the adaptive integrator take tens of thousands of steps per percent of a period."""
    nF, m = fixed.M.shape[0], blade.M.shape[0] - 6
    nq = nF + n_blades * m
    nx = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    nn = np.outer(axis, axis)

    def J(t, b):
        """J_b and its first two time derivatives."""
        a = omega * t + 2 * np.pi * b / n_blades
        c, s = np.cos(a), np.sin(a)
        rots = (c * np.eye(3) + s * nx + (1 - c) * nn,
                omega * (-s * np.eye(3) + c * nx + s * nn),
                omega**2 * (-c * np.eye(3) - s * nx + c * nn))
        out = []
        for k, R in enumerate(rots):
            j = np.zeros((6 + m, nq))
            j[:3, :nF] = R.T @ fixed.L[:3]
            j[3:6, :nF] = R.T @ fixed.L[3:]
            if k == 0:
                j[6:, nF + b * m: nF + (b + 1) * m] = np.eye(m)
            out.append(j)
        return out

    base = [np.zeros((nq, nq)) for _ in range(3)]
    for X, Y in zip(base, (fixed.M, fixed.C, fixed.K)):
        X[:nF, :nF] = Y

    def A(t):
        M, C, K = (X.copy() for X in base)
        for b in range(n_blades):
            j0, j1, j2 = J(t, b)
            M += j0.T @ blade.M @ j0
            C += j0.T @ (2 * blade.M @ j1 + blade.C @ j0)
            K += j0.T @ (blade.M @ j2 + blade.C @ j1 + blade.K @ j0)
        MinvKC = np.linalg.solve(M, np.hstack([K, C]))
        out = np.zeros((2 * nq, 2 * nq))
        out[:nq, nq:] = np.eye(nq)
        out[nq:, :nq] = -MinvKC[:, :nq]
        out[nq:, nq:] = -MinvKC[:, nq:]
        return out

    return A, 2 * nq


def test_floquet_exponents_equal_multiblade_eigenvalues(nrel_rotor_blade, nrel_support):
    """Rotor of 3 flexible blades (2 modes each) on a flexible 2-mode tower with drivetrain: the
    eigenvalues of the multi-blade system equal the Floquet exponents of the periodic system
    (monodromy matrix over one revolution by time integration), modulo i Omega."""
    rb = nrel_rotor_blade
    om = 1.27
    w2, Phi = sla.eigh(rb.struct.Kr.toarray(), rb.struct.Mr.toarray())
    M, C, K = rb.matrices(Phi[:, :2]).at(om)
    C = C.copy()
    C[6:, 6:] += 0.002 * K[6:, 6:]  # blade damping (deformation only), so the exponents are distinct
    blade = BladeSystem(M, C, K)
    sup = nrel_support
    w2s, Vs = sla.eigh(sup.K, sup.M)
    sm = support_model(sup.fe, sup.struct, basis=Vs[:, :2])
    ff = fixed_frame(sm, rigid_body_mass(5.7e4, np.diag([1.2e5, 6e4, 6e4]), np.zeros(3)), rb.axis,
                     Drivetrain(stiffness=5e7, damping=1e6, generator_inertia=5.0e6))
    lam = np.linalg.eigvals(multiblade_system(ff, blade, 3, om, rb.axis).state_matrix())
    A, n = _periodic_rhs(blade, ff, 3, om, rb.axis)
    T = 2 * np.pi / om
    sol = solve_ivp(lambda t, x: (A(t) @ x.reshape(n, n)).ravel(), (0.0, T), np.eye(n).ravel(),
                    method="DOP853", rtol=1e-10, atol=1e-11)
    mu = np.linalg.eigvals(sol.y[:, -1].reshape(n, n))
    flo = np.log(mu.astype(complex)) / T  # defined modulo i Omega
    for x in flo:  # the nearest multi-blade eigenvalue, modulo i Omega
        di = (lam - x).imag
        d = np.hypot((lam - x).real, di - om * np.round(di / om))
        assert d.min() < 1e-6 * max(abs(x), 1.0)
