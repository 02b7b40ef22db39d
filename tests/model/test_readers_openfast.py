"""OpenFAST deck reader against independent data: the ElastoDyn/BeamDyn/AeroDyn files themselves,
tube formulas, and the windIO-built models of the same turbines (natural frequencies)."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from windflutter.errors import InputError
from windflutter.mesh.analysis import turbine_modes
from windflutter.mesh.settings import MeshSettings
from windflutter.model import load_turbine
from windflutter.model.bundled import DATA_DIR
from windflutter.model.elastodyn import read_elastodyn_blade_table, read_elastodyn_tower_table

N5 = DATA_DIR / "nrel5mw"
I15 = DATA_DIR / "iea15mw" / "openfast"


def test_nrel5mw_deck_rotor_nacelle_values(turbine):
    """Every lumped value against the ElastoDyn main file (Jonkman 2009 table 5-1/6-1), with
    windflutter's signs; the apex height of those numbers is the 90 m hub height."""
    t = turbine("nrel5mw_openfast")
    assert t.source_format == "OpenFAST" and t.n_blades == 3 and t.rotor_diameter == 126.0
    assert t.hub.radius == 1.5 and t.hub.mass == 56780.0 and t.hub.inertia[0, 0] == 115926.0
    assert np.degrees(t.hub.precone) == pytest.approx(2.5) and np.degrees(t.nacelle.shaft_tilt) == pytest.approx(5.0)
    n = t.nacelle
    assert (n.mass, n.overhang, n.tower_to_shaft, n.gear_ratio) == (240000.0, -5.0191, 1.96256, 97.0)
    np.testing.assert_allclose(n.cg, [1.9, 0.0, 1.75])
    # NacYIner is about the yaw axis: 2.60789e6 - 240000 x 1.9^2 about the nacelle CG
    assert n.inertia[2, 2] == pytest.approx(2.60789e6 - 240000 * 1.9**2, rel=1e-12)
    assert (n.drivetrain_torsional_stiffness, n.drivetrain_torsional_damping, n.generator_inertia) == (
        8.67637e8, 6.215e6, 534.116)
    assert t.hub_height == pytest.approx(90.0, abs=1e-5)  # tolerance: 6-digit inputs
    assert t.tower.z[0] == 0.0 and t.tower.top_z == 87.6
    assert not t.missing and not t.warnings
    assert t.operating_curve is not None and t.rated_rotor_speed == pytest.approx(12.1 * np.pi / 30)


def test_equivalent_tower_tube_reproduces_elastodyn_table(turbine):
    """The tube made from TMassDen/TwFAStif has exactly that mass and EI at every station (tube
    formulas evaluated here independently, rho = 8500, E = 210 GPa) and Jonkman's geometry
    (D 6 -> 3.87 m, wall 35.1 -> 24.7 mm, sec. 6); tolerance 1e-9 (exact algebra) and 1e-4
    (6-digit table) for the geometry."""
    t = turbine("nrel5mw_openfast")
    tt = read_elastodyn_tower_table(N5 / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")
    D, w = t.tower.outer_diameter, t.tower.layers[0].thickness
    ro, ri = D / 2, D / 2 - w
    mat = t.materials[t.tower.layers[0].material]
    np.testing.assert_allclose(mat.rho * np.pi * (ro**2 - ri**2), tt.mass, rtol=1e-9)
    np.testing.assert_allclose(mat.E * np.pi / 4 * (ro**4 - ri**4), tt.ei_fore_aft, rtol=1e-9)
    np.testing.assert_allclose(D[[0, -1]], [6.0, 3.87], rtol=1e-4)
    np.testing.assert_allclose(w[[0, -1]], [0.0351, 0.0247], rtol=1e-4)
    assert t.tower.damping.fore_aft_ratio.tolist() == [0.01, 0.01]


def test_pitch_axis_from_aerodyn_ac_offsets_matches_elastodyn(tmp_path):
    """Two independent descriptions of the NREL 5 MW reference axis: ElastoDyn's PitchAxis
    column, and AeroDyn's BlCrvAC/BlSwpAC offsets of the aerodynamic centre (read as a quarter
    chord).  With the ElastoDyn column removed (OpenFAST v4 blade files have none) the reader
    derives the axis from AeroDyn; at the AeroDyn nodes (the file's own stations) the two agree
    within 0.002 chord (AeroDyn's offsets have 5 significant digits; ElastoDyn's column is
    interpolated to the nodes)."""
    deck = tmp_path / "deck"
    shutil.copytree(N5, deck)
    ed = deck / "NRELOffshrBsline5MW_Blade.dat"
    lines = ed.read_text().splitlines()
    i0 = next(i for i, ln in enumerate(lines) if "BlFract" in ln and "PitchAxis" in ln)
    for i in range(i0, i0 + 51):
        tok = lines[i].split()
        lines[i] = "  ".join(tok[:1] + tok[2:])
    ed.write_text("\n".join(lines) + "\n")
    b = load_turbine(deck / "NREL-5MW_Onshore.fst").blade
    table = read_elastodyn_blade_table(N5 / "NRELOffshrBsline5MW_Blade.dat")
    nodes = b.airfoil_positions
    pa_ac = np.interp(nodes, b.s, b.pitch_axis)
    assert np.max(np.abs(pa_ac - np.interp(nodes, table.frac, table.pitch_axis))) < 0.002


def test_blade_damping_and_airfoils_from_the_deck(turbine):
    t = turbine("nrel5mw_openfast")
    d = t.blade.damping
    np.testing.assert_allclose(d.mu_beamdyn, [1e-3, 1e-3, 1e-3, 1.4e-3, 2.2e-3, 2.2e-3])
    np.testing.assert_allclose(d.flap_ratio, [0.00477465, 0.00477465])
    assert set(t.blade.airfoil_names) == set(t.airfoils) and len(t.airfoils) == 8
    du25 = t.airfoils["DU25_A17"]
    assert du25.relative_thickness == pytest.approx(0.25, abs=2e-3)  # from its coordinates
    assert du25.reynolds.tolist() == [0.75e6] and du25.polar.alpha[0] == pytest.approx(-np.pi)


def _modes(t, part, n):
    return turbine_modes(t, MeshSettings(model="beam", part=part), n_modes=n).frequencies_hz


@pytest.mark.parametrize("deck, windio, n", [("nrel5mw_openfast", "nrel5mw", 10), ("iea15mw_openfast", "iea15mw", 12)])
def test_deck_frequencies_match_the_windio_model(deck, windio, n, turbine):
    """Whole-turbine beam modes (tower, flap, edge; parked) of the deck-built model within 2 %
    of the windIO-built model of the same turbine (the issue's bar).  Known remaining
    differences: the IEA 15 MW ElastoDyn nacelle has a yaw inertia only (the windIO supplement
    the full tabular tensor): 1.2 % on the 2nd edge collective mode, 0.7 % on the 2nd flap."""
    fa, fb = _modes(turbine(windio), "turbine", n), _modes(turbine(deck), "turbine", n)
    np.testing.assert_allclose(fb, fa, rtol=0.02)


def test_structural_deck_without_aerodynamics(turbine):
    """The IEA 15 MW deck has CompAero = 0 (no airfoil tables bundled): modes work, and a
    stability analysis is refused, naming what is missing."""
    t = turbine("iea15mw_openfast")
    assert t.missing == ("airfoil polars",) and all(not a.polars for a in t.airfoils.values())
    t.require("turbine")
    with pytest.raises(InputError, match="airfoil polars"):
        t.require("turbine", aerodynamics=True)
    from windflutter.frozen.turbine import TurbineStability

    with pytest.raises(InputError, match="airfoil polars"):
        TurbineStability(t)


def test_elastodyn_blades_have_no_torsion_for_stability(tmp_path):
    """CompElast = 1: blades from the ElastoDyn file (mass, flap/edge EI, AdjBlMs applied; no
    torsion): loads, records the missing torsion, refuses a stability analysis."""
    deck = tmp_path / "deck"
    shutil.copytree(N5, deck)
    fst = deck / "NREL-5MW_Onshore.fst"
    fst.write_text(fst.read_text().replace("          2   CompElast", "          1   CompElast"))
    (deck / "NREL-5MW_Onshore.windflutter.yaml").unlink()  # the deck alone (no mass factor, no curve)
    t = load_turbine(fst)
    assert "blade torsion" in t.missing and t.operating_curve is None
    assert t.blade.beam.total_mass == pytest.approx(17740, rel=0.01)  # ElastoDyn x AdjBlMs (Jonkman: 17,740 kg)
    with pytest.raises(InputError, match="blade torsion"):
        t.require("turbine", aerodynamics=True)
