"""Rigid links, lumped masses, springs, SPCs, damping, DOF bookkeeping."""

import numpy as np
import pytest

from windflutter.errors import InputError, ModelError
from windflutter.structure import assemble, damping_matrix, modes
from windflutter.structure.damping import rayleigh_coefficients
from windflutter.structure.fem import Diaphragm, FEModel, LumpedMass, RigidLink, Spring


def block_on_springs(h=0.0, with_nodes=True):
    """Rigid block: CONM2 at master node 0 (CG offset (0, 0, h)), RBE2 to 4 corners on springs."""
    a, b = 1.0, 0.6
    corners = np.array([[a, b, 0], [-a, b, 0], [-a, -b, 0], [a, -b, 0]], float)
    nodes = np.vstack([[0, 0, 0], corners])
    kx, ky, kz = 2e5, 3e5, 1e6
    m, J = 500.0, np.diag([40.0, 90.0, 110.0])
    fe = FEModel(
        nodes=nodes,
        masses=[LumpedMass(node=0, mass=m, inertia=J, offset=np.array([0.0, 0.0, h]))],
        rigid_links=[RigidLink(independent=0, dependent=np.arange(1, 5))],
        springs=[Spring(node_a=i, stiffness=np.diag([kx, ky, kz, 0, 0, 0])) for i in range(1, 5)],
    )
    return fe, dict(a=a, b=b, kx=kx, ky=ky, kz=kz, m=m, J=J)


def test_rigid_body_on_springs_decoupled():
    fe, p = block_on_springs(h=0.0)
    st = assemble(fe)
    assert st.nq == 6  # only the master's 6 DOFs remain (corners are dependent)
    f = np.sort(modes(st, n=6).freq)
    a, b, m, J = p["a"], p["b"], p["m"], p["J"]
    om = np.sqrt([4 * p["kx"] / m, 4 * p["ky"] / m, 4 * p["kz"] / m, 4 * p["kz"] * b**2 / J[0, 0],
                  4 * p["kz"] * a**2 / J[1, 1], 4 * (p["kx"] * b**2 + p["ky"] * a**2) / J[2, 2]])
    # hand calculation, exact (no discretisation): 1e-10
    np.testing.assert_allclose(f, np.sort(om) / (2 * np.pi), rtol=1e-10)


def test_rigid_body_on_springs_cg_offset():
    """CG at height h above the spring plane couples sway x with pitch ry (2x2 by hand)."""
    h = 0.4
    fe, p = block_on_springs(h=h)
    f = np.sort(modes(assemble(fe), n=6).freq)
    m, J, a, b = p["m"], p["J"], p["a"], p["b"]
    # x_cg = x + h ry: M = [[m, m h], [m h, Jyy + m h^2]], K = diag(4 kx, 4 kz a^2)
    def pair(k1, k2, Jr):
        Mm = np.array([[m, m * h], [m * h, Jr + m * h**2]])
        Kk = np.diag([k1, k2])
        # closed form of det(K - w2 M) = 0
        A = np.linalg.det(Mm)
        B = -(Kk[0, 0] * Mm[1, 1] + Kk[1, 1] * Mm[0, 0])
        C = Kk[0, 0] * Kk[1, 1]
        return [(-B - np.sqrt(B * B - 4 * A * C)) / (2 * A), (-B + np.sqrt(B * B - 4 * A * C)) / (2 * A)]
    w2 = pair(4 * p["kx"], 4 * p["kz"] * a**2, J[1, 1])  # x - ry
    # y - rx: y_cg = y - h rx  (sign irrelevant for the eigenvalues)
    w2 += pair(4 * p["ky"], 4 * p["kz"] * b**2, J[0, 0])
    w2 += [4 * p["kz"] / m, 4 * (p["kx"] * b**2 + p["ky"] * a**2) / J[2, 2]]
    np.testing.assert_allclose(f, np.sort(np.sqrt(w2)) / (2 * np.pi), rtol=1e-10)


def test_rigid_link_kinematics_and_chain():
    # node 2 depends on 1, node 1 depends on 0 (chain); node 3 only on rotations
    nodes = np.array([[0, 0, 0], [1, 0, 0], [1, 2, 0], [0, 0, 3]], float)
    fe = FEModel(nodes=nodes, rigid_links=[RigidLink(1, np.array([2])), RigidLink(0, np.array([1])),
                                           RigidLink(0, np.array([3]), dofs=(3, 4, 5))],
                 springs=[Spring(0, np.eye(6) * 1e3), Spring(3, np.eye(6) * 1e3)])
    st = assemble(fe)
    q = np.zeros(st.nq)
    th = np.array([0.01, -0.02, 0.03])
    for c, v in zip((3, 4, 5), th):
        q[st.dof_index(0, c)] = v
    q[st.dof_index(0, "ux")] = 0.1
    u = st.expand(q).reshape(-1, 6)
    for n in (1, 2):
        np.testing.assert_allclose(u[n, :3], [0.1, 0, 0] + np.cross(th, nodes[n]), atol=1e-15)
        np.testing.assert_allclose(u[n, 3:], th, atol=1e-15)
    np.testing.assert_allclose(u[3, 3:], th)
    assert np.all(u[3, :3] == 0)  # translations of node 3 are independent
    fe.rigid_links.append(RigidLink(2, np.array([0])))
    with pytest.raises(ModelError):
        assemble(fe)


def _plane_frame(seed=3):
    """A random orthonormal frame (e1, e2, n): the diaphragm's plane is not aligned with the axes."""
    Q, _ = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    return Q[:, 0], Q[:, 1], Q[:, 2]


def test_diaphragm_kinematics():
    """Every constrained motion keeps the section's shape in its plane; rigid-body motions and
    out-of-plane (warping) motion of any node remain possible; two DOFs removed per dependent node."""
    e1, e2, n = _plane_frame()
    pts = np.random.default_rng(1).normal(size=(6, 2))
    x = pts[:, :1] * e1 + pts[:, 1:] * e2 + np.array([1.0, 2.0, 3.0])
    fe = FEModel(nodes=x, diaphragms=[Diaphragm(0, np.arange(1, 6), n)])
    from windflutter.structure.constraints import constraint_map

    T, free = constraint_map(fe)
    assert T.shape == (36, 36 - 2 * 5)
    u = (T @ np.random.default_rng(2).normal(size=T.shape[1])).reshape(-1, 6)
    E = np.vstack([e1, e2])
    rel = u[1:, :3] - u[0, :3] - np.cross(u[0, 3:], x[1:] - x[0])
    np.testing.assert_allclose(rel @ E.T, 0.0, atol=1e-13)
    th, a = np.array([0.3, -0.1, 0.2]), np.array([0.5, 0.7, -0.4])
    rigid = np.hstack([a + np.cross(th, x - x[0]), np.tile(th, (6, 1))]).ravel()
    warp = np.zeros((6, 6))
    warp[3, :3] = n
    for target in (rigid, warp.ravel()):
        q = np.linalg.lstsq(T.toarray(), target, rcond=None)[0]
        np.testing.assert_allclose(T @ q, target, atol=1e-12)


def test_diaphragm_masses_on_springs():
    """Four masses on springs tied in a tilted plane: exact frequencies from a hand-built 3-DOF
    in-plane rigid system (master translation in the plane, rotation about the normal) and
    independent out-of-plane and rotational oscillators; tolerance 1e-9 (no discretisation)."""
    e1, e2, n = _plane_frame()
    r = np.array([[0.0, 0.0], [2.0, 0.3], [1.5, 1.2], [-0.4, 0.9]])
    x = r[:, :1] * e1 + r[:, 1:] * e2
    m, j, k_in, kz, kr = 3.0, 0.2, 4e4, 9e3, 700.0
    Kt = k_in * (np.outer(e1, e1) + np.outer(e2, e2)) + kz * np.outer(n, n)
    K6 = np.zeros((6, 6))
    K6[:3, :3], K6[3:, 3:] = Kt, kr * np.eye(3)
    fe = FEModel(nodes=x, masses=[LumpedMass(i, m, inertia=j * np.eye(3)) for i in range(4)],
                 springs=[Spring(i, K6) for i in range(4)], diaphragms=[Diaphragm(0, np.arange(1, 4), n)])
    st = assemble(fe)
    assert st.nq == 24 - 6
    # in-plane: node i moves a1 e1 + a2 e2 + psi n x r_i
    B = [np.column_stack([e1, e2, np.cross(n, xi)]) for xi in x]
    M3 = sum(m * b.T @ b for b in B) + np.diag([0.0, 0.0, j])
    K3 = sum(k_in * b.T @ b for b in B) + np.diag([0.0, 0.0, kr])
    import scipy.linalg as sla

    w_in = np.sqrt(sla.eigh(K3, M3, eigvals_only=True))
    expect = np.sort(np.concatenate([w_in, np.full(4, np.sqrt(kz / m)), np.full(11, np.sqrt(kr / j))])) / (2 * np.pi)
    np.testing.assert_allclose(np.sort(modes(st, n=18).freq), expect, rtol=1e-9)


def test_spc_on_dependent_dof_is_an_error():
    fe, _ = block_on_springs()
    fe.spc = {1: (2,)}
    with pytest.raises(ModelError, match="dependent"):
        assemble(fe)


def test_two_node_spring_and_labels():
    nodes = np.array([[0, 0, 0], [1, 0, 0]], float)
    k = 1e4
    fe = FEModel(nodes=nodes, springs=[Spring(0, np.diag([k] * 6), node_b=1)],
                 masses=[LumpedMass(1, 2.0, inertia=np.eye(3))], spc={0: (0, 1, 2, 3, 4, 5)})
    st = assemble(fe)
    assert st.nq == 6 and st.dof_labels()[0] == "1:ux" and len(st.dof_labels(full=True)) == 12
    f = modes(st, n=6).freq
    np.testing.assert_allclose(f[:3], np.sqrt(k / 2.0) / (2 * np.pi), rtol=1e-12)
    np.testing.assert_allclose(f[3:], np.sqrt(k / 1.0) / (2 * np.pi), rtol=1e-12)


def test_unconnected_node_is_auto_constrained():
    fe, _ = block_on_springs()
    fe.nodes = np.vstack([fe.nodes, [5.0, 5.0, 5.0]])
    st = assemble(fe)
    assert st.nq == 6 and set(st.auto_spc // 6) == {5}


def test_mechanism_detected():
    fe, _ = block_on_springs()
    fe.springs = fe.springs[:1]  # one corner spring cannot hold a rigid body
    with pytest.raises(ModelError, match="constrained"):
        assemble(fe)


def test_bad_inputs():
    fe, _ = block_on_springs()
    fe.masses = [LumpedMass(0, 1.0, inertia=np.array([[1.0, 2.0, 0], [0, 1, 0], [0, 0, 1]]))]
    with pytest.raises(InputError, match="inertia"):
        assemble(fe)
    fe, _ = block_on_springs()
    fe.springs[0] = Spring(1, np.eye(3))
    with pytest.raises(InputError, match="springs"):
        assemble(fe)


def test_damping_rayleigh_and_modal():
    fe, _ = block_on_springs(h=0.3)
    st = assemble(fe)
    md = modes(st, n=6)
    om = 2 * np.pi * md.freq
    al, be = rayleigh_coefficients(md.freq[0], md.freq[-1], 0.02, 0.05)
    D = damping_matrix(st, "rayleigh", alpha=al, beta=be)
    Dm = md.shapes.T @ D @ md.shapes
    zeta = np.diag(Dm) / (2 * om)
    np.testing.assert_allclose(zeta, al / (2 * om) + be * om / 2, rtol=1e-9)
    assert zeta[0] == pytest.approx(0.02) and zeta[-1] == pytest.approx(0.05)
    z = np.linspace(0.01, 0.06, 6)
    for reduced, Phi in ((False, md.shapes), (True, md.q)):
        Dmod = damping_matrix(st, "modal", modes=md, zeta=z, reduced=reduced)
        np.testing.assert_allclose(Phi.T @ Dmod @ Phi, np.diag(2 * z * om), atol=1e-9 * om.max())
    with pytest.raises(InputError):
        damping_matrix(st, "viscous")
