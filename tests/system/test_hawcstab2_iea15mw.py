"""The IEA 15 MW whole turbine against a HAWCStab2 Campbell analysis of it (tests/data/iea15mw_hawcstab2,
DLR-AE/CampbellViewer, Apache-2.0).

Criterion (issue 15): every HAWCStab2 mode below 2.2 Hz with a damping ratio below 10 % is matched by a
windflutter mode within 5 % in frequency and within 1 point or 40 % in damping ratio, for at least 85 %
of them at 5, 10, 15, 20 and 25 m/s, and no windflutter mode has negative damping.  The matching is one
to one (a maximum bipartite matching), windflutter modes of any name.  Configuration: HAWCStab2's
operating point (rotor speed, pitch) at each wind speed; the beam model with the turbine file's blade
damping (BeamDyn mu) and the tower damping of HAWCStab2's model, 0.1 % in every tower mode (its
structural Campbell, structural_entire_turbine.cmb; the ElastoDyn tower file has 1 %); the HAWCStab2
model's tower and blade data are its own (differences in docs/campbell.md).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hawcstab2_reference import (DATA, WINDS, hawcstab2_1st_tower_modes, hawcstab2_continued, hawcstab2_labelled,
                                 amplitude_rows, hawcstab2_modes, matches, operating_point, phase_misfit, phase_pairs, shape_pairs)


def _points(turbine, winds=WINDS, **options):
    """Our modes (not rigid, < 8.1 Hz) at HAWCStab2's operating points, by wind speed."""
    from windflutter.system.modes import point_modes
    from windflutter.system.operational import OperationalModel, OperationalOptions

    om = OperationalModel(turbine, OperationalOptions(mesh={"n_span": 20}, tower_damping=0.001,
                                                      structure="deflected", **options))  # (config auto: deflected)
    out = {}
    for v in winds:
        rpm, pitch = operating_point(v)
        ps = om.at(v, rpm=rpm, pitch=np.radians(pitch))
        out[v] = [m for m in point_modes(ps, max_hz=8.1) if not m.rigid]  # (the tests below use < 2.2 and < 8 Hz)
    return out


@pytest.fixture(scope="module")
def windflutter_points():
    """The IEA 15 MW of its windIO file with our defaults."""
    from windflutter.model import load_turbine

    return _points(load_turbine("iea15mw"))


@pytest.fixture(scope="module")
def hawcstab2_configuration_points():
    """The IEA 15 MW as HAWCStab2 ran it: the blade described as its HAWC2 model describes it (about
    the half-chord line, sections normal to it: tests/reference_axis.py::moved_reference, the
    steady-state comparison's configuration, tests/steady/test_steady_references.py) and HAWC2's
    thrust-induction relation (aero/momentum.py, ``high_thrust="madsen"``)."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from reference_axis import moved_reference

    from windflutter.model import load_turbine

    return _points(moved_reference(load_turbine("iea15mw", validate=False), 0.5), high_thrust="madsen")


def hawcstab2_structural(wind: float, max_hz: float):
    d = np.loadtxt(DATA / "structural_entire_turbine.cmb", comments="#")
    f = np.sort(d[np.argmin(np.abs(d[:, 0] - wind)), 1:61])
    return f[(f > 1e-3) & (f < max_hz)]


@pytest.mark.parametrize("wind", [1.0, 10.0])
def test_iea15mw_structural_modes_match_hawcstab2(wind):
    """Without aerodynamics, at HAWCStab2's rotor speed: the multi-blade model's modes below 2.4 Hz
    (tower, flap and edge BW / collective / FW, the collective edge with the drivetrain, 2nd flap,
    2nd tower) against HAWCStab2's structural Campbell, in frequency order.  Measured 0.05-3.2 % (the
    largest: the 2nd tower side-side mode; the two models' tower and blade data differ: windIO 6x6 and
    tower here, HAWCStab2's own model there); tolerance 4 %."""
    from windflutter.model import load_turbine
    from windflutter.system.modes import point_modes
    from windflutter.system.operational import OperationalModel, OperationalOptions

    om = OperationalModel(load_turbine("iea15mw"), OperationalOptions(mesh={"n_span": 20}, aero=None))
    rpm, pitch = operating_point(wind)
    ours = np.sort([m.frequency_hz for m in point_modes(om.at(wind, rpm=rpm, pitch=np.radians(pitch)), max_hz=2.4)
                    if not m.rigid])
    ref = hawcstab2_structural(wind, 2.3)
    assert ours.size >= ref.size
    np.testing.assert_allclose(ours[:ref.size], ref, rtol=0.04)


def test_matcher_counts_one_to_one():
    f_ref, z_ref = np.array([1.0, 1.02]), np.array([0.02, 0.02])
    assert matches(f_ref, z_ref, np.array([1.01]), np.array([0.021])) == 1  # one mode matches one reference
    assert matches(f_ref, z_ref, np.array([1.01, 1.0]), np.array([0.021, 0.05])) == 1  # second: damping off
    assert matches(f_ref, z_ref, np.array([1.2]), np.array([0.02])) == 0


def _matched(windflutter_points, max_hz: float, ours_below: float = np.inf):
    """(matched, total, lines) of HAWCStab2's modes below ``max_hz`` (< 10 % damping) against our
    modes below ``ours_below`` Hz, wind speed by wind speed."""
    total = hit = 0
    lines = []
    for v, modes in windflutter_points.items():
        f_ref, z_ref = hawcstab2_modes(v, max_hz=max_hz)
        modes = [m for m in modes if m.frequency_hz < ours_below]
        f = np.array([m.frequency_hz for m in modes])
        z = np.array([m.damping_ratio for m in modes])
        assert np.all(z > 0), f"negative damping at {v} m/s: {[m.name for m in modes if m.damping_ratio <= 0]}"
        n = matches(f_ref, z_ref, f, z)
        total += f_ref.size
        hit += n
        lines.append(f"{v:4.0f} m/s: {n}/{f_ref.size} HAWCStab2 modes below {max_hz:g} Hz matched")
    print("\n".join(lines))
    return hit, total, "\n".join(lines)


def test_iea15mw_modes_match_hawcstab2(windflutter_points):
    hit, total, lines = _matched(windflutter_points, 2.2, ours_below=2.3)
    assert hit >= 0.85 * total, lines


def test_iea15mw_modes_to_8_hz_match_hawcstab2(windflutter_points):
    """The same one-to-one matching of every HAWCStab2 mode below 8 Hz with less than 10 % damping
    (the 2nd and 3rd edge, the 2nd-4th flap families, the 1st torsion, the 2nd and 3rd tower), names
    not used: 5 % in frequency, 1 point or 40 % in damping ratio.  Measured 98 of 123 (80 %: 17-24
    per wind speed); required 75 %, so that losing more than six of them fails."""
    hit, total, lines = _matched(windflutter_points, 8.0)
    assert hit >= 0.75 * total, lines


# ---------------------------------------------------------------------------- family by family
FAMILY_PAIRS = {("BW edge", 1): "1st edge BW", ("FW edge", 1): "1st edge FW", ("Sym edge", 1): "1st edge collective",
                ("BW flap", 1): "1st flap BW", ("FW flap", 1): "1st flap FW", ("Sym flap", 1): "1st flap collective"}

#: pairs that miss the criterion today with the blade linearized about its deflected shape (the
#: default; docs/notes/iea15mw_hawcstab2.md): the 1st edge BW at rated wind (zeta 3.01 % against 1.55 %: the
#: BW/FW split, a support question, docs/notes/edgewise_damping.md sec. 8).  The 1st edge collective at
#: 25 m/s (2.76 % against 4.24 %, decay rate -35 %) missed until the beams' rotating-frame terms got
#: the sections' mass-centre offsets (windflutter.rotor.spin): 2.89 %, decay rate inside 35 %.  (The
#: undeformed blade missed the 1st edge BW at 10 m/s and the 1st flap collective at 25 m/s.)
#: With the co-rotational steady state (SteadyOptions.corotational, the default) the 1st edge
#: collective at 25 m/s is back at the border: 2.84 % against 4.24 %, decay-rate ratio 0.646 for a
#: bound of 0.65 (0.661 with the linear steady structure); its frequency is 3 % low (1.183 against
#: 1.223 Hz), a drivetrain-coupled mode.
KNOWN_MISSES = {("1st edge BW", 10.0), ("1st edge collective", 25.0)}


#: in HAWCStab2's configuration (the fixture hawcstab2_configuration_points) every pair passes; the
#: closest is the 1st edge BW at rated wind, by the 1-point rule: zeta 2.33 % against 1.55 % (0.78
#: point), decay-rate ratio 1.49 (with the windIO description 3.01 %, ratio 1.91: a miss).
KNOWN_MISSES_HAWCSTAB2_CONFIGURATION: set = set()


def test_iea15mw_damping_family_by_family_against_hawcstab2(windflutter_points):
    """Issue 14's criterion, mode by mode: the decay rate sigma = -Re(lambda) of the 1st edge modes
    within 35 % of HAWCStab2's or the damping ratio within 1 point; the 1st flap modes' damping ratio
    within 25 % (where it is below 0.6).  HAWCStab2's modes named by their own amplitudes.  Every pair
    passes except KNOWN_MISSES, which must still miss (so the list cannot go stale)."""
    _family_by_family(windflutter_points, KNOWN_MISSES)


def test_iea15mw_damping_in_hawcstab2s_configuration(hawcstab2_configuration_points):
    """The same criterion with the blade and the induction as HAWCStab2 had them (the fixture):
    measured, all 30 pairs pass: the 1st flap damping within 5 % of HAWCStab2's from 10 m/s on (+19 %
    at 5 m/s), the 1st edge collective at 25 m/s at its frequency (1.223 Hz) and inside the bound
    (ratio 0.79), the 1st edge BW at 10 m/s within 1 point (0.78).  The modes below 2.2 Hz match
    as in the default configuration (>= 85 %)."""
    _family_by_family(hawcstab2_configuration_points, KNOWN_MISSES_HAWCSTAB2_CONFIGURATION)
    hit, total, lines = _matched(hawcstab2_configuration_points, 2.2, ours_below=2.3)
    assert hit >= 0.85 * total, lines


def _pairs(points, pairs):
    """(wind, our name, our mode, HAWCStab2 natural frequency Hz, damping ratio, decay-rate ratio) of
    the name pairs ``pairs`` at every wind speed.  HAWCStab2's frequencies are damped frequencies
    (Im lambda / 2 pi): its natural frequency is ``f / sqrt(1 - zeta^2)`` and its decay rate
    ``zeta 2 pi f / sqrt(1 - zeta^2)``.  (Measured: converted so, its 1st flap frequencies at
    10-25 m/s are within 1.8 % of our |lambda| / 2 pi in HAWCStab2's configuration; as natural
    frequencies they were 2.9-8.0 % below.)"""
    for v, modes in points.items():
        ours = {m.identity_name: m for m in modes}
        ref = hawcstab2_labelled(v)
        for key, name in pairs.items():
            f, z = ref[key]
            m = ours[name]
            f_n = f / np.sqrt(1 - z**2)
            yield v, name, m, f_n, z, -m.eigenvalue.real / (z * 2 * np.pi * f_n)


def _family_by_family(points, known_misses):
    fails, lines = set(), []
    for v, name, m, f, z, ratio in _pairs(points, FAMILY_PAIRS):
        # the same mode: 10 % in natural frequency (measured: the 1st flap at 5 m/s, 45-55 % damped,
        # up to 7.8 % apart; everything else within 3 %)
        assert abs(m.frequency_hz - f) <= 0.10 * f, (v, name, m.frequency_hz, f)
        if "edge" in name:
            ok = abs(ratio - 1) <= 0.35 or abs(m.damping_ratio - z) <= 0.01
        else:
            ok = z >= 0.6 or abs(m.damping_ratio / z - 1) <= 0.25
        lines.append(f"{v:4.0f} m/s {name:20s} ours {100 * m.damping_ratio:6.2f} %  HAWCStab2 {100 * z:6.2f} %  "
                     f"{'ok' if ok else 'MISS'}")
        if not ok:
            fails.add((name, v))
    print("\n".join(lines))
    assert fails == known_misses, "\n".join(lines)


#: the 2nd flap family as HAWCStab2 continues it from its structural modes (hawcstab2_continued)
SECOND_FLAP = {("BW flap", 2): "2nd flap BW", ("Sym flap", 2): "2nd flap collective"}


def _root(f: float, z: float) -> complex:
    w = 2 * np.pi * f
    return complex(-z * w, w * np.sqrt(max(1 - z * z, 0.0)))


@pytest.mark.parametrize("points", ["windflutter_points", "hawcstab2_configuration_points"])
def test_iea15mw_2nd_flap_as_hawcstab2_continues_it(request, points):
    """The 2nd flap BW and collective modes: ours, named by their participation in the blade's 2nd
    flap (system/identity.py), against HAWCStab2's modes of the same identity -- the ones its own
    continuation carries from its structural 2nd BW and Sym flap modes (1.41 and 1.50 Hz at 3 m/s;
    its mode numbers 11 and 12; hawcstab2_continued).  Above 5 m/s both codes carry them into
    58-68 % damped roots at 3-4.4 Hz (natural frequency); a 20-26 % damped flap mode at 2.5 Hz, which
    HAWCStab2 continues from its structural 3rd flap, is then the lower one (named by frequency order
    within HAWCStab2's labels it had been taken for the 2nd flap: 6-8 of 15 pairs identified).
    The same root: of all HAWCStab2's roots with that label at that wind speed, its continued 2nd
    flap is the nearest to ours in the complex plane (at these damping ratios the natural frequency
    alone does not tell them apart: with 20 strips ours are 8-19 % lower, with the default strips
    0-8 %).  Decay rate within issue 14's 35 %.  Measured: decay-rate ratios 0.76-0.97 (20 strips,
    both configurations)."""
    pts = request.getfixturevalue(points)
    lines = []
    for v, modes in pts.items():
        ours = {m.identity_name: m for m in modes}
        rows = [r for r in amplitude_rows(v) if abs(float(r["damping_pct"])) < 99.0]
        for (label, order), name in SECOND_FLAP.items():
            f, z = hawcstab2_continued(label, order, v)
            m = ours[name]
            ratio = -m.eigenvalue.real / (z * 2 * np.pi * f)
            others = [_root(float(r["frequency_hz"]) / np.sqrt(1 - (float(r["damping_pct"]) / 100) ** 2),
                            float(r["damping_pct"]) / 100) for r in rows if r["blade_label"] == label]
            nearest = min(others, key=lambda lam: abs(lam - m.eigenvalue))
            lines.append(f"{v:4.0f} m/s {name}: {m.frequency_hz:.3f} Hz {100 * m.damping_ratio:.1f} % against "
                         f"{f:.3f} Hz {100 * z:.1f} %, decay-rate ratio {ratio:.3f}")
            assert abs(nearest - _root(f, z)) < 1e-6 * abs(nearest), "\n".join(lines)
            assert abs(ratio - 1) <= 0.35, "\n".join(lines)
    print("\n".join(lines))


def test_tower_names_are_limited_to_the_supports_modes(windflutter_points):
    """A blade mode coupled with the tower is named by its blade motion when the support has no
    structural mode left for it (the identities of system/identity.py, each used once per point).  The IEA 15 MW support
    alone has its 2nd fore-aft and side-side modes at 1.97 and 2.00 Hz and its 3rd side-side at 5.8
    Hz; at 10 m/s four modes at 1.76-2.13 Hz carry most of their energy in the tower, and were named
    the 2nd fore-aft and the 2nd, "3rd" and "4th" side-side modes, with "2nd edge BW" on the blade's
    3rd edge at 4.35 Hz.  Now: no "3rd tower side-side" below 4 Hz at any wind speed, one 2nd side-
    side mode, and the 2nd edge BW between the 1st edge collective and 2.5 Hz at 10 m/s."""
    for v, modes in windflutter_points.items():
        names = [m.name for m in modes if m.frequency_hz < 4.0]
        assert "3rd tower side-side" not in names and "4th tower side-side" not in names, (v, names)
        assert names.count("2nd tower side-side") <= 1, (v, names)
    by = {m.identity_name: m for m in windflutter_points[10.0]}
    assert by["1st edge collective"].frequency_hz < by["2nd edge BW"].frequency_hz < 2.5


def test_whirl_amplitudes_count_as_hawcstab2s(hawcstab2_configuration_points):
    """Our multi-blade tip amplitudes are on HAWCStab2's scale (``ModeRecord.multiblade_components``):
    in the 1st tower modes, where the tower top and the collective flap are plain displacements in
    both codes, HAWCStab2's file gives its cyclic (BW/FW) tip amplitudes twice as large, relative to
    those, as the blades' whirl amplitude ``|a_c -+ i a_s| / 2`` (measured at 5-25 m/s: 2.06-2.30 x,
    while the tower top over the collective flap agrees to 1.06-1.09; the tip in the blade's
    pitching frame, 3 Dec 2026): its whirling parts are
    ``a_c -+ i a_s``.  Held: the cyclic ratios (side-side: largest cyclic tip amplitude over the tower
    top; fore-aft: over the collective flap) within 25 % of HAWCStab2's at every wind speed, as the
    non-cyclic one is; with the half they are 0.44-0.49 and the test fails."""
    cyc = ("bw_edge", "fw_edge", "bw_flap", "fw_flap")
    for v, modes in hawcstab2_configuration_points.items():
        ours = {m.identity_name: m.multiblade_amplitudes() for m in modes}
        ss, fa = hawcstab2_1st_tower_modes(v)
        a, b = ours["1st tower side-side"], ours["1st tower fore-aft"]
        pairs = {"SS cyclic / tower": (max(float(ss[k]) for k in cyc) / float(ss["twr_x"]), max(a[k] for k in cyc) / a["tower_ss"]),
                 "FA cyclic / collective": (max(float(fa[k]) for k in cyc) / float(fa["sym_flap"]), max(b[k] for k in cyc) / b["sym_flap"]),
                 "FA tower / collective": (float(fa["twr_y"]) / float(fa["sym_flap"]), b["tower_fa"] / b["sym_flap"])}
        for what, (h, w) in pairs.items():
            assert w / h == pytest.approx(1.0, abs=0.25), (v, what, h, w)


@pytest.mark.parametrize("points, min_identified", [("windflutter_points", 7), ("hawcstab2_configuration_points", 8)])
def test_iea15mw_1st_torsion_decay_rates_by_mode_shape(request, points, min_identified):
    """Issue 14's 35 % band on the 1st torsion modes' decay rate.  HAWCStab2 names none of its modes;
    its amplitude file gives each mode's blade-tip motion (flap, edge, torsion in symmetric, BW and FW
    components), and ours gives the same quantities, so the torsion modes are paired by that shape, not
    by frequency alone (between 6.5 and 8 Hz both codes have 3-5 edge-torsion-flap modes per wind
    speed within a few per cent).  Measured (2 Dec 2026; HAWCStab2's torsion-labelled modes: 3, 1, 3, 1
    and 1 at 5-25 m/s): with the windIO description 7 of the 9 paired, decay-rate ratios 0.81-1.05,
    tip shapes alike to cosines 0.87-0.99; in HAWCStab2's configuration 8 of 9, ratios 0.85-1.05,
    cosines 0.88-1.00; both counts required.  Our natural frequencies are 5-7 % below HAWCStab2's,
    hence the 10 % window (the collective torsion modes lie 5.5-6.5 % apart).  The 5 m/s BW torsion
    mode (a mix of BW and FW flap, edge and torsion) has no counterpart in either configuration, the
    15 m/s one none with the windIO description.  Ours are named "1st torsion ..." or, where the
    torsion couples with flap, "n-th flap ..." (the largest strip-motion energy): the names are not
    used.  Without the support-share rule the windIO description's 15 m/s BW torsion mode paired with
    our 4th tower fore-aft mode (6.58 Hz, 65 % of its energy in the tower, 2.6 % damped: ratio 0.31),
    whose tip moves alike; HAWCStab2's tower top moves 0.2 % of its blade tip in that mode."""
    pts = request.getfixturevalue(points)
    identified, lines = 0, []
    for v, label, f, z, m, cos in shape_pairs(pts):
        if m is None:
            lines.append(f"{v:4.0f} m/s HAWCStab2 {label} {f:.3f} Hz: no mode of ours with its tip shape")
            continue
        identified += 1
        ratio = -m.eigenvalue.real / (z * 2 * np.pi * f)
        lines.append(f"{v:4.0f} m/s HAWCStab2 {label} {f:.3f} Hz zeta {100 * z:.2f} % <- {m.name} "
                     f"{m.frequency_hz:.3f} Hz zeta {100 * m.damping_ratio:.2f} % (cos {cos:.2f}): ratio {ratio:.2f}")
        assert abs(ratio - 1) <= 0.35, "\n".join(lines)
    print("\n".join(lines))
    assert identified >= min_identified, "\n".join(lines)


#: HAWCStab2's 2nd-edge-region modes (wind speed, natural frequency Hz rounded to 0.01) that miss the
#: criterion, by configuration; each must still miss, so the lists cannot go stale
SECOND_EDGE_MISSES = {
    "windflutter_points": {(5.0, 2.03), (10.0, 2.0), (10.0, 2.08), (25.0, 1.91)},
    "hawcstab2_configuration_points": {(5.0, 2.03), (10.0, 2.0), (10.0, 2.08)},
}


@pytest.mark.parametrize("points", ["windflutter_points", "hawcstab2_configuration_points"])
def test_iea15mw_2nd_edge_damping_by_mode_shape(request, points):
    """Issue 14's edge criterion (decay rate within 35 % or the damping ratio within 1 point) for the
    2nd edge region: HAWCStab2's 1.6-2.45 Hz modes whose largest tip amplitude is an edge one (4-5 per
    wind speed, all labelled "BW edge" or "FW edge" there: 2nd edge, 2nd tower and coupled flap modes
    mixed), paired by tip and tower-top shape as the torsion modes (any share of support energy: the
    2nd tower modes of both codes are among them).  Measured (2 Dec 2026): all 20 paired, shape cosines
    0.90-1.00 (ours named 2nd tower fore-aft / side-side, 2nd edge BW / FW, 2nd / 3rd flap BW / FW);
    16 pass with the windIO description, 17 in HAWCStab2's configuration.  The misses (SECOND_EDGE_
    MISSES) are the 2.0-2.1 Hz BW modes at 5 and 10 m/s where our 2nd tower side-side and 2nd edge BW
    modes couple (ours 4.2-6.8 % damped against HAWCStab2's 1.75-3.4 %: a tower-edge coupling that the
    two codes' towers place differently), and with the windIO description the 25 m/s FW mode at 1.91
    Hz (0.79 % against 1.87 %; 1.57 % in HAWCStab2's configuration)."""
    pts = request.getfixturevalue(points)
    lines, misses, n = [], set(), 0
    for v, label, f, z, m, cos in shape_pairs(pts, 1.6, 2.45, kind="edge", max_support=1.01, tower=True):
        assert m is not None, f"{v} m/s HAWCStab2 {label} {f:.3f} Hz has no mode of ours with its shape"
        n += 1
        ratio = -m.eigenvalue.real / (z * 2 * np.pi * f)
        dz = m.damping_ratio - z
        ok = abs(ratio - 1) <= 0.35 or abs(dz) <= 0.01
        lines.append(f"{v:4.0f} m/s HAWCStab2 {label} {f:.3f} Hz zeta {100 * z:.2f} % <- {m.name} {m.frequency_hz:.3f} Hz "
                     f"zeta {100 * m.damping_ratio:.2f} % (cos {cos:.2f}): ratio {ratio:.2f}, {100 * dz:+.2f} point"
                     + ("" if ok else "  MISS"))
        if not ok:
            misses.add((v, round(float(f), 2)))
    print("\n".join(lines))
    assert n == 20, "\n".join(lines)
    assert misses == SECOND_EDGE_MISSES[points], "\n".join(lines)


@pytest.mark.parametrize("points", ["windflutter_points", "hawcstab2_configuration_points"])
def test_iea15mw_2nd_edge_region_summed_decay_rate(request, points):
    """The decay rates summed over every mode of the 2nd edge region (1.6-2.45 Hz, the region of the
    test above, damping ratio below 30 %) against HAWCStab2's sum: within 20 %, with the same number
    of modes in the region in both codes.  A sum of eigenvalues over a cluster of close modes is the
    trace of the system on that cluster, unchanged by how the coupling inside it shares the damping
    out, so it separates "too much aerodynamic damping" from "the damping shared out differently".
    Measured (2 Dec 2026): 0.90-1.09 (windIO description), 0.94-1.08 (HAWCStab2's configuration), five
    modes each at every wind speed, although the 2.0-2.1 Hz modes one by one miss by 1.6-2.4 x
    (SECOND_EDGE_MISSES): in HAWCStab2 the 2nd flap BW (2.00 Hz, 15.5 % at 10 m/s) carries the damping
    that ours (2.13 Hz, 12.5 %) shares with the 2nd tower side-side and 2nd edge BW.  What it does not
    check: the sum is mostly flap damping (the 2nd flap BW alone is half of it), so it hardly sees the
    edgewise mean-load terms (without them 0.92-1.08); the quasi-steady circulation fails it (1.39 at
    15 m/s), so does the blade without structural damping (0.73 at 5 m/s).  Tolerance: the issue's
    35 % for one decay rate, over five modes whose errors are not all of one sign (35 / sqrt 5 = 16 %),
    rounded up.  Above 30 % a root's natural frequency says little about which modes it mixes with
    (HAWCStab2's 47 %-damped 2nd flap collective at 5 m/s has its natural frequency in the region)."""
    lo, hi, max_zeta = 1.6, 2.45, 0.30
    lines, bad = [], []
    for v, modes in request.getfixturevalue(points).items():
        fn, zk = hawcstab2_modes(v, max_hz=hi, max_zeta=max_zeta)
        inside = (fn > lo) & (fn < hi)
        ref = float(np.sum(zk[inside] * 2 * np.pi * fn[inside]))
        ours = [m for m in modes if lo < m.frequency_hz < hi and m.damping_ratio < max_zeta]
        ratio = sum(-m.eigenvalue.real for m in ours) / ref
        lines.append(f"{v:4.0f} m/s summed decay rate {ref:.3f} 1/s (HAWCStab2, {int(inside.sum())} modes), "
                     f"ours x {ratio:.2f} ({len(ours)} modes: {', '.join(m.name for m in ours)})")
        if len(ours) != int(inside.sum()) or abs(ratio - 1) > 0.20:
            bad.append(v)
    print("\n".join(lines))
    assert not bad, "\n".join(lines)


def test_tower_top_yaw_as_hawcstab2s(hawcstab2_configuration_points):
    """The tower top's yaw (``tower_yaw``, the .amp file's TWR yaw column) in the 1st tower side-side
    mode, where the tower twists with its sideways bending (the rotor hangs ahead of the tower axis),
    over the side-side displacement: within 25 % of HAWCStab2's (as the other amplitude ratios).
    Measured (3 Dec 2026) 1.07-1.11 x HAWCStab2's 0.0024-0.0026 rad/m at 5-25 m/s; in the 1st edge
    whirling modes, per metre of tip edge, 0.83-1.09 x except the BW at 10 m/s (1.53 x, 6.7e-5 rad)."""
    for v, modes in hawcstab2_configuration_points.items():
        ours = {m.identity_name: m.multiblade_amplitudes() for m in modes}["1st tower side-side"]
        ss, _ = hawcstab2_1st_tower_modes(v)
        h, w = float(ss["twr_yaw"]) / float(ss["twr_x"]), ours["tower_yaw"] / ours["tower_ss"]
        assert w / h == pytest.approx(1.0, abs=0.25), (v, h, w)


def test_mode_shape_phases_as_hawcstab2s(hawcstab2_configuration_points):
    """The phases of our mode shapes against HAWCStab2's amplitude file (its .amp phases, modes.csv
    ``*_ph``), every mode below 2.2 Hz paired by its magnitudes (cosine >= 0.9, natural frequency
    within 8 %) at 5-25 m/s and with at least four components above 5 % of its largest in both codes
    (two phases per mode are fitted: each code's eigenvector has its own time origin).  The file's
    convention is found, not assumed: of 24 readings (the FW, the BW or no group conjugated; any of
    flap, edge and torsion reversed; blade 1's azimuth origin on a 3 deg grid, one for all wind
    speeds) the best must be the FW components conjugated (HAWCStab2 writes a FW part as the whirl's
    negative-frequency part), the edge reversed (its blade axes, against our pitching frame), the
    azimuth origin a quarter turn off (270 +- 6 deg), every mode within 30 deg in it, their mean
    within 8 deg and every reading with another conjugation at least twice that mean.  Measured (3 Dec
    2026), 37 modes: 273 deg, mean 4.9 deg, largest 19 deg (the 2nd tower side-side at 15 m/s, a
    tower-edge coupled mode); torsion reversed too 11.0 deg, the other FW-conjugated readings
    14.8-58.5 deg; BW conjugated 36.8-42.4 deg; none conjugated 41.1-56.1 deg.  The "FW flap phase" difference once read in
    docs/notes/edgewise_damping.md sec. 11 was this convention."""
    pairs = [(v, h, w, m) for v, h, w, m in phase_pairs(hawcstab2_configuration_points)
             if phase_misfit(h, w, set(), set(), 0.0)[1] >= 4]
    assert len(pairs) >= 30, len(pairs)
    found = []
    for conj in ({"fw"}, {"bw"}, set()):
        for flip in ({k for k, on in zip(("flap", "edge", "tors"), bits) if on} for bits in np.ndindex(2, 2, 2)):
            grid = np.arange(0, 360, 3)  # the mean misfit of the pairs at every azimuth origin, at once
            means = np.mean([phase_misfit(h, w, conj, flip, np.radians(grid))[0] for _, h, w, _ in pairs], axis=0)
            mean, az = float(means.min()), int(grid[np.argmin(means)])
            found.append((mean, az, sorted(conj), sorted(flip)))
    found.sort()
    (mean, az, conj, flip), others = found[0], found[1:]
    each = [(v, m.name, phase_misfit(h, w, set(conj), set(flip), np.radians(az))[0]) for v, h, w, m in pairs]
    print(f"best: conjugated {conj}, reversed {flip}, azimuth {az} deg, mean {mean:.1f} deg, largest {max(e for *_, e in each):.1f} deg ({len(pairs)} modes)")
    print("\n".join(f"  {o[0]:5.1f} deg at {o[1]} deg: conjugated {o[2]}, reversed {o[3]}" for o in others))
    assert (conj, flip) == (["fw"], ["edge"]) and abs(az - 270) <= 6, found[:3]
    assert mean <= 8.0 and all(o[0] >= 2 * mean for o in others if o[2] != conj), found[:3]
    assert max(e for *_, e in each) <= 30.0, sorted(each, key=lambda x: -x[2])[:3]


def test_tip_flap_of_the_whirling_edge_modes_as_hawcstab2s(hawcstab2_configuration_points):
    """The tip's axes (``ModeRecord.tip``: the blade's pitching frame, the undeformed axes turned with
    the pitch, as HAWCStab2's amplitudes and the steady state's tip deflection): the flap over edge
    tip amplitude of the whirling 1st edge modes (BW flap over BW edge in the BW mode, FW over FW in
    the FW mode) within 25 % + 0.02 of HAWCStab2's at 5-25 m/s.  The 0.02 (a 1.1 deg turn of the
    tip's edgewise motion) because near rated both codes' flap content passes a minimum (HAWCStab2
    0.055 / 0.050 at 10 m/s against 0.08-0.54 elsewhere), where a small difference of either part of
    it moves it much.  Measured (3 Dec 2026): BW 0.095 / 0.077 / 0.168 / 0.315 / 0.427 against
    0.080 / 0.055 / 0.174 / 0.315 / 0.420, FW 0.191 / 0.039 / 0.247 / 0.385 / 0.486 against
    0.194 / 0.050 / 0.280 / 0.429 / 0.539 at 5 / 10 / 15 / 20 / 25 m/s.  In the deflected tip
    section's axes (the former reading; 5.2 deg of elastic tip twist at 10 m/s) the 10 m/s pair is
    0.121 and 0.098 and fails."""
    from hawcstab2_reference import hawcstab2_1st_edge_whirl

    for v, modes in hawcstab2_configuration_points.items():
        for m in modes:
            if m.identity_name not in ("1st edge BW", "1st edge FW"):
                continue
            w = m.whirl.lower()
            ours = m.multiblade_amplitudes()
            ref = hawcstab2_1st_edge_whirl(v, m.whirl)
            h, o = float(ref[f"{w}_flap"]) / float(ref[f"{w}_edge"]), ours[f"{w}_flap"] / ours[f"{w}_edge"]
            assert abs(o - h) <= 0.25 * h + 0.02, (v, m.name, h, o)
