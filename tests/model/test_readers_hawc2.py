"""HAWC2 reader against independent data: the ElastoDyn and BeamDyn files of the same NREL 5 MW,
closed-form section matrices, the IEA 15 MW model's own comments on its Euler angles, and the
windIO-built model (natural frequencies, with the data differences traced)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from windflutter.mesh.analysis import turbine_modes
from windflutter.mesh.settings import MeshSettings
from windflutter.model.beamdyn import read_beamdyn_blade
from windflutter.model.beamprops import beamdyn_to_section
from windflutter.model.bundled import DATA_DIR
from windflutter.model.hawc2_beam import hawc2_mass, hawc2_stiffness
from windflutter.model.hawc2_bodies import _euler
from windflutter.model.hawc2_files import read_st

H2 = DATA_DIR / "nrel5mw" / "hawc2"


def test_geometry_and_masses_equal_the_elastodyn_values(turbine):
    """Tilt, cone, overhang, Twr2Shft, hub radius, tower height, masses, nacelle CG, yaw inertia
    about the CG, generator inertia and drivetrain stiffness recovered from the placed HAWC2
    bodies equal the ElastoDyn inputs they were written from (and HAWC2's shaft G I_p / L equals
    DTTorSpr, independently: 0.01 %)."""
    t = turbine("nrel5mw_hawc2")
    n, h = t.nacelle, t.hub
    assert np.degrees(n.shaft_tilt) == pytest.approx(5.0, abs=1e-9)
    assert np.degrees(h.precone) == pytest.approx(2.5, abs=1e-9)
    assert n.overhang == pytest.approx(-5.0191, abs=1e-9) and n.tower_to_shaft == pytest.approx(1.96256, abs=1e-9)
    assert h.radius == pytest.approx(1.5, abs=1e-9) and t.tower.top_z == pytest.approx(87.6)
    assert t.hub_height == pytest.approx(90.0, abs=1e-5)
    assert h.mass == pytest.approx(56780.0, abs=10.0)  # + 5 kg of distributed shaft/hub body mass
    assert h.inertia[0, 0] == pytest.approx(115926.0, rel=1e-6)
    assert n.mass == pytest.approx(240000.0, rel=1e-6)
    np.testing.assert_allclose(n.cg, [1.9, 0.0, 1.75], atol=1e-6)
    assert n.inertia[2, 2] == pytest.approx(2.60789e6 - 240000 * 1.9**2, rel=1e-6)
    assert n.generator_inertia == pytest.approx(534.116 * 97**2) and n.gear_ratio == 1.0
    assert n.drivetrain_torsional_stiffness == pytest.approx(8.67637e8, rel=1e-4)
    assert t.operating_curve is not None and t.operating_curve.source.startswith("HAWCStab2")


def test_st_sections_equal_the_beamdyn_file():
    """The reader's 6x6 about the c2 line, with the offsets taken out again (Schur complements of
    EA and of the shear terms), gives BeamDyn's EA, edgewise and flapwise EI and GJ station by
    station (two formats of the NREL 5 MW blade; the st file has 3-4 digits: 0.2 %)."""
    st = read_st(H2 / "data" / "NREL_5MW_st.txt", 5, 1)
    K = hawc2_stiffness(st)
    bd, _ = read_beamdyn_blade(DATA_DIR / "nrel5mw" / "NRELOffshrBsline5MW_BeamDyn_Blade.dat", None, 61.5)
    from windflutter.model.blade import PERM_BEAMDYN_TO_SECTION as P

    Kbd = np.empty_like(bd.stiffness)
    Kbd[:, P[:, None], P[None, :]] = bd.stiffness  # back to BeamDyn order
    np.testing.assert_allclose(st["r"] / 61.5, bd.s, atol=5e-3)
    ea = K[:, 2, 2]
    ei_edge = K[:, 3, 3] - K[:, 2, 3] ** 2 / ea
    ei_flap = K[:, 4, 4] - K[:, 2, 4] ** 2 / ea
    gj = K[:, 5, 5] - K[:, 0, 5] ** 2 / K[:, 0, 0] - K[:, 1, 5] ** 2 / K[:, 1, 1]
    for got, j in ((ea, 2), (ei_edge, 3), (ei_flap, 4), (gj, 5)):
        np.testing.assert_allclose(got, Kbd[:, j, j], rtol=5e-3)


def test_section_matrices_closed_form():
    """One station with offsets, against hand formulas (BeamDyn axes x_bd = y_h2, y_bd = -x_h2):
    K34 = EA y_C, K35 = -EA x_C, K44 = EI_edge + EA y_C^2, K66 = GJ + kGA (x_S^2 + y_S^2) terms;
    a 90 deg structural pitch swaps the principal EIs; the mass matrix's polar inertia about the
    reference = m (ri_x^2 + ri_y^2) - m |CG - EC|^2 + m |CG|^2 and it is positive semi-definite."""
    st = {k: np.array([v]) for k, v in dict(r=0.0, m=300.0, x_cg=0.3, y_cg=0.05, ri_x=0.4, ri_y=1.1, x_sh=0.2,
                                             y_sh=0.02, E=1e10, G=4e9, I_x=0.1, I_y=0.5, I_p=0.2, k_x=0.6, k_y=0.8,
                                             A=0.3, pitch=0.0, x_e=0.5, y_e=0.1).items()}
    K = hawc2_stiffness(st)[0]
    EA, xc, yc = 1e10 * 0.3, 0.1, -0.5  # elastic centre in BeamDyn axes
    assert K[2, 3] == pytest.approx(EA * yc) and K[2, 4] == pytest.approx(-EA * xc)
    assert K[3, 3] == pytest.approx(1e10 * 0.5 + EA * yc**2)
    assert K[4, 4] == pytest.approx(1e10 * 0.1 + EA * xc**2)
    xs, ys = 0.02, -0.2
    assert K[5, 5] == pytest.approx(4e9 * 0.2 + 0.8 * 4e9 * 0.3 * ys**2 + 0.6 * 4e9 * 0.3 * xs**2)
    rot = dict(st, pitch=np.array([90.0]), x_e=np.array([0.0]), y_e=np.array([0.0]))
    Kr = hawc2_stiffness(rot)[0]
    assert Kr[3, 3] == pytest.approx(1e10 * 0.1) and Kr[4, 4] == pytest.approx(1e10 * 0.5)
    M = hawc2_mass(st)[0]
    gx, gy = 0.05, -0.3
    dc = (gx - 0.1) ** 2 + (gy + 0.5) ** 2
    assert M[5, 5] == pytest.approx(300 * (0.4**2 + 1.1**2) - 300 * dc + 300 * (gx**2 + gy**2))
    assert M[0, 5] == pytest.approx(-300 * gy) and M[1, 5] == pytest.approx(300 * gx)
    assert np.linalg.eigvalsh(M).min() > -1e-9 * np.abs(M).max()


def test_euler_chain_reads_the_iea15mw_comments():
    """The IEA 15 MW htc (IEAWindTask37) comments its orientation: connector 'mbdy2_eulerang 90 0
    0; 6 0 0' gives 'zC along shaft upwind' (raised 6 deg); hub1 '-90 0 0; 0 180 0; 4 0 0' gives
    'zH along blade' (blade 1 up), coned 4 deg upwind, 'xH towards LE'.  HAWC2 global frame: y
    downwind, z down."""
    conn = _euler([(["90", "0", "0"], ""), (["6", "0", "0"], "")], None)
    z = conn[:, 2]
    assert z[1] < 0 and np.degrees(np.arcsin(-z[2])) == pytest.approx(6.0)  # upwind and up
    hub = conn @ _euler([(["-90", "0", "0"], ""), (["0", "180", "0"], ""), (["4", "0", "0"], "")], None)
    zb = hub[:, 2]
    assert zb[2] < -0.99  # pointing up
    assert np.degrees(np.arcsin(zb @ z)) == pytest.approx(4.0, abs=1e-9)  # coned towards upwind
    assert hub[:, 0] @ np.array([-1.0, 0.0, 0.0]) == pytest.approx(1.0)  # xH: towards the LE of blade 1


def _blade_modes(t):
    return turbine_modes(t, MeshSettings(model="beam", part="blade"), n_modes=5).frequencies_hz


def test_blade_frequencies_with_the_data_differences_traced(turbine):
    """Blade-alone beam modes (1st/2nd/3rd flap, 1st/2nd edge) of the HAWC2-built NREL 5 MW vs the
    windIO-built one.  As read they are 2-13 % lower: the HAWC2 st file has shear factors k = 0.5
    where BeamDyn's shear stiffness corresponds to k = 1.4 (openfast_toolbox's README of these
    files says so), chordwise CG offsets BeamDyn does not have, and 0.8 % more mass.  With k = 1.4,
    the CG on the elastic centre and the windIO model's blade mass the differences are below
    1 % - within the issue's 2 % - so what remains is the readers' business."""
    w = _blade_modes(turbine("nrel5mw"))
    h = turbine("nrel5mw_hawc2")
    as_read = _blade_modes(h) / w - 1
    assert np.all(as_read < -0.015) and as_read.min() > -0.15
    st = dict(read_st(H2 / "data" / "NREL_5MW_st.txt", 5, 1))
    st["k_x"] = st["k_y"] = np.full(st["m"].size, 1.4)
    st["x_cg"], st["y_cg"] = st["x_e"], st["y_e"]
    st["m"] = st["m"] * turbine("nrel5mw").blade.beam.total_mass / h.blade.beam.total_mass
    K, M = beamdyn_to_section(hawc2_stiffness(st), hawc2_mass(st))
    bp = dataclasses.replace(h.blade.beam, stiffness=K, mass=M)
    matched = _blade_modes(dataclasses.replace(h, blade=dataclasses.replace(h.blade, beam=bp)))
    np.testing.assert_allclose(matched, w, rtol=0.02)
    assert np.max(np.abs(matched / w - 1)) < 0.01


def test_continue_in_file_is_relative_to_the_model_folder(tmp_path):
    """HAWC2 runs from the model folder (the parent of ``htc/``): a ``continue_in_file
    ./data/x.htc`` in ``htc/model.htc`` names ``model/data/x.htc``, as every other file name does
    (the IEA 15 MW model's layout).  The aero block moved into such an include reads the same
    turbine as the single file."""
    from windflutter.model import load_turbine

    htc = _model_copy(tmp_path)
    d = htc.parent.parent
    text = htc.read_text()
    i, j = text.index("begin aero"), text.index("end aero")
    j = text.index(";", j) + 1
    (d / "data" / "aero_block.htc").write_text(text[i:j] + "\nexit;\n")
    htc.write_text(text[:i] + "continue_in_file ./data/aero_block.htc ;\n" + text[j:])
    a, b = load_turbine(H2 / "htc" / "NREL_5MW.htc", validate=False), load_turbine(htc, validate=False)
    np.testing.assert_array_equal(a.blade.chord, b.blade.chord)
    assert a.n_blades == b.n_blades and sorted(a.airfoils) == sorted(b.airfoils)


def _model_copy(tmp_path):
    """The htc of a copy of the bundled HAWC2 model in ``tmp_path/model`` (its folder layout kept,
    the operational data file the htc names beside it)."""
    import shutil

    shutil.copytree(H2, tmp_path / "model")
    for f in H2.parent.glob("NREL5MW_hawc2*"):
        shutil.copy(f, tmp_path)
    return tmp_path / "model" / "htc" / "NREL_5MW.htc"


def _model_with(tmp_path, old: str, new: str):
    """A copy of the bundled HAWC2 model with one htc line replaced."""
    htc = _model_copy(tmp_path)
    text = htc.read_text()
    assert old in text
    htc.write_text(text.replace(old, new))
    return htc


def test_blade_damping_is_the_blade_bodys_damping_aniso(turbine, tmp_path):
    """The blade body's ``damping_aniso`` (kx flapwise, ky edgewise, kz torsion: the IEA 15 MW HAWC2
    model's comment says its 3.038e-3 / 2.167e-3 are "tuned to 3 % log dec flap/edge", and its
    BeamDyn file has 2.99e-3 / 2.19e-3 for flap / edge bending) becomes the stiffness-proportional
    mu of the same directions.  The bundled model's line holds the BeamDyn blade's values: its
    torsion, edge and flap mu equal those the BeamDyn reader gives for the OpenFAST deck, exactly.
    A ``damping_posdef`` or mass-proportional terms are not converted (no damping, said in the notes);
    a malformed line is an error naming it."""
    from windflutter.errors import InputError
    from windflutter.model import load_turbine

    h2, deck = turbine("nrel5mw_hawc2"), turbine("nrel5mw_openfast")
    np.testing.assert_array_equal(h2.blade.damping.mu[3:], deck.blade.damping.mu[3:])
    assert any("damping_aniso" in n for n in h2.notes)
    line = "damping_aniso 0.0 0.0 0.0 2.2E-03 1.4E-03 2.2E-03"
    t = load_turbine(_model_with(tmp_path / "a", line, "damping_posdef 0.0 0.0 0.0 2.2E-03 1.4E-03 2.2E-03"),
                     validate=False)
    assert t.blade.damping is None and any("not applied" in n for n in t.notes)
    t = load_turbine(_model_with(tmp_path / "b", line, "damping_aniso 0.1 0.0 0.0 2.2E-03 1.4E-03 2.2E-03"),
                     validate=False)
    assert t.blade.damping is None
    with pytest.raises(InputError, match="damping_aniso"):
        load_turbine(_model_with(tmp_path / "c", line, "damping_aniso 0.0 0.0 0.0 2.2E-03 -1.4E-03"), validate=False)
