"""The operating-point model and `windflutter campbell`: pitch as a rotation, mode names and whirl,
the JSON of the command, no instability in operation (NREL 5 MW, reduced mesh)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry
from windflutter.structure.assembly import assemble
from windflutter.system.pitch import pitch_rotation, rotate_blade


@pytest.mark.parametrize("model, kw", [("beam", {"n_span": 8}), ("shell", {"n_span": 4, "n_chord": 10})])
def test_pitch_rotation_equals_the_model_built_at_that_pitch(nrel5mw_turbine, model, kw):
    """Turning the assembled pitch-0 blade about its pitch axis gives the model meshed at the pitch:
    the same nodes, matrices and strips (round-off)."""
    tb = nrel5mw_turbine
    g = rotor_geometry(tb)
    th = np.radians(14.0)
    fe0, s0 = build_model(tb, MeshSettings(model=model, part="rotor_blade", **kw))
    fe1, s1 = build_model(tb, MeshSettings(model=model, part="rotor_blade", pitch=th, **kw))
    st1 = assemble(fe1)
    R, root = pitch_rotation(tb, th)
    fe2, st2, s2 = rotate_blade(fe0, assemble(fe0), s0, R, root, g.hub_center, g.shaft_axis)
    assert np.allclose(fe2.nodes, fe1.nodes, atol=1e-12)
    for a, b in ((st2.M, st1.M), (st2.K, st1.K), (s2.motion_map, s1.motion_map)):
        assert abs(a - b).max() <= 1e-12 * abs(b).max()
    for k in ("origin", "e_chord", "e_span", "radius"):
        assert np.allclose(getattr(s2, k), getattr(s1, k), atol=1e-12)
    # the constraints too (the shell tip's rib): both maps span the same motions
    assert len(fe1.diaphragms) == (model == "shell")
    T1, T2 = st1.T.toarray(), st2.T.toarray()
    assert T1.shape == T2.shape
    np.testing.assert_allclose(T1 @ np.linalg.lstsq(T1, T2, rcond=None)[0], T2, atol=1e-10)


@pytest.fixture(scope="module")
def nrel_campbell(nrel5mw_turbine):
    from windflutter.system.campbell import campbell
    from windflutter.system.operational import OperationalOptions

    return campbell(nrel5mw_turbine, [6.0, 12.0, 18.0], OperationalOptions(mesh={"n_span": 10}), max_hz=2.2)


def test_campbell_names_and_whirl(nrel_campbell):
    """At each point the named modes are unique, the cyclic pairs come as BW below FW around the
    collective, and the tower's first modes are at the NREL 5 MW values (Jonkman 2009, table 9-1:
    fore-aft 0.324 Hz, side-side 0.312 Hz with the same tower; here the 1st side-side, 5 %)."""
    for p in nrel_campbell.points:
        names = [m.name for m in p.modes]
        assert len(set(names)) == len(names)
        by = {m.name: m for m in p.modes}
        for fam in ("flap", "edge"):
            bw, fw = by.get(f"1st {fam} BW"), by.get(f"1st {fam} FW")
            assert bw is not None and fw is not None and bw.frequency_hz < fw.frequency_hz
        assert by["1st tower side-side"].frequency_hz == pytest.approx(0.312, rel=0.05)
        assert by["1st tower fore-aft"].frequency_hz == pytest.approx(0.324, rel=0.05)


def test_no_instability_in_operation(nrel_campbell):
    """Both reference codes find every mode of a healthy turbine damped in operation; so must we
    (the drivetrain's free rigid-body root excluded)."""
    assert nrel_campbell.unstable() == []
    p, m = nrel_campbell.least_damped()
    assert 0 < m.damping_ratio < 0.05 and m.family in ("edge", "tower_ss")


def test_campbell_cli_json_is_exactly_the_documented_schema(capsys):
    from windflutter.cli import main

    assert main(["campbell", "nrel5mw", "--wind-speeds", "11", "--n-span", "8", "--max-hz", "1.5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) == {"turbine", "part", "frame", "points"} and out["frame"] == "ground-fixed"
    (pt,) = out["points"]
    assert set(pt) == {"wind_speed", "rotor_speed_rpm", "pitch_deg", "modes"}
    keys = {"name", "family", "order", "whirl", "frequency_hz", "damped_frequency_hz", "damping_ratio", "share",
            "mixed", "heavily_damped", "participation_1", "participation_1_share", "participation_2",
            "participation_2_share"}
    assert pt["modes"] and all(set(m) == keys for m in pt["modes"])
    assert {m["whirl"] for m in pt["modes"]} <= {"BW", "FW", "collective", "asymmetric", "none"}
    assert {m["family"] for m in pt["modes"]} <= {"flap", "edge", "torsion", "tower_fa", "tower_ss", "tower_torsion",
                                                  "drivetrain", "rigid", "mixed"}
    for m in pt["modes"]:
        assert m["damped_frequency_hz"] <= m["frequency_hz"] + 1e-12


def test_tower_frequencies_do_not_droop_with_rotor_speed(nrel5mw_turbine):
    """A rotating-frame pitfall (OpenFAST issue 3394): linearized in the rotating frame without
    multi-blade coordinates, the tower modes 'droop' with rotor speed.  In the ground-fixed frame the
    1st tower fore-aft and side-side frequencies (structure only) stay within 1 % of standstill at
    rated and within 2 % at 1.5 x rated.  What moves them is physical: the backward-whirl flap mode
    comes down towards them as the rotor speeds up (0.63 -> 0.46 Hz) and couples through the tower-top
    tilt and yaw (measured: fore-aft -0.6 % at rated, -1.3 % at 18 RPM; side-side < 0.1 %)."""
    from windflutter.system.modes import point_modes
    from windflutter.system.operational import OperationalModel, OperationalOptions

    om = OperationalModel(nrel5mw_turbine, OperationalOptions(mesh={"n_span": 8}, aero=None, damping="none"))

    def tower(rpm):
        by = {m.name: m.frequency_hz for m in point_modes(om.at(10.0, rpm=rpm, pitch=0.0), max_hz=0.5)}
        return by["1st tower fore-aft"], by["1st tower side-side"]

    f0 = np.array(tower(0.0))
    for rpm, tol in ((12.1, 0.01), (18.0, 0.02)):
        assert np.allclose(tower(rpm), f0, rtol=tol)


def test_undeformed_linearization_reads_the_steady_states_own_stress(nrel5mw_turbine):
    """The undeformed-axis linearization takes its hub-link forces and axial-force geometric
    stiffness from the steady state's stress (``SteadyState.f_internal``, ``Ksigma``).  Of the
    co-rotational steady state (the default) they must be its beams' forces: ``f_internal - load``
    vanishes away from the root (equilibrium, to the iteration's 1e-6) and its resultant at the root
    balances the applied loads.  And the modes must not depend on which of the two steady theories
    gave the state (tip flap 2.133 against 2.133 m here): measured at 6 m/s within 0.2 % in
    frequency and 0.1 point of damping ratio; held to 1 % and 1 point.  Before the stress was read
    from the state, ``Ksigma`` of the co-rotational state came from the linear strains of its
    large-rotation ``u`` and gave a 1st flap FW at Re(lambda) = +1.8 1/s (this test then fails)."""
    from windflutter.system.modes import point_modes
    from windflutter.system.operational import OperationalModel, OperationalOptions

    modes, states = {}, {}
    for corot in (True, False):
        om = OperationalModel(nrel5mw_turbine, OperationalOptions(mesh={"n_span": 10}, corotational=corot))
        ps = om.at(6.0)
        assert (ps.steady.configuration is not None) == corot
        states[corot] = (ps.blade, ps.steady)
        modes[corot] = {m.name: m for m in point_modes(ps, max_hz=2.2) if not m.rigid}
    rb, st = states[True]
    r = (st.f_internal - st.load).reshape(-1, 6)
    root = np.unique(np.concatenate([np.asarray(lk.dependent) for lk in rb.fe.rigid_links
                                     if int(lk.independent) == int(rb.hub_node)]))
    away = np.setdiff1d(np.arange(rb.fe.n_nodes), np.append(root, rb.hub_node))
    scale = np.abs(st.load.reshape(-1, 6)[:, :3]).sum(axis=0).max()
    assert np.abs(r[away, :3]).max() <= 1e-5 * scale
    total = st.load.reshape(-1, 6)[:, :3].sum(axis=0)
    assert np.allclose(r[root, :3].sum(axis=0), -total, atol=1e-5 * scale)  # (the beams' f_int sums to 0)
    assert set(modes[True]) == set(modes[False])
    for name, m in modes[True].items():
        ref = modes[False][name]
        assert m.eigenvalue.real < 0, name
        assert m.frequency_hz == pytest.approx(ref.frequency_hz, rel=0.01), name
        assert m.damping_ratio == pytest.approx(ref.damping_ratio, abs=0.01), name


def test_multiblade_amplitudes_split_the_whirl():
    """HAWCStab2's amplitude components from the tip motion in multi-blade coordinates: a cyclic pair
    ``a_c cos psi + a_s sin psi`` with ``a_s = -i a_c`` is all forward whirl (``|a_c + i a_s| =
    2 |a_c|``, HAWCStab2's count: twice the blade's whirl amplitude), with ``a_s = +i a_c`` all
    backward; the collective is ``|a_0|``; torsion in rad as given."""
    from windflutter.system.modes import ModeRecord

    tip = np.zeros((3, 3), complex)
    tip[0] = [0.0, 2.0, -2.0j]  # flap: forward whirl of amplitude 2
    tip[1] = [0.5, 1.0, 1.0j]  # edge: collective 0.5 and backward whirl 1
    tip[2] = [0.0, 0.1, 0.0]  # torsion: a standing cyclic motion, half forward, half backward
    a = ModeRecord(1j, "flap", "FW", tip=tip, tower_top=np.array([0.3, -0.4j, 0.0])).multiblade_amplitudes()
    assert a["fw_flap"] == pytest.approx(4.0) and a["bw_flap"] == pytest.approx(0.0, abs=1e-15)
    assert a["sym_edge"] == pytest.approx(0.5) and a["bw_edge"] == pytest.approx(2.0) and a["fw_edge"] == pytest.approx(0.0, abs=1e-15)
    assert a["bw_tors"] == pytest.approx(0.1) and a["fw_tors"] == pytest.approx(0.1)
    assert a["tower_fa"] == pytest.approx(0.3) and a["tower_ss"] == pytest.approx(0.4)
    assert ModeRecord(1j, "tower_fa", "none").multiblade_amplitudes() is None


def test_amp_file_holds_the_cmb_modes_amplitudes(nrel_campbell, tmp_path):
    """The .amp beside the .cmb: read as HAWCStab2's own (docs/scripts/extract_hawcstab2_modes.py:
    ``row[1:].reshape(n_modes, 30)``), column k is the .cmb's mode k at every wind speed -- its
    magnitudes those of the mode's multi-blade components over their largest (the tower yaw too), NaN
    for the shaft, and a mode's largest magnitude 1 with phase 0."""
    from windflutter.post.campbell_amp import write_amp
    from windflutter.post.campbell_export import cmb_tracks, read_cmb, write_cmb

    cmb = read_cmb(write_cmb(nrel_campbell, tmp_path / "t.cmb"))
    amp = np.loadtxt(write_amp(nrel_campbell, tmp_path / "t.amp"), comments="#")
    n = cmb.frequency.shape[1]
    assert amp.shape == (3, 1 + 30 * n)
    np.testing.assert_array_equal(amp[:, 0], cmb.wind_speed)
    order, keep = cmb_tracks(nrel_campbell)
    assert len(keep) == n
    mag = amp[:, 1:].reshape(3, n, 15, 2)
    for r, i in enumerate(order):
        pt = nrel_campbell.points[i]
        for c, t in enumerate(keep):
            k = nrel_campbell.tracks[t].index[i]
            if k < 0:
                assert np.all(np.isnan(mag[r, c])) and np.isnan(cmb.frequency[r, c])
                continue
            m = pt.modes[k]
            assert cmb.frequency[r, c] == pytest.approx(m.damped_frequency_hz, rel=1e-8)
            a = m.multiblade_amplitudes()
            top = max(a.values())
            np.testing.assert_allclose(mag[r, c, 6:, 0], [a[x] / top for x in ("sym_edge", "bw_edge", "fw_edge",
                                       "sym_flap", "bw_flap", "fw_flap", "sym_tors", "bw_tors", "fw_tors")], rtol=1e-5)
            assert mag[r, c, 2, 0] == pytest.approx(a["tower_yaw"] / top, rel=1e-5)  # TWR yaw
            assert np.all(np.isnan(mag[r, c, 3:6])) and np.nanmax(mag[r, c, :, 0]) == pytest.approx(1.0)
            j = int(np.nanargmax(mag[r, c, :, 0]))
            assert mag[r, c, j, 1] == pytest.approx(0.0, abs=1e-6)


def test_blade_modes_refined_from_the_last_point_equal_a_fresh_solve(nrel5mw_turbine, monkeypatch):
    """The shell blade's fixed-interface modes at the next rotor speed are refined by subspace
    iteration from the last point's (``system.blade_basis.BladeBasis``).  Driven here on the beam
    blade (the sparse path forced by ``DENSE_BASIS_LIMIT = 0``): the named modes of the point equal
    those of the dense path (LAPACK on the same matrices, shares nothing with the refinement) to
    1e-5 in frequency and 1e-6 in damping ratio (the refinement's 1e-2 on the highest basis mode
    moves the low modes far less; measured 1e-8), the refinement was used, and after
    ``restart_modes`` the modes are the cold-started ones (a map's wind speed does not depend on
    what its worker ran before)."""
    import windflutter.solve.symmetric as red
    import windflutter.system.blade_basis as bb
    import windflutter.system.operational as opm
    from windflutter.system.modes import point_modes

    opts = opm.OperationalOptions(mesh={"n_span": 10})

    def named(ps):
        return {m.name: m for m in point_modes(ps, max_hz=2.2) if not m.rigid}

    ref = named(opm.OperationalModel(nrel5mw_turbine, opts).at(8.0, rpm=13.0, pitch=0.0))
    calls = []
    orig = red.refine_modes
    monkeypatch.setattr(red, "refine_modes", lambda *a, **k: calls.append(orig(*a, **k)) or calls[-1])
    monkeypatch.setattr(bb, "DENSE_BASIS_LIMIT", 0)
    om = opm.OperationalModel(nrel5mw_turbine, opts)
    om.at(8.0, rpm=12.0, pitch=0.0)
    warm = named(om.at(8.0, rpm=13.0, pitch=0.0))
    assert len(calls) == 1 and calls[0] is not None
    assert set(warm) == set(ref)
    for name, m in ref.items():
        assert warm[name].frequency_hz == pytest.approx(m.frequency_hz, rel=1e-5), name
        assert warm[name].damping_ratio == pytest.approx(m.damping_ratio, abs=1e-6), name
    om.restart_modes()
    again = named(om.at(8.0, rpm=13.0, pitch=0.0))
    cold = named(opm.OperationalModel(nrel5mw_turbine, opts).at(8.0, rpm=13.0, pitch=0.0))
    assert len(calls) == 1  # no refinement after the restart: the modes of a cold start
    for name, m in cold.items():  # (the steady state's own warm start leaves 1e-12)
        assert abs(again[name].eigenvalue - m.eigenvalue) <= 1e-9 * abs(m.eigenvalue), name


def test_the_support_basis_is_the_same_in_every_model(nrel5mw_turbine):
    """Two models of the same turbine have the same support basis bit for bit, so a point's reduced
    matrices do not depend on the process or on what ran before (the support's Lanczos start is fixed;
    ARPACK's random one gave each model its own rotation of the shell tower's degenerate wall pairs:
    on the NREL 5 MW shell turbine the reduced matrices differed by 3e-3 of their largest entry; this
    test fails with it)."""
    from windflutter.system.operational import OperationalModel, OperationalOptions

    shell = OperationalOptions(model="shell", mesh={"n_span": 6, "n_chord": 12})  # a shell tower: degenerate pairs
    a, b = (OperationalModel(nrel5mw_turbine, shell).support() for _ in range(2))
    assert a.expand.shape[1] > 10
    assert np.array_equal(np.asarray(a.expand), np.asarray(b.expand))
    assert np.array_equal(a.K, b.K) and np.array_equal(a.M, b.M)
