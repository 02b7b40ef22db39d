"""Our mode names against HAWCStab2's own continuation of its modes (IEA 15 MW, tests/data/iea15mw_hawcstab2,
DLR-AE/CampbellViewer, Apache-2.0; issue 32).

HAWCStab2 does not name its modes.  What it gives is (1) its .amp file: each mode's tip amplitudes in
multi-blade components (what its users read to name a mode), and (2) its mode numbers, which follow its
modes along the wind speeds (its continuation).  Its tip labels alone cannot name every mode: a 1st
torsion mode moves the deflected tip more in flap (m) than it turns (rad), a 2nd or 3rd tower mode
whirls the blade tips (its .amp has no tower-top tilt), so "BW flap" covers the 1st, 2nd and 3rd flap
BW, the 1st torsion BW and the 3rd tower fore-aft alike.  The test therefore uses HAWCStab2's
continuation as the reference of identity: where one of its mode numbers keeps its label (the family
and whirl of its largest tip component) from one wind speed to the next, it is one mode there, and our
name of the mode paired with it by shape must be the same at both.  Where its label changes whirl or
family, its numbering has switched modes (its 3rd flap BW and collective, numbers 18 and 19, swap
between 5 and 10 m/s, as their labels show) or the mode is a tower mode whose tip whirl is not its own;
those steps say nothing and are left out.  Through a veering the two codes differ by design:
HAWCStab2's numbers follow the branch (continuity of the eigenvector), our names the participation
(issue 32: "crossings and veerings keep their names by participation, not by frequency order"); where
its continuation exchanges our names in a closed cycle (its 1st torsion FW and 3rd tower fore-aft at
12-13 m/s, where the two exchange character) the step is reported as a veering, not as a miss.

Pairing: HAWCStab2's modes at 0.3-4 Hz (damping below 99 %) one to one with ours by the cosine of
their vectors of magnitudes (tower top and blade tip, hawcstab2_reference.PHASE_COMPONENTS) at least
0.9, the natural frequency within 8 % (15 % above 30 % damping, where ours are 0-19 % lower with the
strip count: test_iea15mw_2nd_flap_as_hawcstab2_continues_it) and the damping ratio within 10 points
(a 60 % damped 2nd flap and a 5 % damped 1st torsion both move the tip mostly in flap).
"""

from __future__ import annotations

import numpy as np
import pytest

from hawcstab2_reference import WINDS, amplitude_rows, magnitude_pairs, operating_point

#: the 1st torsion and the 3rd tower fore-aft share 3.6-4.0 Hz at 20-25 m/s, where neither the
#: pairing by tip amplitudes nor HAWCStab2's labels tell them apart: the names are checked to 3.5 Hz there
LIMIT_HZ = {5.0: 4.0, 10.0: 4.0, 15.0: 4.0, 20.0: 3.5, 25.0: 3.5}


@pytest.fixture(scope="module")
def sweep():
    """Our named modes along HAWCStab2's operating curve, 3-25 m/s in 1 m/s steps, each point continuing
    the names of the previous one (as ``windflutter campbell`` does)."""
    from windflutter.model import load_turbine
    from windflutter.system.modes import point_modes
    from windflutter.system.operational import OperationalModel, OperationalOptions

    om = OperationalModel(load_turbine("iea15mw"), OperationalOptions(tower_damping=0.001, structure="deflected"))
    out, previous = {}, None
    for v in np.arange(3.0, 25.5, 1.0):
        rpm, pitch = operating_point(v)
        previous = [m for m in point_modes(om.at(v, rpm=rpm, pitch=np.radians(pitch)), max_hz=5.0, previous=previous)
                    if not m.rigid]
        out[float(v)] = previous
    return out


def _pairs(modes, wind):
    """(HAWCStab2 mode number, its label, natural frequency Hz, our mode or None) at ``wind``."""
    ref = [r for r in amplitude_rows(wind) if 0.3 < float(r["frequency_hz"]) < 4.0 and abs(float(r["damping_pct"])) < 99]
    ours = [m for m in modes if m.tip is not None and m.frequency_hz < 5.0]
    z = np.array([float(r["damping_pct"]) / 100 for r in ref])
    got, fn, _ = magnitude_pairs(ref, ours, np.where(z > 0.3, 0.15, 0.08), 0.9, max_dzeta=0.10)
    return [(int(r["mode"]), r["blade_label"], fn[i], got[i]) for i, r in enumerate(ref)]


def _identity(name: str) -> str:
    """The identity part of a name ("2nd edge BW + 2nd tower side-side" -> "2nd edge BW")."""
    return name.split(" + ")[0]


@pytest.mark.slow
def test_hawcstab2_modes_below_4_hz_keep_our_names_as_hawcstab2_continues_them(sweep):
    """Every HAWCStab2 mode below 4 Hz at 5, 10, 15, 20 and 25 m/s paired by shape (at least 95 % of
    them); along HAWCStab2's continuation, where its mode keeps its label from one of these wind speeds
    to the next, the mode paired with it carries our same name at both, or the names are exchanged
    in a closed cycle (a veering; all of them, below LIMIT_HZ).  Measured: 99 of 102 paired; 57
    continued steps, 56 with one name -- the 1st and 2nd edge, 1st, 2nd and 3rd flap (BW, FW,
    collective), 1st torsion, 2nd tower fore-aft and side-side and the tower torsion among them --
    and one veering (HAWCStab2's mode 26, 10 -> 15 m/s: our 1st torsion FW -> 3rd tower fore-aft)."""
    pairs = {v: _pairs(sweep[v], v) for v in WINDS}
    n = sum(len(p) for p in pairs.values())
    unpaired = [(v, k, label, round(f, 3)) for v, p in pairs.items() for k, label, f, m in p if m is None]
    assert len(unpaired) <= 0.05 * n, f"unpaired HAWCStab2 modes: {unpaired}"
    steps, wrong, veering = 0, [], []
    for a, b in zip(WINDS[:-1], WINDS[1:]):
        at_a = {k: (label, f, m) for k, label, f, m in pairs[a]}
        moved = {_identity(at_a[k][2].identity_name): _identity(m.identity_name) for k, label, f, m in pairs[b]
                 if k in at_a and m is not None and at_a[k][2] is not None}
        for k, label, f, m in pairs[b]:
            if k not in at_a or m is None or at_a[k][2] is None or at_a[k][0] != label:
                continue
            if max(f, at_a[k][1]) > min(LIMIT_HZ[a], LIMIT_HZ[b]):
                continue
            steps += 1
            before, after = _identity(at_a[k][2].identity_name), _identity(m.identity_name)
            if before == after:
                continue
            line = f"HAWCStab2 mode {k} ({label}) {a:.0f} -> {b:.0f} m/s: ours {before} -> {after}"
            (veering if _cycle(moved, before) else wrong).append(line)
    print(f"{n - len(unpaired)} of {n} paired, {steps} continued steps; veerings: {veering}")
    assert steps >= 30, steps  # the check is not empty
    assert not wrong, "\n".join(wrong)


def _cycle(moved: dict, name: str) -> bool:
    """Whether HAWCStab2's continuation permutes our names in a closed cycle through ``name``
    (``moved``: our name at the first wind speed -> at the next, along HAWCStab2's mode numbers): two or
    more of its modes exchange our names -- a veering, through which HAWCStab2's numbers follow the
    branch (continuity of the eigenvector) and our names the participation, as issue 32 asks."""
    seen, x = set(), moved.get(name)
    while x is not None and x not in seen:
        if x == name:
            return True
        seen.add(x)
        x = moved.get(x)
    return False
