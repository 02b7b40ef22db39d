"""Rotating-frame terms of rigid sections (windflutter.rotor.spin): offsets and rotary inertia.

Three independent references:

* the exact kinetic energy of a rigid body made of point masses, differentiated numerically with
  exact rotations (scipy's rotation vectors) -- shares nothing with the closed forms;
* the hinged pendulums of rotor dynamics: a point mass at ``s`` radially outside a hinge at radius
  ``r`` on a spinning arm swings in the plane of rotation at ``Omega^2 r / s`` (lead-lag) and out of
  it at ``Omega^2 (r + s) / s`` (flap); e.g. Johnson, *Helicopter Theory* (1980), ch. 9;
* a rotating beam whose sections carry a mass-centre offset against the same beam with massless
  sections and point masses on stiff massless arms at the offsets: the point masses need only the
  translational Coriolis and softening, and the arms' second-order rotation comes from their own
  initial-stress matrix, so the offsets' couplings come from different code and different physics
  bookkeeping.  Without the section terms (the translational mass alone, as before) the beam's
  frequencies are off by 2-10 %; the tolerance 0.3 % is twice the discretization difference of the
  two models at rest (0.13 %, consistent vs nodal masses, 40 elements).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from windflutter.linalg_tools import skew
from windflutter.rotor.translational import coriolis_and_softening
from windflutter.rotor.spin import inertia_moments, section_spin, spin_terms
from windflutter.structure.assembly import assemble
from windflutter.structure.beam import beam_frames
from windflutter.structure.fem import BeamSection, FEModel, LumpedMass
from windflutter.structure.prestress import geometric_stiffness, static_solve

AXIS = np.array([0.0, 0.0, 1.0])


def _point_bodies(seed=1, n=5):
    rng = np.random.default_rng(seed)
    return rng.uniform(1.0, 2.0, n), rng.normal(size=(n, 3))


def _rigid_mass(masses, points):
    Ms = np.zeros((6, 6))
    for m, s in zip(masses, points):
        B = np.hstack([np.eye(3), -skew(s)])
        Ms += m * B.T @ B
    return Ms


def test_section_terms_are_the_exact_energy_derivatives():
    """Softening and load: central differences (h = 1e-4) of the exact centrifugal potential
    ``-1/2 sum m |Omega x (X + u + Rot(theta) s)|^2``; Coriolis: ``sum B^T 2 m S(Omega) B``.
    Tolerance 1e-6 relative: the differences' O(h^2) error."""
    mk, S = _point_bodies()
    X = np.array([3.0, 1.0, 0.5])
    w = np.array([0.2, 0.3, 1.0]) / np.linalg.norm([0.2, 0.3, 1.0])
    G, Kr, f = section_spin(*inertia_moments(_rigid_mass(mk, S)), w, X)

    def V(q):
        R = Rotation.from_rotvec(q[3:]).as_matrix()
        r = X + q[:3] + S @ R.T
        return -0.5 * float(np.sum(mk * np.sum(np.cross(w, r) ** 2, axis=1)))

    h, E = 1e-4, np.eye(6) * 1e-4
    grad = np.array([(V(E[i]) - V(-E[i])) / (2 * h) for i in range(6)])
    hess = np.array([[(V(E[i] + E[j]) - V(E[i] - E[j]) - V(E[j] - E[i]) + V(-E[i] - E[j])) / (4 * h * h)
                      for j in range(6)] for i in range(6)])
    assert np.abs(-hess - Kr).max() < 1e-6 * np.abs(Kr).max()
    assert np.abs(-grad - f).max() < 1e-6 * np.abs(f).max()
    Gx = sum(m * np.hstack([np.eye(3), -skew(s)]).T @ (2 * skew(w)) @ np.hstack([np.eye(3), -skew(s)])
             for m, s in zip(mk, S))
    assert np.abs(Gx - G).max() < 1e-12 * np.abs(Gx).max()


@pytest.mark.parametrize("hinge, expected", [(2, lambda r, s: r / s), (0, lambda r, s: (r + s) / s)])
def test_hinged_point_mass_swings_at_the_pendulum_frequency(hinge, expected):
    """A point mass on a massless arm of length s, hinged at radius r on the spinning hub
    (rotation about the shaft axis z: lead-lag; about the tangential axis x: flap)."""
    r, s, m, Om = 4.0, 1.5, 30.0, 2.0
    fe = FEModel(nodes=np.array([[0.0, r, 0.0]]), masses=[LumpedMass(node=0, mass=m, offset=np.array([0.0, s, 0.0]))],
                 node_groups={"rotor": np.array([0])})
    M = assemble(fe, check=False, allow_rigid=True).M
    G1, Kr1, _ = spin_terms(fe, M, np.array([0]), AXIS, np.zeros(3))
    d = 3 + hinge
    w2 = -Om**2 * Kr1[d, d] / M[d, d]
    assert w2 == pytest.approx(Om**2 * expected(r, s), rel=1e-12)
    assert abs(G1[d, d]) < 1e-12


def _stiffness(EA, GA, GJ, EIy, EIz):
    return np.diag([EA, GA, GA, GJ, EIy, EIz]).astype(float)


def _section_mass(m, c, Jcg):
    S = skew(c)
    Ms = np.zeros((6, 6))
    Ms[:3, :3] = m * np.eye(3)
    Ms[3:, :3], Ms[:3, 3:] = m * S, (m * S).T
    Ms[3:, 3:] = Jcg + m * (c @ c * np.eye(3) - np.outer(c, c))
    return Ms


def _blade(n, arms, c=(0.05, 0.5, 0.15), r0=2.0, L=10.0, m=50.0, Jcg=(2.0, 0.3, 1.7)):
    """A straight blade along y from radius r0, spinning about z; section mass-centre offset ``c``
    (section frame: x along the blade, y ~ in the plane of rotation, slightly pitched)."""
    K = _stiffness(1e9, 1e8, 1e5, 3e5, 1.2e6)
    y = r0 + np.linspace(0.0, L, n + 1)
    nodes = np.column_stack([np.zeros(n + 1), y, np.zeros(n + 1)])
    conn = np.column_stack([np.arange(n), np.arange(1, n + 1)])
    orient = np.tile([1.0, 0.2, 0.1], (n, 1))
    c, J = np.asarray(c, float), np.diag(Jcg)
    common = dict(beam_conn=conn, beam_section=np.zeros(n, dtype=np.int64), beam_orient=orient)
    if not arms:
        return FEModel(nodes=nodes, beam_sections=[BeamSection(K, _section_mass(m, c, J))], spc={0: (0, 1, 2, 3, 4, 5)},
                       node_groups={"rotor": np.arange(n + 1)}, **common)
    _, R = beam_frames(FEModel(nodes=nodes, beam_sections=[BeamSection(K, np.zeros((6, 6)))], **common))
    cg = R[0].T @ c  # the offset in global axes (straight blade: one frame)
    h = np.full(n + 1, L / n)
    h[[0, -1]] *= 0.5
    a = cg / np.linalg.norm(cg)
    o = np.cross(a, [0.0, 1.0, 0.3])
    arm_section = BeamSection(_stiffness(1e11, 1e11, 1e10, 1e10, 1e10), np.zeros((6, 6)))
    return FEModel(nodes=np.vstack([nodes, nodes + cg]),
                   beam_conn=np.vstack([conn, np.column_stack([np.arange(n + 1), np.arange(n + 1) + n + 1])]),
                   beam_section=np.r_[np.zeros(n, dtype=np.int64), np.ones(n + 1, dtype=np.int64)],
                   beam_orient=np.vstack([orient, np.tile(o, (n + 1, 1))]),
                   beam_sections=[BeamSection(K, _section_mass(0.0, np.zeros(3), J)), arm_section],
                   masses=[LumpedMass(node=n + 1 + i, mass=m * h[i]) for i in range(n + 1)],
                   spc={0: (0, 1, 2, 3, 4, 5), n + 1: (0, 1, 2, 3, 4, 5)}, node_groups={"rotor": np.arange(2 * n + 2)})


def _frequencies(fe, Om, translational=False, k=6):
    """Lowest ``k`` frequencies (Hz) of the spinning, centrifugally prestressed blade; massless
    DOFs (the arms' ends' rotations) condensed statically."""
    st = assemble(fe, check=False, allow_rigid=True)
    nodes = np.arange(fe.n_nodes)
    if translational:
        G1, Kr1 = coriolis_and_softening(st.M, (6 * nodes[:, None] + np.arange(3)).ravel(), AXIS)
        X = np.zeros(fe.n_dof)
        X.reshape(-1, 6)[:, :3] = fe.nodes
        f1 = Kr1 @ X
    else:
        G1, Kr1, f1 = spin_terms(fe, st.M, nodes, AXIS, np.zeros(3))
    Ks = geometric_stiffness(fe, static_solve(st, Om**2 * f1), moments=True)
    T = st.T
    M, G = (T.T @ st.M @ T).toarray(), (T.T @ (Om * G1) @ T).toarray()
    K = (T.T @ (st.K + Ks - Om**2 * Kr1) @ T).toarray()
    K = 0.5 * (K + K.T)
    w = np.abs(M).sum(1) + np.abs(G).sum(1)
    keep = w > 1e-12 * w.max()
    if not keep.all():
        C = np.zeros((len(w), keep.sum()))
        C[keep] = np.eye(keep.sum())
        C[~keep] = -np.linalg.solve(K[np.ix_(~keep, ~keep)], K[np.ix_(~keep, keep)])
        M, G, K = C.T @ M @ C, C.T @ G @ C, C.T @ K @ C
    m = M.shape[0]
    A = np.block([[np.zeros((m, m)), np.eye(m)], [-np.linalg.solve(M, K), -np.linalg.solve(M, G)]])
    lam = np.linalg.eigvals(A)
    return np.sort(lam[lam.imag > 1e-9].imag)[:k] / (2 * np.pi)


@pytest.mark.parametrize("Om", [0.0, 6.0])
def test_offset_sections_equal_point_masses_on_arms(Om):
    """At 6 rad/s (above the first flap frequency at rest, 0.42 Hz) the offsets move the frequencies
    by 2-10 %; with the section terms both models agree within 0.3 % (module docstring)."""
    n = 40
    ref = _frequencies(_blade(n, arms=True), Om)
    ours = _frequencies(_blade(n, arms=False), Om)
    assert np.abs(ours / ref - 1).max() < 3e-3, (ours, ref)
    if Om:  # the translational mass alone misses the couplings (the test can fail)
        old = _frequencies(_blade(n, arms=False), Om, translational=True)
        assert np.abs(old / ref - 1).max() > 0.05


def test_without_offsets_and_inertia_the_terms_are_the_point_masses():
    """Sections with no offset and no rotary inertia on a lumped-mass grid: the same G and Kr as the
    translational formula of windflutter.rotor.rotating on the lumped masses (exact)."""
    nodes = np.array([[0.0, 2.0, 0.0], [0.1, 3.0, 0.2]])
    fe = FEModel(nodes=nodes, masses=[LumpedMass(node=0, mass=3.0), LumpedMass(node=1, mass=5.0)],
                 node_groups={"rotor": np.arange(2)})
    M = assemble(fe, check=False, allow_rigid=True).M
    w = np.array([0.3, -0.2, 1.1]) / np.linalg.norm([0.3, -0.2, 1.1])
    G1, Kr1, f1 = spin_terms(fe, M, np.arange(2), w, np.zeros(3))
    Gt, Krt = coriolis_and_softening(M, (6 * np.arange(2)[:, None] + np.arange(3)).ravel(), w)
    assert abs(G1 - Gt).max() < 1e-12 and abs(Kr1 - Krt).max() < 1e-12
    X = np.zeros(12)
    X.reshape(-1, 6)[:, :3] = nodes
    assert np.allclose(f1, Krt @ X)
