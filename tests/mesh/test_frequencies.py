"""Natural frequencies of the generated models against independent references.

References
----------
* Euler-Bernoulli cantilever (1.8751^2, 4.6941^2) and Bredt-Batho torsion (f = sqrt(GJ/I_p)/(4L))
  for thin-walled elliptical tubes (analytic).
* Jonkman, Butterfield, Musial, Scott (2009), NREL/TP-500-38060, table 9-1: NREL 5 MW isolated
  blade and full-system natural frequencies (FAST / ADAMS).
* pyBmodes 1.19 (Apache-2.0, independent Python BModes port) on the NREL 5 MW ElastoDyn decks it
  ships (not our data files), parked and at 12.1 rpm.
* Gaertner et al. (2020), NREL/TP-5000-75698, IEA 15 MW RWT: blade 1st flap 0.555 Hz, 1st edge
  0.642 Hz.
"""

import dataclasses
import glob
import os
import warnings

import numpy as np
import pytest

from synthetic import STEEL, synthetic_turbine, tube_beam_props, tube_blade
from windflutter.mesh.analysis import turbine_modes
from windflutter.mesh.settings import SEED_MESH, MeshSettings
from windflutter.model.turbine import IsotropicMaterial, Tower, TowerLayer
from windflutter.structure.fem import OrthotropicMaterial

B1, B2 = 1.8751041**2, 4.6940911**2


def tube_reference(L, c, th, t, E=70e9, nu=0.3, rho=2700.0):
    bp = tube_beam_props(L, c, th, t, E, nu, rho)
    K, M = bp.stiffness[0], bp.mass[0]
    m = M[0, 0]
    f = lambda b, EI: b / (2 * np.pi) * np.sqrt(EI / (m * L**4))  # noqa: E731
    return {
        "flap1": f(B1, K[5, 5]), "edge1": f(B1, K[4, 4]), "flap2": f(B2, K[5, 5]),
        "torsion1": np.sqrt(K[3, 3] / M[3, 3]) / (4 * L),
    }, bp


def first(res, label):
    return float(res.frequencies_hz[res.labels.index(label)])


@pytest.mark.parametrize("model", ["shell", "beam"])
def test_elliptic_tube_blade_vs_analytic(model):
    """Straight isotropic elliptical tube (t/c 0.4, wall 10 mm) clamped at the root: bending.

    Tolerance 1.5 % (24x20 shell mesh; shear deformation and the discrete contour make up
    < 1 %).  The reference's wall midline is the given ellipse: the shell's skin on it
    (``reference_surface="outer"``; the default midsurface would put the wall t/2 inside it)."""
    L, c, th, t = 40.0, 2.0, 0.4, 0.01
    ref, bp = tube_reference(L, c, th, t)
    tb = synthetic_turbine(tube_blade(L, c, th, t, beam=bp))
    kw = {"reference_surface": "outer"} if model == "shell" else {}
    res = turbine_modes(tb, MeshSettings(model=model, part="blade", n_chord=24, n_span=20, **kw), n_modes=5)
    assert first(res, "1st flap") == pytest.approx(ref["flap1"], rel=0.015)
    assert first(res, "1st edge") == pytest.approx(ref["edge1"], rel=0.015)
    assert first(res, "2nd flap") == pytest.approx(ref["flap2"], rel=0.015)


@pytest.mark.parametrize("model", ["shell", "beam"])
def test_circular_tube_torsion_vs_bredt(model):
    """Circular tube (R 1 m, wall 50 mm): 1st torsion sqrt(GJ/I_p)/(4L) = 19.74 Hz, 1 %.  (A
    thinner unstiffened wall has n=2 ovalisation shell modes below the torsion mode: ring
    frequency ~6.6 Hz for 10 mm; they are physical, not labelled torsion reliably.)"""
    L, c, th, t = 40.0, 2.0, 1.0, 0.05
    ref, bp = tube_reference(L, c, th, t)
    tb = synthetic_turbine(tube_blade(L, c, th, t, beam=bp))
    res = turbine_modes(tb, MeshSettings(model=model, part="blade", n_chord=24, n_span=20), n_modes=7)
    assert first(res, "1st torsion") == pytest.approx(ref["torsion1"], rel=0.01)


def test_orthotropic_plies_follow_span_direction():
    """Fibres along the span (ply angle 0 from the per-element span axis): the bending frequency
    uses E1; with 90 deg plies it uses E2 (ratio sqrt(E1/E2) = sqrt(10)).  1.5 %."""
    L, c, th, t = 40.0, 2.0, 1.0, 0.01
    ref, _ = tube_reference(L, c, th, t)
    ortho = OrthotropicMaterial(70e9, 7e9, 0.3, 26.9e9, 26.9e9, 26.9e9, 2700.0, "alu")
    blade = tube_blade(L, c, th, t)
    for angle, E in ((0.0, 70e9), (np.pi / 2, 7e9)):
        lay = dataclasses.replace(blade.layup.layers[0], orientation=np.full(2, angle))
        b2 = dataclasses.replace(blade, layup=dataclasses.replace(blade.layup, layers=(lay,)))
        tb = dataclasses.replace(synthetic_turbine(b2), materials={"alu": ortho, "steel": STEEL})
        res = turbine_modes(tb, MeshSettings(model="shell", part="blade", n_chord=24, n_span=16), n_modes=2)
        assert res.frequencies_hz[0] == pytest.approx(ref["flap1"] * np.sqrt(E / 70e9), rel=0.015)


def _pybmodes_nrel5mw(rpm):
    import pybmodes
    from pybmodes.models import RotatingBlade

    d = os.path.join(os.path.dirname(pybmodes.__file__), "_examples", "reference_decks", "nrel5mw_oc3monopile")
    main = glob.glob(os.path.join(d, "*ElastoDyn.dat"))[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        b = RotatingBlade.from_elastodyn(main)
        b._bmi.rot_rpm = rpm
        return b.run(4, check_model=False).frequencies


def shear_rigid(turbine):
    """The turbine with the blade 6x6 shear stiffnesses x 1e3 (Euler-Bernoulli, like BModes)."""
    bp = turbine.blade.beam
    K = bp.stiffness.copy()
    K[:, 1, 1] *= 1e3
    K[:, 2, 2] *= 1e3
    return dataclasses.replace(turbine, blade=dataclasses.replace(turbine.blade, beam=dataclasses.replace(bp, stiffness=K)))


@pytest.mark.parametrize("rpm", [0.0, 12.1])
def test_nrel5mw_beam_blade_vs_pybmodes(nrel5mw, rpm):
    """Beam blade from the windIO/BeamDyn 6x6 vs pyBmodes on the ElastoDyn blade tables (same
    NREL 5 MW blade, different source tables and code).  pyBmodes modes 1-3 are flap 1, edge 1,
    flap 2.  pyBmodes (like BModes/ElastoDyn) is an Euler-Bernoulli beam, so it is compared with
    our model made shear-rigid: 1.5 % (mass 17.61 vs 17.74 t, Simpson-averaged 30 elements).
    The Timoshenko model with the BeamDyn shear stiffness is 1-3 % lower (edge most): 4 %."""
    ref = _pybmodes_nrel5mw(rpm)
    eb = turbine_modes(shear_rigid(nrel5mw), MeshSettings(model="beam", part="blade", n_span=30), n_modes=6, rpm=rpm)
    ts = turbine_modes(nrel5mw, MeshSettings(model="beam", part="blade", n_span=30), n_modes=6, rpm=rpm)
    print(f"rpm {rpm}: EB {eb.frequencies_hz[:3]}, Timoshenko {ts.frequencies_hz[:3]}, pyBmodes {ref[:3]}")
    for res, tol in ((eb, 0.015), (ts, 0.04)):
        assert first(res, "1st flap") == pytest.approx(ref[0], rel=tol)
        assert first(res, "1st edge") == pytest.approx(ref[1], rel=tol)
        assert first(res, "2nd flap") == pytest.approx(ref[2], rel=tol)


def test_nrel5mw_beam_blade_vs_jonkman_and_rotating_shift(nrel5mw):
    """Jonkman 2009 table 9-1 / BModes ranges (Euler-Bernoulli codes): flap 1 0.65-0.70,
    edge 1 1.07-1.09, flap 2 1.90-2.02 Hz, checked on the shear-rigid model.  Rotating at
    12.1 rpm raises flap 1 by centrifugal stiffening: pyBmodes gives +7.7 % (0.676 -> 0.729); we
    require +5..+10 %, and an edgewise change below 2 %."""
    p = turbine_modes(shear_rigid(nrel5mw), MeshSettings(model="beam", part="blade"), n_modes=6)
    r = turbine_modes(shear_rigid(nrel5mw), MeshSettings(model="beam", part="blade"), n_modes=6, rpm=12.1)
    assert 0.65 <= first(p, "1st flap") <= 0.70
    assert 1.07 <= first(p, "1st edge") <= 1.09
    assert 1.90 <= first(p, "2nd flap") <= 2.02
    shift = first(r, "1st flap") / first(p, "1st flap") - 1
    assert 0.05 < shift < 0.10
    assert abs(first(r, "1st edge") / first(p, "1st edge") - 1) < 0.02
    assert first(p, "1st torsion") > 4.0  # Jonkman's blade is torsionally stiff (BModes ~5.6 Hz)


def jonkman_tower(turbine):
    """The seed's / Jonkman's tower (seed fig. 4.1, table 4.2): D 6 -> 3.87 m, t 35.1 -> 24.7 mm,
    E 210 GPa, G 80.8 GPa, effective density 8500 kg/m^3, 87.6 m."""
    tw = Tower(s=np.array([0.0, 1.0]), z=np.array([0.0, 87.6]), outer_diameter=np.array([6.0, 3.87]),
               layers=(TowerLayer("wall", "tower_steel", np.array([0.0351, 0.0247])),))
    mats = dict(turbine.materials)
    mats["tower_steel"] = IsotropicMaterial(210e9, 210 / (2 * 80.8) - 1, 8500.0, "tower_steel")
    return dataclasses.replace(turbine, tower=tw, materials=mats)


@pytest.mark.parametrize("model", ["beam", "shell"])
def test_nrel5mw_tower_with_top_mass(nrel5mw_fixed, model):
    """Tower with the rotor-nacelle assembly lumped at the top: 1st fore-aft and side-side
    0.312-0.324 Hz (Jonkman 2009 table 9-1, FAST/ADAMS); seed range 0.32-0.34.  We accept
    0.31-0.34 Hz (our blades lack the 4.5 % ElastoDyn mass adjustment)."""
    tb = jonkman_tower(nrel5mw_fixed)
    res = turbine_modes(tb, MeshSettings(model=model, part="tower", n_span=10, n_tower_circ=16, n_tower_axial=16), n_modes=4)
    fa, ss = first(res, "1st tower fore-aft"), first(res, "1st tower side-side")
    print(model, res.frequencies_hz, res.labels)
    assert 0.31 <= fa <= 0.34 and 0.31 <= ss <= 0.34


def test_nrel5mw_beam_turbine_labels(nrel5mw_fixed):
    """Whole beam turbine: tower modes first, then the 1st flap family (1 collective + 2
    asymmetric) between 0.6 and 0.75 Hz and the 1st edge family ~1.0-1.1 Hz (Jonkman 2009
    table 9-1: 1st tower FA/SS 0.324/0.312, 1st flap yaw/tilt 0.666/0.668, collective 0.700,
    1st edge 1.079/1.089 Hz).  Bounds +-5 %."""
    tb = jonkman_tower(nrel5mw_fixed)
    res = turbine_modes(tb, MeshSettings(model="beam", part="turbine"), n_modes=8)
    f = dict(zip(res.labels, res.frequencies_hz))
    assert res.labels[:2] == ["1st tower side-side", "1st tower fore-aft"] or set(res.labels[:2]) == {"1st tower side-side", "1st tower fore-aft"}
    assert res.labels.count("1st flap asymmetric") == 2 and "1st flap collective" in res.labels
    assert f["1st flap collective"] == pytest.approx(0.700, rel=0.05)
    assert f["1st tower fore-aft"] == pytest.approx(0.324, rel=0.05)
    assert res.labels.count("1st edge asymmetric") == 2


def test_iea15mw_blade_shell_and_beam():
    """IEA 15 MW blade: Gaertner 2020 flap 1 0.555 Hz, edge 1 0.642 Hz.  The WISDEM-example
    windIO file is a later revision of the blade (tapered-chord tip; pyBmodes on the ElastoDyn
    deck it ships gives 0.538 / 0.729 Hz, i.e. +14 % in edge against the report).  Measured:
    shell (windIO layup, the seed's mesh SEED_MESH: 40 x 30, outer mould line) 0.560 / 0.702, beam (windIO 6x6) 0.505 / 0.692 Hz.
    Bound: 12 % (the revision gap shown by pyBmodes), flap of the shell 5 %."""
    from windflutter.model.windio import load_turbine

    tb = load_turbine("iea15mw")
    sh = turbine_modes(tb, MeshSettings(model="shell", part="blade", **SEED_MESH), n_modes=3)
    bm = turbine_modes(tb, MeshSettings(model="beam", part="blade"), n_modes=3)
    print("shell", sh.frequencies_hz, sh.labels, "beam", bm.frequencies_hz, bm.labels)
    assert first(sh, "1st flap") == pytest.approx(0.555, rel=0.05)
    for res in (sh, bm):
        assert first(res, "1st flap") == pytest.approx(0.555, rel=0.12)
        assert first(res, "1st edge") == pytest.approx(0.642, rel=0.12)


def test_iea10mw_blade_shell_and_beam():
    """IEA 10 MW (WISDEM windIO v2, after the reader's two corrections, see
    tests/model/test_windio.py) builds as beams and as shells.  Reference: pyBmodes 1.19.1
    (independent Euler-Bernoulli code) on the same file's published 6x6
    (``RotatingBlade.from_windio(windIO_v1/IEA-10-198-RWT.yaml, elastic="file")``; the v2 file's
    width-placeholder anchors are not supported by pyBmodes): 0.3892 / 0.6559 / 1.0335 Hz
    (flap 1, edge 1, flap 2).  Beam (30 elements, same 6x6) measured 0.3853 / 0.6434 / 1.0164:
    2.5 %.  Shell (the seed's mesh, SEED_MESH) measured 0.4044 / 0.6213 / 1.0780: 8 % (midsurface on the outer
    mould line stiffens flap; no 6x6 shear terms in the file).  Shell blade mass 48.58 t vs the 6x6
    48.90 t: 2 %; both vs the HAWC2 blade of the RWT repository (IEAWindTask37/IEA-10.0-198-RWT
    hawc2/data/iea10mw_rc1_hawc2_blade_st.dat @ b00b748, mass per length over its 19 stations,
    trapezoid: 47.76 t): +1.7 % / +2.4 %, 3 % allowed.  Before the corrections neither model built."""
    import warnings as _w

    from windflutter.mesh import build_model
    from windflutter.model.windio import load_turbine
    from windflutter.structure import assemble

    with _w.catch_warnings():
        _w.simplefilter("ignore")
        tb = load_turbine("iea10mw")
    ref = (0.3892, 0.6559, 1.0335)
    bm = turbine_modes(tb, MeshSettings(model="beam", part="blade", n_span=30), n_modes=4)
    sh = turbine_modes(tb, MeshSettings(model="shell", part="blade", **SEED_MESH), n_modes=4)
    print("beam", bm.frequencies_hz, "shell", sh.frequencies_hz)
    for res, tol in ((bm, 0.025), (sh, 0.08)):
        for lab, f in zip(("1st flap", "1st edge", "2nd flap"), ref):
            assert first(res, lab) == pytest.approx(f, rel=tol)
    fe, _ = build_model(tb, MeshSettings(model="shell", part="blade", **SEED_MESH))
    M = assemble(fe).M
    u = np.zeros(M.shape[0])
    u[0::6] = 1.0
    assert u @ (M @ u) == pytest.approx(tb.blade.beam.total_mass, rel=0.02)
    assert u @ (M @ u) == pytest.approx(47756.0, rel=0.03)
    assert tb.blade.beam.total_mass == pytest.approx(47756.0, rel=0.03)


def test_seed5mw_shell_and_thin_walled_beam():
    """The seed's NREL 5 MW blade (UpWind layup, seed appendix A) as shells and as thin-walled
    beams of the same layup.  Against Jonkman 2009 / BModes (flap 1 ~0.675, edge 1 ~1.08,
    flap 2 ~1.96 Hz): 12 % -- the UpWind layup is not the ElastoDyn blade (seed ch. 4 notes the
    inconsistency; chordwise extents are from the WISDEM anchors; the shell blade weighs 22.0 t
    against 17.7 t, see docs/turbine_input.md).  Measured (the seed's mesh, SEED_MESH): 0.754 / 1.018 / 2.113 Hz
    (+11.6 / -5.8 / +7.8 %).  Shell vs thin-walled beam (classical theory, model/section.py: wall
    midline offset inwards by t/2, no shear lag, no section deformation): measured beam/shell
    0.977 / 1.033 / 0.962.  The shell mesh puts the laminate midsurface on the outer mould line,
    which lifts flap EI (thick spar caps); the beam lacks shear lag and section deformation, which
    lowers the shell.  Accepted band 0.93-1.10 (flap lower bound: sqrt of the ~15 % flap-EI
    difference between midline and outer-line geometry)."""
    from windflutter.model.windio import load_turbine

    tb = load_turbine("seed5mw")
    sh = turbine_modes(tb, MeshSettings(model="shell", part="blade", **SEED_MESH), n_modes=6)  # the seed's 40x30
    bm = turbine_modes(tb, MeshSettings(model="beam", part="blade"), n_modes=6)
    print("shell", sh.frequencies_hz, sh.labels, "beam", bm.frequencies_hz, bm.labels)
    for lab, ref in (("1st flap", 0.675), ("1st edge", 1.08), ("2nd flap", 1.96)):
        assert first(sh, lab) == pytest.approx(ref, rel=0.12)
        assert 0.93 <= first(bm, lab) / first(sh, lab) <= 1.10


MESHES = ((32, 16), (48, 24), (64, 32), (96, 48))


def _bending(turbine, nc, ns):
    r = turbine_modes(turbine, MeshSettings(model="shell", part="blade", n_chord=nc, n_span=ns), n_modes=6)
    return np.array([first(r, "1st flap"), first(r, "1st edge"), first(r, "2nd flap")]), r


def test_blade_mesh_convergence_reduced(nrel5mw):
    """Shell blade (windIO layup), 24x12 vs 48x24: flap 1, edge 1, flap 2 agree within 3 %
    (the slow test shows the spread of all meshes from 32x16 up is ~1 %)."""
    a, _ = _bending(nrel5mw, 24, 12)
    b, _ = _bending(nrel5mw, 48, 24)
    print(a, b)
    assert np.allclose(a, b, rtol=0.03)


@pytest.mark.slow
def test_blade_mesh_convergence_full(nrel5mw):
    """Shell blade on 32x16 .. 96x48: bending frequencies of the 48x24 and finer meshes within
    1.5 % of the finest mesh, 32x16 within 2.5 % (measured 1.8 %; non-monotone at the 1 % level
    as key arcs and layer edges move with the grid); the 1st torsion frequency decreases
    monotonically with refinement (shells are too stiff in torsion on coarse meshes)."""
    fs, tors = [], []
    for nc, ns in MESHES:
        f, r = _bending(nrel5mw, nc, ns)
        fs.append(f)
        tors.append(first(r, "1st torsion") if "1st torsion" in r.labels else np.nan)
    fs = np.array(fs)
    print(fs, tors)
    assert np.allclose(fs[1:], fs[-1], rtol=0.015)
    assert np.allclose(fs[0], fs[-1], rtol=0.025)
    t = np.array(tors)
    assert np.all(np.diff(t[np.isfinite(t)]) < 0)


def test_rotating_shift_shell_vs_beam():
    """Centrifugal stiffening at 12.1 rpm on the seed 5 MW blade: the shell model's 1st flap
    rise (geometric stiffness of the shell prestress) against the thin-walled beam's of the same
    layup, and pyBmodes' +7.7 % on the ElastoDyn blade.  Both between +4 % and +10 %, and within
    2 percentage points of each other (measured shell +5.28 %, beam +6.19 %: the beam, softer in
    flap (midline geometry), gains relatively more from the same centrifugal stiffening)."""
    from windflutter.model.windio import load_turbine

    tb = load_turbine("seed5mw")
    rise = {}
    for model in ("shell", "beam"):
        st = MeshSettings(model=model, part="blade", n_chord=24, n_span=16)
        p = first(turbine_modes(tb, st, n_modes=3), "1st flap")
        r = first(turbine_modes(tb, st, n_modes=3, rpm=12.1), "1st flap")
        rise[model] = r / p - 1
    print(rise)
    assert 0.04 < rise["shell"] < 0.10 and 0.04 < rise["beam"] < 0.10
    assert abs(rise["shell"] - rise["beam"]) < 0.02
