"""The shell blade linearized about its deflected steady state (system/deflected_shell.py,
``OperationalOptions(model="shell", structure="deflected")``): the mesh carried by the steady strip
chain, invariance under a rigid motion, continuity with the undeformed linearization, the
operating point, and (slow) the static deflection against the co-rotational beam."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.linalg as sla

from windflutter.linalg_tools import skew
from windflutter.structure.assembly import assemble_matrices
from windflutter.system.deflected_shell import _deformed_fe, carried_nodes, deflected_shell_blade, station_frames
from windflutter.system.operational import OperationalModel, OperationalOptions

RATED = 12.1 * np.pi / 30
SMALL_MESH = {"n_span": 8, "n_chord": 16, "reference_surface": "outer"}  # the mesh of the tests written for it (Dec 2026)


@pytest.fixture(scope="module")
def shell_model(nrel5mw_turbine):
    """NREL 5 MW shell rotor (hub clamped) on a reduced mesh, linearized about the deflected shape."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the layup is not the 6x6 tables' blade (known, warned)
        om = OperationalModel(nrel5mw_turbine, OperationalOptions(model="shell", part="rotor", mesh=SMALL_MESH,
                                                                  structure="deflected"))
        om.blade(0.0)
    return om


def clamped_frequencies(blade, ksigma, klink, omega, k=6):
    """The hub-clamped blade's lowest frequencies (Hz) and its (shaft rotation stiffness, shaft
    inertia) with the rotating-frame and steady-stress terms."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    st = blade.struct
    K = st.Kr + st.reduce(sp.csr_matrix(ksigma - omega**2 * blade.Kr1))
    w2 = np.sort(spla.eigsh(K.tocsc(), k=k, M=st.Mr.tocsc(), sigma=-1.0, return_eigenvectors=False))
    G = blade.Gamma
    e = np.r_[0.0, 0.0, 0.0, blade.axis]
    Kh = G.T @ (ksigma @ G) - omega**2 * (G.T @ (blade.Kr1 @ G))
    Kh[3:6, 3:6] += klink
    return np.sqrt(w2) / (2 * np.pi), e @ Kh @ e, e @ (G.T @ (st.M @ G)) @ e


def test_at_rest_the_deflected_shell_is_the_undeformed_one(shell_model):
    """No load: the same nodes, stiffness, mass and motion map; no initial stress."""
    rb = shell_model.blade(0.0)
    d = deflected_shell_blade(rb, None, 0.0)
    assert np.array_equal(d.nodes, rb.fe.nodes)
    assert abs(d.blade.struct.K - rb.struct.K).max() <= 1e-12 * abs(rb.struct.K).max()
    assert abs(d.blade.struct.M - rb.struct.M).max() <= 1e-12 * abs(rb.struct.M).max()
    assert abs(d.blade.sections.motion_map - rb.sections.motion_map).max() <= 1e-12
    assert abs(d.ksigma).max() == 0.0 and np.abs(d.klink).max() == 0.0


def test_a_rigid_motion_of_the_frames_moves_the_blade_rigidly(shell_model):
    """Every station frame the same rigid motion (R0, c): each node goes to ``R0 x + c``, and the
    shell re-assembled there (material axes turned) is the undeformed one turned, ``Q K Q^T``
    (the element's frame invariance, 1e-10)."""
    rb = shell_model.blade(0.0)
    n = rb.sections.n_sections + 1
    R0 = sla.expm(skew(np.array([0.3, -0.2, 0.5])))
    c = np.array([1.0, -2.0, 0.5])
    P0 = np.asarray(rb.sections.origin, float)[[0] * n] + np.linspace(0, 60, n)[:, None] * np.array([0, 0, 1.0])
    frames = (P0, P0 @ R0.T + c, np.broadcast_to(R0, (n, 3, 3)).copy(), np.tile([0, 0, 1.0], (n, 1)))
    X = np.asarray(rb.fe.nodes, float)
    x, Rn = carried_nodes(X, frames)
    np.testing.assert_allclose(x, X @ R0.T + c, atol=1e-9)
    _, K = assemble_matrices(rb.fe)
    _, Kd = assemble_matrices(_deformed_fe(rb.fe, x, Rn))
    import scipy.sparse as sp

    Q = sp.kron(sp.identity(2 * rb.fe.n_nodes), sp.csr_matrix(R0), format="csr")
    assert abs(Kd - Q @ K @ Q.T).max() <= 1e-10 * abs(K).max()


def test_nodes_between_stations_follow_the_interpolated_frame():
    """A node a quarter of the way from station 0 to 1 (planes normal to z): its point is the
    quarter point, its rotation a quarter of the relative rotation (about one axis: a quarter of the
    angle); beyond the tip, the tip frame."""
    R1 = sla.expm(skew(np.array([0.0, 0.4, 0.0])))
    frames = (np.array([[0, 0, 0.0], [0, 0, 4.0]]), np.array([[0, 0, 0.0], [1.0, 0, 4.0]]),
              np.stack([np.eye(3), R1]), np.tile([0, 0, 1.0], (2, 1)))
    X = np.array([[0.5, 0.0, 1.0], [0.0, 0.3, 5.0]])
    x, Rn = carried_nodes(X, frames)
    Rq = sla.expm(skew(np.array([0.0, 0.1, 0.0])))
    np.testing.assert_allclose(Rn[0], Rq, atol=1e-12)
    np.testing.assert_allclose(x[0], np.array([0.25, 0, 1.0]) + Rq @ np.array([0.5, 0, 0]), atol=1e-12)
    np.testing.assert_allclose(x[1], np.array([1.0, 0, 4.0]) + R1 @ np.array([0, 0.3, 1.0]), atol=1e-12)


def test_spinning_shell_is_continuous_with_the_undeformed_linearization(shell_model):
    """Centrifugal loads alone: the deflected linearization differs from the undeformed one by the
    second order of the centrifugal deflection -- measured 1e-6 at 0.1 rad/s and 1.5e-4 at rated
    speed on this mesh; tolerances 1e-5 and 1e-3.  The rigid rotation of the blade about the shaft
    has no stiffness in the rotating frame (the centrifugal loads' second-order work, Omega^2 x the
    shaft inertia, cancels the spin softening's): with the complete initial stress (issue 33)
    1.6e-4 (undeformed) and 3e-5 (deflected, rated) of Omega^2 x the shaft inertia, where the
    membrane-only matrix left 1.04 %; tolerance 1e-3 for both."""
    rb = shell_model.blade(0.0)
    for omega, tol in ((0.1, 1e-5), (RATED, 1e-3)):
        kg, kl, _ = rb.unit_prestress()
        f0, k0, _ = clamped_frequencies(rb, kg * omega**2, kl * omega**2, omega)
        d = deflected_shell_blade(rb, None, omega)
        f1, k_shaft, i_shaft = clamped_frequencies(d.blade, d.ksigma, d.klink, omega)
        np.testing.assert_allclose(f1, f0, rtol=tol)
        assert abs(k_shaft) < 1e-3 * omega**2 * i_shaft and abs(k0) < 1e-3 * omega**2 * i_shaft


@pytest.fixture(scope="module")
def shell_point(shell_model):
    om = shell_model
    omega, pitch = om.operating_point(11.0)
    rb = om.blade(pitch)
    st = om.steady(rb, 11.0, omega)
    return rb, st, deflected_shell_blade(rb, st, omega), omega


def test_the_mesh_follows_the_shell_steady_state(shell_point):
    """At 11 m/s the carried nodes against the shell's own linear displacement ``u``: the same
    motion up to the second order of the rotations and the sections' own deformation (measured
    3.8 % of the largest motion, 2.9 m; tolerance 6 %), and each station's ring of skin nodes at its
    steady frame: the strip points refitted from the carried nodes are the steady strips' points
    (the moderate-rotation chain; measured 0.25 mm, tolerance 2 mm)."""
    rb, st, d, _ = shell_point
    u = st.u.reshape(-1, 6)[:, :3]
    moved = d.nodes - np.asarray(rb.fe.nodes, float)
    assert np.abs(moved - u).max() < 0.06 * np.abs(u).max()
    fit = (rb.sections.motion_map @ np.hstack([moved, np.zeros_like(moved)]).ravel()).reshape(-1, 6)
    shift = np.asarray(st.sections.origin) - np.asarray(rb.sections.origin)
    assert np.abs(fit[:, :3] - shift).max() < 2e-3


def test_deflected_shell_operating_point(shell_point, shell_model):
    """The operating point on the deflected shell: stable (no mode below 3 Hz with negative damping),
    the blade's clamped structure positive definite, and the same modes as the undeformed
    linearization within 8 % in frequency (the deflection moves the edge modes most)."""
    from windflutter.system.modes import point_modes

    om = shell_model
    ps = om.at(11.0)
    M, K = ps.blade_structure
    e = slice(6, None)
    assert np.all(sla.eigh(K[e, e], M[e, e], eigvals_only=True) > 0)
    modes = [m for m in point_modes(ps, max_hz=3.0) if not m.rigid]
    assert modes and all(m.damping_ratio > 0 for m in modes)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        om0 = OperationalModel(om.turbine, OperationalOptions(model="shell", part="rotor", mesh=SMALL_MESH,
                                                              structure="undeformed"))
        ps0 = om0.at(11.0)
    f0 = sorted(m.frequency_hz for m in point_modes(ps0, max_hz=3.0) if not m.rigid)
    f1 = sorted(m.frequency_hz for m in modes)
    n = min(len(f0), len(f1), 8)
    np.testing.assert_allclose(f1[:n], f0[:n], rtol=0.08)


def test_turned_element_blocks_are_the_elements_of_a_rigidly_turned_mesh(shell_model):
    """``turned_blocks``: the undeformed elements' stiffness and mass turned by one rotation, assembled
    on the turned nodes, are pyfe3d's elements computed there (material axes turned) -- the element's
    frame invariance, to round-off (1e-10 of the largest entry; a transposed rotation fails it)."""
    from windflutter.structure.assembly import assemble
    from windflutter.structure.shell import turned_blocks

    rb = shell_model.blade(0.0)
    R0 = sla.expm(skew(np.array([0.3, -0.2, 0.5])))
    n = rb.fe.n_nodes
    fe_t = _deformed_fe(rb.fe, np.asarray(rb.fe.nodes, float) @ R0.T, np.broadcast_to(R0, (n, 3, 3)).copy())
    Re = np.broadcast_to(R0, (len(rb.fe.shell_conn), 3, 3))
    st = assemble(fe_t, check=False, shell_blocks=[turned_blocks(B, Re) for B in rb.shell_blocks()])
    M, K = assemble_matrices(fe_t)
    assert abs(st.K - K).max() <= 1e-10 * abs(K).max()
    assert abs(st.M - M).max() <= 1e-10 * abs(M).max()
    st_wrong = assemble(fe_t, check=False, shell_blocks=[turned_blocks(B, np.swapaxes(Re, 1, 2))
                                                         for B in rb.shell_blocks()])
    assert abs(st_wrong.K - K).max() > 1e-3 * abs(K).max()


def test_a_pitched_blades_elements_are_the_pitch_zero_ones_turned(shell_model):
    """A pitched blade is the pitch-0 one turned (``system/pitch.py``): its element blocks, the pitch-0
    blocks turned by the pitch rotation, are pyfe3d's elements on the pitched mesh (1e-10)."""
    from windflutter.structure.shell import shell_element_blocks

    rb = shell_model.blade(np.radians(12.0))
    for mine, ref in zip(rb.shell_blocks(), shell_element_blocks(rb.fe)):
        assert np.abs(mine - ref).max() <= 1e-10 * np.abs(ref).max()


def test_deflected_shell_elements_are_carried_with_their_rotations(shell_point):
    """At 11 m/s the deflected blade's elements are the undeformed ones turned: its mass (the
    rigid-body mass about the apex: total mass and first moments along the turned span) is the
    undeformed blade's to round-off, where pyfe3d's elements computed again on the carried nodes
    (``reassemble=True``, the route before 6 Dec 2026) change it with the elements' stretch (measured
    +4.9e-5); the two routes' six lowest clamped frequencies agree to the order of the strains
    (measured 4e-4 to 6e-4; tolerance 0.5 %)."""
    rb, st, d, omega = shell_point
    d_re = deflected_shell_blade(rb, st, omega, reassemble=True)
    mass = [float(b.Gamma[:, 0] @ (b.struct.M @ b.Gamma[:, 0])) for b in (rb, d.blade, d_re.blade)]
    assert mass[1] == pytest.approx(mass[0], rel=1e-12)
    assert abs(mass[2] / mass[0] - 1) > 1e-9
    f, _, _ = clamped_frequencies(d.blade, d.ksigma, d.klink, omega)
    f_re, _, _ = clamped_frequencies(d_re.blade, d_re.ksigma, d_re.klink, omega)
    np.testing.assert_allclose(f, f_re, rtol=5e-3)


@pytest.mark.slow
def test_iea22mw_shell_static_deflection_against_the_corotational_beam():
    """IEA 22 MW at 11 m/s (near rated): the shell blade's steady tip flap on the seed's mesh (30
    span elements, skin on the outer mould line) against the co-rotational beam's (the windIO 6x6
    tables) within 8 % (measured +7.3 %: 21.93 m against 20.44 m; +5.5 %, 21.57 m, with the
    membrane-only initial stress, whose hoop term stiffened this coarse mesh's centrifugal state:
    issue 33, docs/structure.md).  The tolerance is the data's, not the solver's: on the converged
    default mesh (skin on the laminate midsurface) the shell deflects +10.0 % (22.48 m): its own section
    properties (windflutter beam-properties, docs/mesh.md) are 2-8 % softer in flap than the 6x6
    tables at 25-85 % span and 25 % softer at 10 % span, the root transition: against the beam of
    those properties it is within 1.4 % (tests/system/test_shell_same_blade.py).  The
    elastic tip twist is NOT compared: -3.5 deg against -5.4 deg, the layup's torsion and
    bend--twist coupling against the 6x6 tables' (docs/steady_state.md)."""
    from windflutter.mesh.settings import SEED_MESH
    from windflutter.model import load_turbine

    t = load_turbine("iea22mw")
    flap = {}
    for model in ("beam", "shell"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            om = OperationalModel(t, OperationalOptions(model=model, part="rotor",
                                                        mesh=dict(SEED_MESH) if model == "shell" else {}))
            omega, pitch = om.operating_point(11.0)
            st = om.steady(om.blade(pitch), 11.0, omega)
        flap[model] = st.tip_flap
    assert flap["shell"] == pytest.approx(flap["beam"], rel=0.08)


@pytest.mark.slow
def test_iea22mw_shell_second_edge_fw_damping_follows_the_beam():
    """The issue's case: the IEA 22 MW shell's 2nd edge FW at 8-13 m/s.  Linearized about the
    undeformed blade it lost its damping (1.0, 0.1, -0.6 % at 8, 9, 10 m/s); about the deflected
    shape it is positive, within issue 33's band of the beam model's (1 point or 35 %) at 8 and 13
    m/s, and no mode below 2 Hz
    but the drivetrain's free rotation has negative damping.  Measured: on the seed's 30-element
    outer-surface mesh 1.9-2.3 % against the beam's 1.7-2.1 %; on the converged default mesh, with the
    files' damping per direction (system/damping.py ``shell_modal_damping``), 1.69 / 3.93 / 1.89 %
    against 1.71 / 2.04 / 1.94 % at 8 / 10 / 13 m/s.  At 10 m/s the shell's mode of that name is a
    mixed one (2nd edge FW + 2nd tower fore-aft, its share 0.18, against the beam's 0.82), in a
    cluster of tower and heavily damped flap modes at 1.35-1.78 Hz that the beam does not have
    there: only its sign is checked at 10 m/s (with the earlier ``beta K`` damping, the flap's
    ``mu`` on every direction, it was 2.75 %)."""
    from windflutter.model import load_turbine
    from windflutter.system.modes import point_modes

    got = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = load_turbine("iea22mw")
        models = {m: OperationalModel(t, OperationalOptions(model=m, structure="deflected")) for m in ("beam", "shell")}
        for V in (8.0, 10.0, 13.0):
            z = {}
            for m, om in models.items():
                modes = point_modes(om.at(V), max_hz=2.0)
                assert all(x.damping_ratio > 0 for x in modes if not x.rigid and x.family != "drivetrain"), (m, V)
                fw = [x for x in modes if x.family == "edge" and x.order == 2 and x.whirl == "FW"]
                z[m] = fw[0].damping_ratio
            got[V] = z
    print(got)
    for V, z in got.items():
        d = abs(z["shell"] - z["beam"])
        assert z["shell"] > 0 and (V == 10.0 or d <= 0.01 or d <= 0.35 * z["beam"]), (V, got)
