"""The shell blade against the beam of the SAME blade (issue 33, Verified): the beam model built on the
shell's own extracted section properties (mesh/shell_beam.py ``with_shell_blade_properties``), not on
the turbine file's 6x6 tables, which describe another blade (NREL 5 MW: flap EI +76 %, GJ +52 % in the
layup) or the same layup through another section code (IEA 22 MW).

Static deflection at rated: the shell's steady state (linear shell, moderate-rotation strip chain,
steady/state.py) against the co-rotational beam's (steady/exact.py), same BEM induction, same
operating point.  Twist is read the same way on both: each strip's rotation about its deflected span
axis between its deflected chord and its undeformed chord carried by the shortest rotation of the
span axis (:func:`strip_twist`)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.shell_beam import with_shell_blade_properties
from windflutter.model import load_turbine
from windflutter.system.operational import OperationalModel, OperationalOptions


def strip_twist(undeformed, deflected) -> np.ndarray:
    """(ns,) elastic twist (deg, negative towards feather as ``SteadyState.tip_twist``) of each strip:
    the undeformed chord carried by the shortest rotation taking the undeformed span axis to the
    deflected one, then turned about the deflected span axis onto the deflected chord."""
    e0, e1 = np.asarray(undeformed.e_span, float), np.asarray(deflected.e_span, float)
    c0, c1 = np.asarray(undeformed.e_chord, float), np.asarray(deflected.e_chord, float)
    e0 = e0 / np.linalg.norm(e0, axis=1, keepdims=True)
    e1 = e1 / np.linalg.norm(e1, axis=1, keepdims=True)
    out = []
    for a, b, ca, cb in zip(e0, e1, c0, c1):
        v, c = np.cross(a, b), float(a @ b)
        K = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
        R = np.eye(3) + K + K @ K / (1.0 + c)  # the shortest rotation a -> b (Rodrigues)
        cs = R @ ca
        out.append(np.degrees(np.arctan2(np.cross(cs, cb) @ b, cs @ cb)))
    return np.array(out)


COARSE = {"n_span": 30, "n_chord": 24}  # the reduced checks' shell mesh (the default: 100 x 44)


def same_blade(name: str, n_stations: int, mesh: dict):
    """(the turbine, the turbine whose beam is its shell's extracted properties on ``mesh``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # NREL 5 MW: the layup is not the 6x6 tables' blade (known, warned)
        t = load_turbine(name)
        return t, with_shell_blade_properties(t, n_stations, MeshSettings(model="shell", part="blade", **mesh))


def steady_pair(turbines, wind_speed: float, mesh: dict) -> dict:
    """The steady states of the shell rotor (mesh ``mesh``), of the beam on the shell's extracted
    properties and of the beam on the file's 6x6 (``turbines``: :func:`same_blade`): per model the tip
    flap (m), the tip twist (deg), the strips' span fraction and twist (deg)."""
    t, ts = turbines
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for lab, tb, model, m in (("shell", t, "shell", mesh), ("beam", ts, "beam", {}), ("file", t, "beam", {})):
            om = OperationalModel(tb, OperationalOptions(model=model, part="rotor", mesh=m))
            omega, pitch = om.operating_point(wind_speed)
            rb = om.blade(pitch)
            st = om.steady(rb, wind_speed, omega)
            p = np.asarray(rb.sections.origin, float)
            r = np.linalg.norm(p - p[0], axis=1)
            out[lab] = dict(flap=st.tip_flap, twist=np.degrees(st.tip_twist), s=r / r[-1],
                            strip_twist=strip_twist(rb.sections, st.sections))
    print({k: (round(v["flap"], 3), round(float(v["twist"]), 3)) for k, v in out.items()})
    return out


@pytest.fixture(scope="module")
def nrel5mw_coarse():
    """NREL 5 MW and the beam of its shell blade on the reduced mesh (12 stations)."""
    return same_blade("nrel5mw", 12, COARSE)


def test_nrel5mw_shell_static_deflection_against_the_beam_of_its_own_properties_reduced(nrel5mw_coarse):
    """The reduced check (coarse mesh, 30 x 24, for both; 12 stations): NREL 5 MW at 11.4 m/s (rated).
    Tip flap within the issue's 5 % (measured -1.1 %: beam 3.11 m against the shell's 3.15 m); the
    tip twist within 0.5 deg (measured: shell -0.02, beam +0.20 deg -- this blade hardly twists, so
    a fraction of its twist is no measure; 0.5 deg is a tenth of the IEA 22 MW's tip twist).  The
    same beam on the file's 6x6 deflects 5.5 m: the tables' blade, not the layup's."""
    got = steady_pair(nrel5mw_coarse, 11.4, COARSE)
    assert got["beam"]["flap"] == pytest.approx(got["shell"]["flap"], rel=0.05)
    assert abs(got["beam"]["twist"] - got["shell"]["twist"]) < 0.5
    assert got["file"]["flap"] > 1.3 * got["shell"]["flap"]  # the check above is not the file's beam


def test_nrel5mw_overspeed_blade_modes_shell_against_the_beam_of_its_own_properties_reduced(nrel5mw_coarse):
    """The structure behind the overspeed onsets (the slow test below): the blade clamped at the
    root, spinning at 20 RPM (1.65 x rated, centrifugal stiffening and spin softening), its lowest
    six modes, shell against the beam of its extracted properties, by name and within the issue's
    Campbell band, 5 % in frequency.  Measured on this mesh: 1st/2nd flap, 1st/2nd edge -0.2, -1.4,
    -0.6, -1.9 %, 3rd flap -2.3 %, 1st torsion -3.7 %; on the default mesh (40 stations) +0.3 to
    +0.5 % and 1st torsion +3.8 % (the beam stiffer in torsion).  The file-6x6 beam: 1st flap -17 %,
    1st torsion -27 %."""
    from windflutter.mesh.analysis import turbine_modes

    t, ts = nrel5mw_coarse
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sh = turbine_modes(t, MeshSettings(model="shell", part="blade", **COARSE), n_modes=6, rpm=20.0)
        bm = turbine_modes(ts, MeshSettings(model="beam", part="blade"), n_modes=6, rpm=20.0)
    print(list(zip(sh.labels, sh.frequencies_hz, bm.labels, bm.frequencies_hz)))
    assert list(bm.labels) == list(sh.labels)
    assert "1st torsion" in sh.labels
    np.testing.assert_allclose(bm.frequencies_hz, sh.frequencies_hz, rtol=0.05)


def test_nrel5mw_shell_blade_modes_get_the_beams_structural_damping_reduced(nrel5mw_coarse):
    """Issue 33 (a): each of the shell blade's modes gets the file's damping for its direction.
    Reference: the beam of the same blade (its extracted properties), damped as beam blades are,
    stiffness-proportional per direction with the file's ``mu`` (edge 0.0014, flap and torsion
    0.0022 s) -- strain-energy weighted, where the shell's modal damping weighs the directions by
    the mode's motion (system/damping.py ``shell_modal_damping``).  Both clamped at the root, at
    rest; the lowest six modes paired in order (frequencies within 5 %, checked), damping ratios
    within 6 % for the four bending modes and 12 % for the 3rd flap and 1st torsion.  Measured on
    this mesh: -3.3, +5.3, +4.5, +3.9, +10.4, +3.3 % (the shell's frequencies are 0.2-2.4 % higher,
    and ``zeta ~ f``).  The one ``beta K`` the shell had before (the flap's ``mu`` everywhere) gives
    the 1st edge +57 %: the check can fail.

    The coupling of the two lowest modes by the damping (``c_12 / sqrt(c_11 c_22)``, the modes'
    signs paired by their tip motion): the beam's stiffness-proportional damping couples the 1st
    flap and edge modes, which share directions of different ``mu``; the shell's direction terms
    give the same sign and size (measured -0.166 against -0.123; within 0.1; 0 without them).  Without it the
    shell's 1st edge BW at 8 m/s, 20.4 RPM got 0.11 point more structural damping than the beam's
    (+17 %); with it 0.001 point more."""
    import scipy.sparse as sp

    from windflutter.structure.modal import symmetric_eigs

    t, ts = nrel5mw_coarse
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rs = OperationalModel(t, OperationalOptions(model="shell", part="rotor", mesh=COARSE)).blade(0.0)
        rb = OperationalModel(ts, OperationalOptions(model="beam", part="rotor")).blade(0.0)
    D = rs.damping
    got = {}
    for lab, b in (("shell", rs), ("beam", rb)):
        st = b.struct
        w2, X = symmetric_eigs(sp.csc_matrix(st.Kr), sp.csc_matrix(st.Mr), 6, shift=0.0, v0=np.ones(st.nq))
        X = X / np.sqrt(np.einsum("im,im->m", X, st.Mr @ X))
        P = np.asarray(st.T @ X)
        tip = np.asarray(b.sections.motion_map @ P)[-6:-3]  # the tip strip's translation
        got[lab] = (np.sqrt(w2) / (2 * np.pi), P.T @ (b.damping @ P), tip)
    f, C, tip = got["beam"]
    beam = np.diag(C) / (4 * np.pi * f)
    sign = np.sign(np.einsum("im,im->m", tip, got["shell"][2]))
    corr = {lab: g[1][0, 1] / np.sqrt(g[1][0, 0] * g[1][1, 1]) for lab, g in got.items()}
    corr["beam"] *= sign[0] * sign[1]
    print(np.c_[D.freq_hz[:6], f, 100 * D.zeta[:6], 100 * beam], corr)
    np.testing.assert_allclose(D.freq_hz[:6], f, rtol=0.05)
    np.testing.assert_allclose(D.zeta[:4], beam[:4], rtol=0.06)
    np.testing.assert_allclose(D.zeta[4:6], beam[4:6], rtol=0.12)
    assert corr["shell"] * corr["beam"] > 0 and abs(corr["shell"] - corr["beam"]) < 0.1


@pytest.mark.slow
@pytest.mark.parametrize("name, wind_speed", [("iea22mw", 11.0), ("nrel5mw", 11.4)])
def test_shell_static_deflection_against_the_beam_of_its_own_properties(name, wind_speed):
    """The default (converged) shell mesh, 40 stations, at rated (IEA 22 MW: 11 m/s, the test of
    tests/system/test_deflected_shell.py; NREL 5 MW: 11.4 m/s).  Tip flap within the issue's 5 %
    (measured: IEA 22 MW beam 22.12 m against the shell's 22.48 m, -1.6 %; NREL 5 MW +0.5 %), where
    the beam on the windIO 6x6 gives 20.44 m (-9.1 %): the shell's +10.0 % over the file's beam is its
    data (its flap EI 0.60-0.85 of the tables' at 6-16 % span, 0.93-0.98 outboard; docs/mesh.md),
    1.6 points of it the two models.

    Tip twist: IEA 22 MW beam -4.61 deg against the shell's -4.46 (+3.4 %; -4.37 and +5.6 % with the
    membrane-only initial stress before issue 33's complete matrix, whose hoop term stiffened the
    centrifugal state's twist), and the difference arises in the root transition, 10-28 % span, where the shell
    twists 0.1 deg nose-up and the beam 0.25 deg towards feather; outboard of 30 % span the two
    twist by the same amount (measured 0.1 %).  It is inside the extraction's own spread: with the
    segments' ends 0.5-3 chords from the reading rings instead of 1 the beam's tip twist is -4.19 ...
    -4.62 deg (80 stations: -4.62; docs/mesh.md "The beam of the shell's own blade").  Accepted:
    tip twist within 7 %, its increment outboard of 30 % span within 3 %, up to the beam's last
    station of its own stiffness.  With MITC4's shear (Dec 2026) the readings of the two tip
    stations (96 and 98 % span) fail and the beam holds the 94 % station's stiffness to the tip:
    shell -4.44 / beam -4.36 deg at the tip (-1.8 %), the increment from 30 to 94 % span -3.68 /
    -3.76 deg (+2.1 %), to the tip -4.29 / -3.95 deg (the held stiffness over the last 6 %; with the
    one-point shear, whose 98 % reading passed, -4.32 / -4.20).  NREL 5 MW: tip twist within 0.5 deg
    (measured 0.30 against 0.00 deg)."""
    t, ts = same_blade(name, 40, {})
    got = steady_pair((t, ts), wind_speed, {})
    sh, bm = got["shell"], got["beam"]
    assert bm["flap"] == pytest.approx(sh["flap"], rel=0.05)
    if name == "iea22mw":
        assert bm["twist"] == pytest.approx(sh["twist"], rel=0.07)
        K = np.asarray(ts.blade.beam.stiffness)
        own = len(K) - 1  # the last station with its own stiffness (those beyond hold it)
        while own > 0 and np.array_equal(K[own - 1], K[-1]):
            own -= 1
        end = float(ts.blade.beam.s[own])

        def outboard(g):
            return float(np.interp(end, g["s"], g["strip_twist"]) - np.interp(0.3, g["s"], g["strip_twist"]))

        assert end > 0.9 and outboard(bm) == pytest.approx(outboard(sh), rel=0.03)
        assert got["file"]["flap"] < 0.93 * sh["flap"]  # the file's beam is another blade's data
    else:
        assert abs(bm["twist"] - sh["twist"]) < 0.5


@pytest.mark.slow
@pytest.mark.timeout(3600)
@pytest.mark.parametrize("wind_speed", [8.0, 10.0])
def test_nrel5mw_shell_overspeed_onsets_against_the_beam_of_its_own_properties(wind_speed):
    """Issue 33: the NREL 5 MW shell at 8 and 10 m/s at the default mesh, its first overspeed
    instability (``windflutter.stability``, method p, the defaults) within 5 % of the beam's and in
    the same mode -- the beam of the same blade (40 stations of the shell's extracted properties),
    each model with its own reading of the files' structural damping (the beam: ``mu`` per
    direction on its sections; the shell: modal damping by direction, system/damping.py
    ``shell_modal_damping``).  Measured (4 Dec 2026):

    * 8 m/s: both first flutter in the 1st edge BW + 1st flap BW, shell 20.56 against 20.37 RPM
      (+0.9 %; 0.678 / 0.685 Hz); divergence beyond it 26.25 against 26.57 RPM;
    * 10 m/s: the same mode, 19.20 against 19.45 RPM (-1.3 %); divergence 26.55 against 26.77.

    With the shell's stress balanced on the bent geometry (5 Dec 2026; the shell map of the 9th session):
    8 m/s 21.03 RPM (+3.2 %), divergence 26.23; 10 m/s 19.42 RPM (-0.2 %), divergence 26.45.
    With the deflected shell's elements its undeformed ones turned (6 Dec 2026, MITC4 shear; the map):
    8 m/s 19.65 RPM (-3.5 %), 10 m/s 18.71 RPM (-3.8 %).

    With the shell's earlier damping (one ``beta K``, the flap's ``mu`` on every direction: its edge
    +57 %) the shell's first instability was the divergence at 8 m/s (its edge BW only grazing zero)
    and the edge BW at 21.22 RPM at 10 m/s (+9.1 %); with modal damping without the direction terms
    between modes, 22.37 RPM at 8 m/s (+9.8 %).  That mode's damping falls by only 0.09 point per
    RPM at 8 m/s, so 0.1 point of structural damping moves its crossing by 1-2 RPM.  The file-6x6
    beam (the tables' blade): 16.37 / 16.88 RPM, 1st edge BW.  3-5 min per wind speed on an idle
    machine, 13 min for both on the loaded shared one."""
    import windflutter.api as api

    t, ts = same_blade("nrel5mw", 40, {})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sh = api.stability(t, wind_speed, model="shell")[0].as_dict()
        bm = api.stability(ts, wind_speed, model="beam")[0].as_dict()
    print(wind_speed, "shell", sh, "beam", bm)
    assert sh["first_instability"] == bm["first_instability"]
    kind = sh["first_instability"]
    assert sh[f"{kind}_rpm"] == pytest.approx(bm[f"{kind}_rpm"], rel=0.05)
    assert sh["flutter_mode"] == bm["flutter_mode"]
    if kind == "divergence":  # the flutter beyond it: the same mode, within 5 % as well
        assert sh["flutter_rpm"] == pytest.approx(bm["flutter_rpm"], rel=0.05)
