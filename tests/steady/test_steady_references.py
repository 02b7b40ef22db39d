"""Deflected steady state of the IEA 22 MW and IEA 15 MW rotors against HAWC2, OpenFAST and WISDEM.

References (bundled extracts, Apache-2.0, see src/windflutter/data/SOURCES.md):
* IEA 22 MW: HAWC2 and OpenFAST steady states of IEAWindTask37/IEA-22-280-RWT
  (outputs/01_steady_states; "normal operation, no tilt, no gravity"): rotor speed, pitch, aero
  power, thrust, tip deflection and tip rotation in the blade-root pitching system
  (``data/iea22mw/steady_states_hawc2_openfast.csv``);
* IEA 15 MW: the HAWCStab2 operating points of the onshore HAWC2 model
  (``data/iea15mw/IEA_15MW_RWT_Onshore_hawc2.opt``: wind, pitch, rpm, aero power, thrust) and
  WISDEM's rotor performance table (rigid CCBlade, ``IEA-15-240-RWT_tabular_Rotor_Performance.csv``).

Set-up: one beam blade clamped at the root with the global geometry (precone, prebend), pitched as
the reference says, in a uniform wind along the shaft (no tilt, no gravity, as the references),
3 blades, air density 1.225 kg/m^3.  Tolerances (issue 14): power and thrust 5 %; tip flapwise
deflection 10 % where the reference is at least 5 m (below, where a relative error says little,
0.5 m: 10 % of 5 m); tip elastic twist 10 %.
"""

import csv
import dataclasses
import math

import numpy as np
import pytest

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry
from windflutter.model.bundled import DATA_DIR
from windflutter.model.windio import load_turbine
from windflutter.rotor.rotating import rotor_terms
from windflutter.steady import SteadyOptions, steady_state
from windflutter.structure.assembly import assemble

RPM = math.pi / 30


@pytest.fixture(scope="module")
def iea22():
    return load_turbine("iea22mw", validate=False)  # the schema is checked in tests/model


def _iea22_refs(source):
    with open(DATA_DIR / "iea22mw" / "steady_states_hawc2_openfast.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["source"] == source]
    return {float(r["wind_speed"]): {k: float(v) for k, v in r.items() if k != "source"} for r in rows}


def _model(turbine, pitch_deg, n_span=30, part="blade"):
    """(fe, struct, strips, rotor geometry without tilt) of one beam blade at ``pitch_deg``."""
    ms = MeshSettings(model="beam", part=part, n_span=n_span, pitch=math.radians(pitch_deg))
    fe, sec = build_model(turbine, ms)
    g = rotor_geometry(turbine)
    return fe, assemble(fe), sec, dataclasses.replace(g, wind_direction=g.shaft_axis)  # no tilt


def _solve(turbine, V, rpm, pitch_deg, n_span=30, **opts):
    fe, struct, sec, g = _model(turbine, pitch_deg, n_span)
    return steady_state(fe, struct, sec, g, V, rpm * RPM, n_blades=turbine.n_blades, options=SteadyOptions(**opts))


def _errors(s, ref):
    """Relative errors of power, thrust, twist and the flap check value (relative or absolute)."""
    x_ref = ref["tip_deflection_x_m"]
    flap = (s.tip_flap / x_ref - 1) if abs(x_ref) >= 5.0 else (s.tip_flap - x_ref) / 5.0
    return (s.power / ref["mechanical_power_W"] - 1, s.thrust / ref["rotor_thrust_N"] - 1, flap,
            math.degrees(s.tip_twist) / ref["tip_rotation_z_deg"] - 1)


def _check(s, ref, tol=(0.05, 0.05, 0.10, 0.10), label=""):
    e = _errors(s, ref)
    for name, err, t in zip(("power", "thrust", "tip flap", "tip twist"), e, tol):
        assert abs(err) <= t, f"{label} {name}: {100 * err:+.1f} % (tolerance {100 * t:.0f} %)"
    return e


def test_iea22mw_steady_state_reduced(iea22):
    # The reduced default version of the slow comparison: one point below rated (9 m/s, the
    # largest deflection: 19.6 m, -4.9 deg) and one above (15 m/s, pitch 10.5 deg), 15 beam
    # elements (the 30-element results differ by < 0.7 % in power, 2 % in twist).
    refs = _iea22_refs("hawc2")
    for V in (9.0, 15.0):
        r = refs[V]
        s = _solve(iea22, V, r["rotor_speed_rpm"], r["pitch_deg"], n_span=15)
        assert s.converged and s.iterations < 30
        _check(s, r, label=f"{V} m/s")
        # the undeformed rotor at the same pitch: the issue's +20..+50 % (15 m/s)
        if V == 15.0:
            s0 = _solve(iea22, V, r["rotor_speed_rpm"], r["pitch_deg"], n_span=15, deflection=False)
            assert s0.power / r["mechanical_power_W"] - 1 > 0.2


def test_deflection_off_is_the_seeds_linearization(iea22):
    # deflection=False: the seed's centrifugal prestress (rotor_terms: K_sigma per unit Omega^2 of
    # the linear centrifugal displacement, translational mass) to round-off, and, with cone=False,
    # the BEM of the undeformed strips bit for bit (AeroelasticModel(induction=True) calls
    # sections_induction the same way).
    from windflutter.aero.induction import sections_induction

    fe, sec = build_model(iea22, MeshSettings(model="beam", part="blade", n_span=10, pitch=math.radians(5.0)))
    st = assemble(fe)
    g = dataclasses.replace(rotor_geometry(iea22), wind_direction=np.array([1.0, 0.0, 0.0]))
    om = 7.0 * RPM
    s = steady_state(fe, st, sec, g, 12.0, om, n_blades=3, options=SteadyOptions(deflection=False, cone=False))
    Ks = rotor_terms(fe, st, g).Ksigma1 * om**2
    assert abs(s.Ksigma - Ks).max() <= 1e-12 * abs(Ks).max()
    assert s.sections is sec and s.iterations == 0
    b = sections_induction(sec, g, 12.0, om, n_blades=3)
    for k in ("a", "ap", "phi", "alpha", "cl", "cd"):
        np.testing.assert_array_equal(getattr(s.bem, k), getattr(b, k), err_msg=k)
    # the deflected state's K_sigma holds the aerodynamic stress too: it differs
    s1 = steady_state(fe, st, sec, g, 12.0, om, n_blades=3)
    assert abs(s1.Ksigma - Ks).max() > 1e-3 * abs(Ks).max()


def test_three_blade_rotor_equals_one_blade(iea22):
    # part="rotor" (3 blades on the clamped hub) in the axisymmetric inflow: every blade deflects
    # like the single clamped blade, and the totals are the same (1e-6: each model's iteration
    # stops at its own iterate within the steady tolerance 1e-6; measured 6e-8)
    out = {}
    for part in ("blade", "rotor"):
        fe, sec = build_model(iea22, MeshSettings(model="beam", part=part, n_span=10, pitch=math.radians(10.5)))
        g = dataclasses.replace(rotor_geometry(iea22), wind_direction=rotor_geometry(iea22).shaft_axis)
        out[part] = steady_state(fe, assemble(fe), sec, g, 15.0, 7.06 * RPM, n_blades=3)
    one, three = out["blade"], out["rotor"]
    assert three.tip_deflection.shape == (3, 3)
    for b in range(3):
        np.testing.assert_allclose(three.tip_deflection[b], one.tip_deflection[0], rtol=1e-6, atol=1e-6)
        np.testing.assert_allclose(three.tip_rotation[b], one.tip_rotation[0], rtol=1e-6, atol=1e-9)
    assert three.power == pytest.approx(one.power, rel=1e-6)
    assert three.thrust == pytest.approx(one.thrust, rel=1e-6)


def _table(rows, head):
    print("\n" + head)
    for r in rows:
        print(" ".join(f"{v:8.3f}" if isinstance(v, float) else f"{v:>8}" for v in r))


#: IEA 22 MW points outside the tolerance since the co-rotational steady state (2 Dec 2026), each
#: with the bound it must stay within (and must exceed its tolerance: the list shrinks when a cause
#: is found).  25 m/s, HAWC2: the tip flap deflection is 0.07 m against 0.58 m (the check value is
#: the difference over 5 m: -10.3 %; the linear structure gave -8.8 %); at 21-25 m/s, where the
#: blade is pitched 17-22 deg and its flapwise deflection is a small difference of the lift and the
#: centrifugal and prebend terms, our flap is 0.2-0.5 m below HAWC2's.  Narrowed (2 Dec 2026, against
#: the reference file's root loads and load distributions): our root flap moment is 6 % low (23.4
#: against 24.9 MN m; HAWC2's flap response there is 0.41 m per MN m, which accounts for the 0.5 m);
#: the outboard third, at -2 ... -6 deg angle of attack, carries 300-500 N/m more negative load, the
#: share of a tip twist 8.7 % further towards feather (about 0.3 deg of angle of attack).  The torsion
#: moments cannot be compared directly (ours about the pitch axis, HAWC2's about the half chord: the
#: flap shear, 0.55 MN at the root, times the axes' chordwise offset is of their size); outboard of
#: mid-span, where the offset is small, they agree to 5 %.  The twist at high pitch is the open
#: question (the pitch-dependent propeller moment, 14 -> 35 kN m integrated, is too small to be it).
IEA22_KNOWN_MISSES = {("hawc2", 25.0, "tip flap"): 0.12}


def _check_listed(s, ref, tol, source, V, label):
    """_check with IEA22_KNOWN_MISSES allowed up to their bound (and required to miss)."""
    e = _errors(s, ref)
    for name, err, t in zip(("power", "thrust", "tip flap", "tip twist"), e, tol):
        bound = IEA22_KNOWN_MISSES.get((source, V, name))
        if bound is None:
            assert abs(err) <= t, f"{label} {name}: {100 * err:+.1f} % (tolerance {100 * t:.0f} %)"
        else:
            assert t < abs(err) <= bound, f"{label} {name} (listed): {100 * err:+.1f} % (listed: {100 * t:.0f}..{100 * bound:.0f} %)"
    return e


@pytest.mark.slow
def test_iea22mw_vs_hawc2_and_openfast_4_to_25(iea22):
    # Every reference point 4-25 m/s, 30 beam elements.  HAWC2: the tolerances of the module
    # docstring.  OpenFAST (BeamDyn + AeroDyn): power 5 % up to 11 m/s and thrust 5 % everywhere;
    # above rated its rotor needs 0.1-0.2 deg more pitch than HAWC2's for the same 23.1 MW (at
    # 5 MW/deg), and its tip twist differs from HAWC2's by up to 11 % (-5.06 vs -5.62 deg at
    # 12 m/s): there power 7 % and twist 12 % (our HAWC2 agreement is the tighter check).
    for source in ("hawc2", "openfast"):
        rows = []
        for V, r in sorted(_iea22_refs(source).items()):
            if not 4.0 <= V <= 25.0:
                continue
            # each reference with its code's thrust-induction relation (aero/momentum.py; the
            # difference is <= 1.1 point here, the IEA 22 MW runs below C_T = 0.85)
            s = _solve(iea22, V, r["rotor_speed_rpm"], r["pitch_deg"],
                       bem={"high_thrust": "madsen" if source == "hawc2" else "buhl"})
            if source == "hawc2":
                tol = (0.05, 0.05, 0.10, 0.10)
            else:
                tol = (0.05 if V <= 11 else 0.07, 0.05, 0.10, 0.12)
            e = _check_listed(s, r, tol, source, V, f"{source} {V} m/s")
            rows.append((V, s.power / 1e6, 100 * e[0], s.thrust / 1e3, 100 * e[1], s.tip_flap, r["tip_deflection_x_m"],
                         math.degrees(s.tip_twist), r["tip_rotation_z_deg"], s.iterations))
        _table(rows, f"IEA 22 MW vs {source}: V  P(MW) dP%  T(kN) dT%  flap ref  twist ref  iterations")


def _iea15_wisdem():
    out = []
    with open(DATA_DIR / "iea15mw" / "IEA-15-240-RWT_tabular_Rotor_Performance.csv") as f:
        for row in csv.reader(f):
            try:
                v = [float(x) for x in row[:13]]
            except ValueError:
                continue
            out.append(v)
    return np.array(out)


#: The HAWCStab2 operating points were computed on the IEA 15 MW *HAWC2* model, whose blade is the
#: windIO blade described about its half-chord line (HAWC2's c2_def) with its sections normal to
#: that line: the line sweeps in the chord plane as the chord tapers and the pitch axis moves
#: (0.5 c at the root, 0.29 c outboard), and the turned section planes see a share of the flapwise
#: bending moment as torsion (about 1.5 deg more tip twist towards feather at rated).  The windIO
#: blade's sections are normal to its pitch axis.  The co-rotational steady state does not depend on
#: the line's position for a given blade (test_steady_reference_axis.py), so the two descriptions
#: are two blades.  Measured (2 Dec 2026, 30 elements): the half-chord description within 1.3 % of
#: HAWCStab2 in power and thrust at 7-25 m/s; the windIO description up to +7.1 % in thrust (11 m/s)
#: and -9.4 % in power (25 m/s).  The IEA 15 MW HAWC2 files themselves (IEAWindTask37 repository,
#: not bundled: the pc file is 0.5 MB) read by windflutter's HAWC2 reader give -0.3 ... +0.1 % at
#: 8-15 m/s.
IEA15_WINDIO_BOUND = 0.10


@pytest.mark.slow
def test_iea15mw_vs_hawcstab2_and_wisdem():
    # HAWCStab2 operating points of the onshore HAWC2 model (aero power, thrust): the blade as the
    # HAWC2 model describes it (moved_reference(.., 0.5), the comment above) with HAWC2's
    # thrust-induction relation (Madsen et al. 2020): 5 % on power and thrust at 3-25 m/s (issue 14;
    # measured -1.6 ... +1.3 %).  With Buhl's relation (the default) power at 3 and 5 m/s is -24 and
    # -8 % (tip-speed ratio 21 and 12.6, local C_T above 0.85, where the relations part): held
    # below -10 % at 3 m/s, so that the check can fail, and to 5 % from 7 m/s.  The windIO
    # description: within IEA15_WINDIO_BOUND, and more than 5 % off near rated (the description
    # matters: the check can fail).
    # WISDEM: rigid CCBlade (no deflection) with its own pitch schedule, so our undeformed state
    # (deflection=False, coned BEM as CCBlade's): thrust 5 %; power 7 % (we are 2-6 % above it;
    # CCBlade in WISDEM runs with the 6 deg shaft tilt, not modelled here, and its own BEM details).
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from reference_axis import moved_reference

    t = load_turbine("iea15mw", validate=False)
    c2 = moved_reference(t, 0.5)
    h = np.loadtxt(DATA_DIR / "iea15mw" / "IEA_15MW_RWT_Onshore_hawc2.opt", skiprows=1)
    rows, worst_windio = [], 0.0
    hawc2 = {"high_thrust": "madsen"}  # HAWCStab2's thrust-induction relation (aero/momentum.py)
    for V, pitch, rpm, p_kw, t_kn in h[h[:, 0] >= 3]:
        s = _solve(c2, V, rpm, pitch, bem=hawc2)
        dp, dt = s.power / (1e3 * p_kw) - 1, s.thrust / (1e3 * t_kn) - 1
        assert abs(dp) <= 0.05, ("power", V, dp)
        assert abs(dt) <= 0.05, ("thrust", V, dt)
        b = _solve(c2, V, rpm, pitch)  # Buhl's relation (the default, AeroDyn's)
        dpb = b.power / (1e3 * p_kw) - 1
        if V >= 7:
            assert abs(dpb) <= 0.05, ("power, Buhl", V, dpb)
        elif V == 3:
            assert dpb < -0.10, ("power, Buhl", V, dpb)  # the relation matters at C_T > 0.85
        w = _solve(t, V, rpm, pitch, bem=hawc2)
        dpw, dtw = w.power / (1e3 * p_kw) - 1, w.thrust / (1e3 * t_kn) - 1
        if V >= 7:
            assert max(abs(dpw), abs(dtw)) <= IEA15_WINDIO_BOUND, ("windIO", V, dpw, dtw)
        if 10 <= V <= 13:
            worst_windio = max(worst_windio, abs(dtw))
        rows.append((V, s.power / 1e6, 100 * dp, s.thrust / 1e3, 100 * dt, s.tip_flap, math.degrees(s.tip_twist),
                     100 * dpb, 100 * dpw, 100 * dtw))
    assert worst_windio > 0.05
    _table(rows, "IEA 15 MW (half-chord description, HAWC2's induction) vs HAWCStab2: V  P(MW) dP%  T(kN) dT%  "
                 "flap twist | Buhl dP% | windIO dP% dT%")
    rows = []
    w = _iea15_wisdem()
    for V, pitch, _, _, _, rpm, _, T_MN, _, Q_MNm in w[::3, :10]:
        s = _solve(t, V, rpm, pitch, deflection=False)
        P = Q_MNm * 1e6 * rpm * RPM
        dp, dt = s.power / P - 1, s.thrust / (1e6 * T_MN) - 1
        rows.append((V, s.power / 1e6, 100 * dp, s.thrust / 1e6, 100 * dt))
        assert abs(dt) <= 0.05, (V, dt)
        if V >= 4:
            assert abs(dp) <= 0.07, (V, dp)
    _table(rows, "IEA 15 MW (undeformed) vs WISDEM: V  P(MW) dP%  T(MN) dT%")


def test_iea15mw_steady_state_is_the_corotational_beams_equilibrium():
    """The steady state of a beam blade is an equilibrium of the co-rotational beam (the default,
    steady/exact.py): a Newton iteration from it under its own loads (system/deflected.py, the
    method-p linearization) stops after one step at the same configuration (1e-9 m).  The linear
    structure with second-order corrections (``corotational=False``), the default, lands
    near it on this blade (IEA 15 MW, 13 m/s; its mass centres lie 0.1-0.2 chord aft of the pitch
    axis): measured tip flap 8.82 against 8.98 m, twist -4.36 against -4.24 deg (last strip),
    thrust -1.0 %; held to 3 %, 0.3 deg and 2 % (two theories of one beam; the linear one is
    reference-line dependent, tests/steady/test_steady_reference_axis.py)."""
    from windflutter.system.blade import RotorBlade
    from windflutter.system.deflected import deflected_blade

    t = load_turbine("iea15mw", validate=False)
    V, pitch, rpm = 13.0, 6.052129, 7.559987  # the HAWCStab2 operating point (bundled .opt)
    fe, struct, sec, g = _model(t, pitch, part="rotor_blade")
    s = steady_state(fe, struct, sec, g, V, rpm * RPM, n_blades=3, options=SteadyOptions(corotational=True))
    assert s.configuration is not None
    rb = RotorBlade(fe, struct, sec, np.asarray(g.hub_center, float), np.asarray(g.shaft_axis, float))
    d = deflected_blade(rb, s, rpm * RPM)
    assert d.equilibrium.iterations == 1
    assert np.abs(d.equilibrium.config.x - s.configuration.x).max() < 1e-9
    lin = steady_state(fe, struct, sec, g, V, rpm * RPM, n_blades=3, options=SteadyOptions(corotational=False))
    assert lin.configuration is None
    assert lin.tip_flap == pytest.approx(s.tip_flap, rel=0.03)
    assert math.degrees(lin.tip_twist) == pytest.approx(math.degrees(s.tip_twist), abs=0.3)
    assert lin.thrust == pytest.approx(s.thrust, rel=0.02)
