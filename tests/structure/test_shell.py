"""Shell verification: isotropic plates (Navier, Leissa), thin tube (beam theory), laminates (CLT Navier)."""

import numpy as np
import pytest
from shellmodels import iso, plate, tube

from windflutter.structure import assemble, modes
from windflutter.structure.fem import OrthotropicMaterial, Ply, ShellProperty

E_AL, NU, RHO_AL = 70e9, 0.3, 2700.0


def ss_plate(n, a=1.0, b=1.0, h=0.01, prop=None, ss2=False):
    """Simply supported ("hard": w = 0 and the rotation about the edge normal = 0, i.e. the tangential
    slope, as in the Kirchhoff/Navier solution) rectangular plate; ss2 also restrains the
    edge-normal in-plane displacement.  (With the "soft" support, rotations free, the Mindlin plate
    has edge boundary layers and converges ~0.5 % below Navier at a/h = 100.)"""
    fe, idx = plate(n, n, a, b, prop or iso(E_AL, NU, RHO_AL, h))
    spc = {}
    for nodes, comp in ((idx[0], 0), (idx[-1], 0), (idx[:, 0], 1), (idx[:, -1], 1)):
        for k in nodes:
            spc.setdefault(int(k), set()).update({2, 3 + comp} | ({comp} if ss2 else set()))
    if not ss2:  # remove the in-plane rigid motion only
        spc[int(idx[0, 0])].update({0, 1})
        spc[int(idx[-1, 0])].update({1})
    fe.spc = {k: tuple(sorted(v)) for k, v in spc.items()}
    return fe


def kirchhoff_ss(m, n, a, b, D, rho_h):
    return np.pi / 2 * ((m / a) ** 2 + (n / b) ** 2) * np.sqrt(D / rho_h)


def test_simply_supported_isotropic_plate():
    a, b, h = 1.0, 0.8, 0.01
    fe = ss_plate(20, a, b, h)
    fe, _ = fe, None
    md = modes(assemble(fe), n=6)
    D = E_AL * h**3 / (12 * (1 - NU**2))
    ref = sorted(kirchhoff_ss(m, n, a, b, D, RHO_AL * h) for m in range(1, 4) for n in range(1, 4))[:4]
    # 20x20 Quad4, a/h = 100: discretisation error O(h^2) ~ 0.2-1 % for these modes (see convergence test)
    np.testing.assert_allclose(md.freq[:4], ref, rtol=0.012)


def test_incompressible_isotropic_ply_plane_stress():
    """nu = 0.5 (e.g. the IEA 10 MW balsa) is accepted and gives the plane-stress plate:
    Kirchhoff D = E h^3 / (12 (1 - nu^2)) with nu = 0.5; 1.2 % as the nu = 0.3 plate.  nu > 0.5 is
    refused (no isotropic solid has it)."""
    from windflutter.errors import InputError

    a, b, h, nu = 1.0, 0.8, 0.01, 0.5
    md = modes(assemble(ss_plate(20, a, b, h, prop=iso(E_AL, nu, RHO_AL, h))), n=2)
    D = E_AL * h**3 / (12 * (1 - nu**2))
    ref = sorted(kirchhoff_ss(m, n, a, b, D, RHO_AL * h) for m in range(1, 4) for n in range(1, 4))[:2]
    np.testing.assert_allclose(md.freq[:2], ref, rtol=0.012)
    with pytest.raises(InputError, match="nu <= 0.5"):
        assemble(ss_plate(4, a, b, h, prop=iso(E_AL, 0.55, RHO_AL, h)))


def test_mesh_convergence_rate():
    """Observed convergence order of the fundamental frequency of the SS square plate."""
    h = 0.01
    D = E_AL * h**3 / (12 * (1 - NU**2))
    f_ref = kirchhoff_ss(1, 1, 1.0, 1.0, D, RHO_AL * h)
    f = np.array([modes(assemble(ss_plate(n, h=h)), n=1).freq[0] for n in (4, 8, 16)])
    # observed order from three meshes (Richardson), independent of the reference value
    p = np.log2((f[0] - f[1]) / (f[1] - f[2]))
    f_inf = f[2] - (f[1] - f[2]) / (2**p - 1)
    # bilinear displacement fields: frequency error O(h^2) -> p close to 2
    assert 1.7 < p < 2.3, (f, p)
    # extrapolated value vs Kirchhoff (thin plate a/h = 100: Mindlin correction ~1e-4)
    assert f_inf == pytest.approx(f_ref, rel=1e-3)
    assert abs(f[2] - f_ref) / f_ref < 5e-3  # 16x16: +0.39 % observed


def test_cantilever_square_plate_leissa():
    # Leissa (1969) NASA SP-160, cantilever square plate (CFFF), nu = 0.3:
    # lambda = omega a^2 sqrt(rho h / D) = 3.492, 8.525, 21.43, 27.33, 31.11
    a, h = 1.0, 0.01
    fe, idx = plate(16, 16, a, a, iso(E_AL, NU, RHO_AL, h))
    fe.spc = {int(k): (0, 1, 2, 3, 4, 5) for k in idx[0]}
    md = modes(assemble(fe), n=5)
    D = E_AL * h**3 / (12 * (1 - NU**2))
    lam = 2 * np.pi * md.freq * a**2 * np.sqrt(RHO_AL * h / D)
    # 16x16 mesh: 1.5 % covers discretisation + Mindlin free-edge effects for the first five
    np.testing.assert_allclose(lam, [3.492, 8.525, 21.43, 27.33, 31.11], rtol=0.015)


def test_thin_tube_bending_and_torsion():
    R, L, t, E, nu, rho = 0.25, 10.0, 0.005, 210e9, 0.3, 7850.0
    fe, idx = tube(24, 40, R, L, iso(E, nu, rho, t))
    fe.spc = {int(k): (0, 1, 2, 3, 4, 5) for k in idx[0]}
    md = modes(assemble(fe), n=20)  # torsion is mode ~13
    I, A = np.pi * R**3 * t, 2 * np.pi * R * t
    f_bend = 1.87510407**2 / L**2 * np.sqrt(E * I / (rho * A)) / (2 * np.pi)
    f_tors = 1 / (4 * L) * np.sqrt(E / (2 * (1 + nu)) / rho)  # Saint-Venant, J = 2 pi R^3 t
    # bending: first two modes (pair).  Euler-Bernoulli ignores shear (thin tube shear factor 1/2)
    # and rotary inertia: Timoshenko correction for L/R = 40 is about -0.5 %; mesh ~ -0.3 %.
    np.testing.assert_allclose(md.freq[:2], f_bend, rtol=0.012)
    # torsion: the mode with the largest effective polar inertia about the tube axis
    k = int(np.argmax(md.effective_mass[:, 3]))
    assert md.freq[k] == pytest.approx(f_tors, rel=0.005)  # 40 elements along: O(h^2) ~ 1e-4
    # effective masses of the bending pair in y and z: first mode ~61.3 % of the mass
    m_tot = rho * A * L
    # (EB cantilever: 0.6131 for mode 1), the pair shares y and z: sum = 2 x 0.613
    assert md.effective_mass[:2, 1:3].sum() / m_tot == pytest.approx(2 * 0.613, abs=0.02)


# ---------------------------------------------------------------- laminates (CLT reference)
MAT = OrthotropicMaterial(E1=250e9, E2=10e9, nu12=0.25, G12=5e9, G13=5e9, G23=2e9, rho=1500.0)
# CLT assumes rigid transverse shear; the FE shell is FSDT.  To compare with the CLT Navier solution
# the transverse shear moduli are made 100x stiffer (with the physical G13, G23 the FSDT frequency of
# the [45/-45]2 plate at a/h = 100 is 3 % below CLT, and converges to it as G13, G23 grow or a/h grows:
# 0.969, 0.993, 0.999 for 1x, 10x, 100x; 0.996 at a/h = 500).
MAT_CLT = OrthotropicMaterial(E1=250e9, E2=10e9, nu12=0.25, G12=5e9, G13=5e11, G23=2e11, rho=1500.0)


def clt_abd(angles_deg, t_ply, mat):
    """Our own classical-lamination-theory A, B, D (material frame), bottom ply first."""
    nu21 = mat.nu12 * mat.E2 / mat.E1
    d = 1 - mat.nu12 * nu21
    Q = np.array([[mat.E1 / d, mat.nu12 * mat.E2 / d, 0], [mat.nu12 * mat.E2 / d, mat.E2 / d, 0], [0, 0, mat.G12]])
    h = t_ply * len(angles_deg)
    z = -h / 2 + t_ply * np.arange(len(angles_deg) + 1)
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for k, th in enumerate(np.radians(angles_deg)):
        c, s = np.cos(th), np.sin(th)
        # strain transformation laminate -> ply (engineering shear)
        Te = np.array([[c * c, s * s, c * s], [s * s, c * c, -c * s], [-2 * c * s, 2 * c * s, c * c - s * s]])
        Qb = Te.T @ Q @ Te
        A += Qb * (z[k + 1] - z[k])
        B += Qb * (z[k + 1] ** 2 - z[k] ** 2) / 2
        D += Qb * (z[k + 1] ** 3 - z[k] ** 3) / 3
    return A, B, D, h


def navier_ritz(A, B, D, rho_h, a, b, m=1, n=1):
    """Exact CLT frequency (Hz) of a SS-2 plate with u=U sin cos, v=V cos sin, w=W sin sin.

    These are the Navier functions for cross-ply and antisymmetric angle-ply laminates (Reddy 2004,
    Mechanics of Laminated Composite Plates and Shells, ch. 6), so a Rayleigh-Ritz solution with
    them is the exact CLT eigenvalue.  In-plane and transverse inertia rho h, no rotary inertia.
    """
    al, be = m * np.pi / a, n * np.pi / b
    gx, wx = np.polynomial.legendre.leggauss(24)
    X, Y = np.meshgrid(a / 2 * (gx + 1), b / 2 * (gx + 1), indexing="ij")
    W = np.outer(wx, wx) * a * b / 4
    sx, cx, sy, cy = np.sin(al * X), np.cos(al * X), np.sin(be * Y), np.cos(be * Y)
    # generalized strain operators (3 gen. coords U, V, W): eps = [u_x, v_y, u_y + v_x], kap = -[w_xx, w_yy, 2 w_xy]
    eps = np.zeros((3, 3) + X.shape)
    kap = np.zeros((3, 3) + X.shape)
    eps[0, 0] = al * cx * cy
    eps[1, 1] = be * cx * cy
    eps[2, 0] = -be * sx * sy
    eps[2, 1] = -al * sx * sy
    kap[0, 2] = al**2 * sx * sy
    kap[1, 2] = be**2 * sx * sy
    kap[2, 2] = -2 * al * be * cx * cy
    K = (np.einsum("iaxy,ij,jbxy,xy->ab", eps, A, eps, W) + np.einsum("iaxy,ij,jbxy,xy->ab", eps, B, kap, W)
         + np.einsum("iaxy,ij,jbxy,xy->ab", kap, B, eps, W) + np.einsum("iaxy,ij,jbxy,xy->ab", kap, D, kap, W))
    shp = np.stack([sx * cy, cx * sy, sx * sy])
    Mm = rho_h * np.diag(np.einsum("axy,axy,xy->a", shp, shp, W))
    w2 = np.linalg.eigvalsh(np.linalg.solve(np.linalg.cholesky(Mm), np.linalg.solve(np.linalg.cholesky(Mm), K).T))
    return np.sqrt(w2.min()) / (2 * np.pi)


@pytest.mark.parametrize("angles", [(0, 90, 90, 0), (45, -45, 45, -45), (30, -30)])
def test_laminated_ss_plate_navier(angles):
    a, b, t_ply = 1.0, 1.0, 0.01 / len(angles)
    prop = ShellProperty(plies=tuple(Ply(MAT_CLT, t_ply, np.radians(th)) for th in angles))
    fe = ss_plate(20, a, b, prop=prop, ss2=True)
    f_fe = modes(assemble(fe), n=1).freq[0]
    A, B, D, h = clt_abd(angles, t_ply, MAT_CLT)
    if angles[0] == 0:  # symmetric cross-ply: closed form, B = 0, D16 = D26 = 0
        assert np.allclose(B, 0) and abs(D[0, 2]) < 1e-12 * D[0, 0]
        f_cf = np.pi / 2 * np.sqrt((D[0, 0] / a**4 + 2 * (D[0, 1] + 2 * D[2, 2]) / (a * b) ** 2 + D[1, 1] / b**4)
                                   / (MAT.rho * h))
        assert navier_ritz(A, B, D, MAT.rho * h, a, b) == pytest.approx(f_cf, rel=1e-9)
    else:  # antisymmetric angle-ply: A16 = A26 = D16 = D26 = 0, B16, B26 != 0
        assert abs(D[0, 2]) < 1e-9 * D[0, 0] and abs(B[0, 2]) > 0
    f_ref = navier_ritz(A, B, D, MAT.rho * h, a, b)
    # 20x20 mesh, a/h = 100, near-rigid transverse shear: observed within 0.3 %; 1 % allowed
    assert f_fe == pytest.approx(f_ref, rel=0.01)


def _rotation(seed=3):
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def _ss_freq_in_local_frame(fe_rot, fe_flat, R):
    """Lowest frequency (Hz) of the rotated plate with the flat plate's SS-2 constraints applied
    in the plate frame: K_loc = T^T K T with T = diag(R) per node translation/rotation."""
    import scipy.sparse as sps
    from scipy.sparse.linalg import eigsh

    from windflutter.structure.assembly import assemble_matrices

    M, K = assemble_matrices(fe_rot)
    T = sps.block_diag([R] * (2 * fe_rot.n_nodes), format="csr")
    K, M = (T.T @ K @ T).tocsr(), (T.T @ M @ T).tocsr()
    fixed = {6 * n + c for n, cs in fe_flat.spc.items() for c in cs}
    free = np.array([d for d in range(K.shape[0]) if d not in fixed])
    lam = eigsh(K[free][:, free], k=1, M=M[free][:, free], sigma=0.0, which="LM")[0]
    return float(np.sqrt(lam[0]) / (2 * np.pi))


def test_material_axis_equal_to_element_axis_rotated_plate_vs_clt():
    """pyfe3d 0.11 Quad4.update_rotation_matrix takes sin = sqrt(1 - cos^2) of the material angle;
    with the material axis equal to the element x axis, cos rounds to 1 + 2.2e-16 and sin is NaN
    on a share of arbitrarily oriented elements (shown below for this mesh).  windflutter computes
    the angle with atan2 (shell.material_rotation).  The [30/-30] angle-ply SS-2 plate, turned by
    an arbitrary rotation, (a) aligned: material axis = the exact element x axis, plies +-30 deg;
    (b) rotated: material axis 30 deg off, plies 0/-60 deg: both match the CLT Navier frequency
    (1 %, as the flat-plate test) and the flat plate's FE frequency (1e-7: rotation invariance)."""
    from pyfe3d import Quad4, Quad4Probe

    from windflutter.structure.shell import material_rotation

    angles, t_ply, a, b = (30, -30), 0.005, 1.0, 1.0
    flat = ss_plate(12, a, b, prop=ShellProperty(plies=tuple(Ply(MAT_CLT, t_ply, np.radians(th)) for th in angles)),
                    ss2=True)
    f_flat = modes(assemble(flat), n=1).freq[0]
    A, B, D, h = clt_abd(angles, t_ply, MAT_CLT)
    f_clt = navier_ritz(A, B, D, MAT_CLT.rho * h, a, b)
    R = _rotation()
    nodes = flat.nodes @ R.T
    X = nodes[flat.shell_conn]
    ex = (X[:, 2] - X[:, 0]) + (X[:, 1] - X[:, 3])
    ex /= np.linalg.norm(ex, axis=1, keepdims=True)  # pyfe3d's element x axis, as it computes it
    # the cause: raw pyfe3d with this material vector gives NaN on some elements
    q = Quad4(Quad4Probe())
    x = np.ascontiguousarray(nodes.ravel())
    n_nan = 0
    for e, c in enumerate(flat.shell_conn):
        q.c1, q.c2, q.c3, q.c4 = (int(6 * i) for i in c)
        q.m11, q.m12, q.m21, q.m22 = 1.0, 0.0, 0.0, 1.0
        try:
            q.update_rotation_matrix(x, *ex[e])
            n_nan += not np.isfinite(q.m12)
        except TypeError:  # "Cannot convert 'complex' ... to 'double'" from (1 - cos**2)**0.5
            n_nan += 1
    assert n_nan > 0
    cs = material_rotation(X, ex)
    assert np.all(np.isfinite(cs)) and np.allclose(cs, [1.0, 0.0], atol=1e-12)
    import copy

    aligned = copy.deepcopy(flat)
    aligned.nodes, aligned.spc, aligned.shell_matdir = nodes, {}, ex
    # (b) material axis turned +30 deg about the element normal (pyfe3d's z = (x2 - x4) x (x3 - x1),
    # here R e_z), plies 0 and -60 deg from it: the same laminate in absolute angles
    rot30 = copy.deepcopy(aligned)
    ey = np.cross(R @ [0.0, 0.0, 1.0], ex)
    th = np.radians(30.0)
    rot30.shell_matdir = np.cos(th) * ex + np.sin(th) * ey
    rot30.shell_properties = [ShellProperty(plies=tuple(Ply(MAT_CLT, t_ply, np.radians(t)) for t in (0, -60)))]
    for fe in (aligned, rot30):
        f = _ss_freq_in_local_frame(fe, flat, R)
        assert f == pytest.approx(f_flat, rel=1e-7)
        assert f == pytest.approx(f_clt, rel=0.01)


def test_material_direction_equals_ply_angle():
    """A 30 deg ply with material axis x == a 0 deg ply with material axis at +30 deg about the normal."""
    th = np.radians(30.0)
    p30 = ShellProperty(plies=(Ply(MAT, 0.01, th),))
    p0 = ShellProperty(plies=(Ply(MAT, 0.01, 0.0),))
    fe1 = ss_plate(6, prop=p30)
    fe2 = ss_plate(6, prop=p0)
    fe2.shell_matdir = np.tile([np.cos(th), np.sin(th), 0.0], (len(fe2.shell_conn), 1))
    K1, K2 = assemble(fe1).K, assemble(fe2).K
    assert abs(K1 - K2).max() < 1e-9 * abs(K1).max()
    fe3 = ss_plate(6, prop=ShellProperty(plies=(Ply(MAT, 0.01, -th),)))
    assert abs(assemble(fe3).K - K1).max() > 1e-3 * abs(K1).max()  # the check can fail


def test_free_shell_tube_raises_and_lumped_mass_total():
    from windflutter.errors import ModelError

    R, L, t, E, nu, rho = 0.25, 2.0, 0.005, 210e9, 0.3, 7850.0
    fe, idx = tube(16, 8, R, L, iso(E, nu, rho, t))
    with pytest.raises(ModelError, match="not sufficiently constrained"):
        assemble(fe)
    m_exact = rho * t * L * 16 * 2 * R * np.sin(np.pi / 16)  # facetted (polygonal) tube area
    for kind in ("consistent", "lumped"):
        st = assemble(fe, check=False, shell_mass=kind)
        assert st.total_mass() == pytest.approx(m_exact, rel=1e-10)


def test_modes_interior_shift_and_reduce_complex():
    fe = ss_plate(8, a=1.0, b=0.7)
    st = assemble(fe)
    low = modes(st, n=6).freq
    # shift just above mode 4 (K - sigma M indefinite): the mode nearest the shift is returned
    mid = modes(st, n=1, shift=(2 * np.pi * low[3]) ** 2 * 1.01).freq
    np.testing.assert_allclose(mid, low[3], rtol=1e-8)
    A = (st.K + 1j * st.M).toarray()
    R = st.reduce(A)
    np.testing.assert_allclose(R, (st.Kr + 1j * st.Mr).toarray(), rtol=1e-12, atol=1e-9 * abs(R).max())
