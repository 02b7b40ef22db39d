"""A blade structure that loses static stability on its own is not reported as divergence.

Found on the NREL 5 MW shell blade at 8 m/s: its steady stress makes the FE structure statically
unstable at 22.0 RPM without any aerodynamics (a local mode of the tip's slender shell elements,
w^2 from +38 to -7800 1/s^2 between 22 and 23 RPM), and the static-margin search called that
"divergence".  Aeroelastic divergence is the aerodynamic stiffness overcoming a stable structure;
a structural instability of the FE model stops the sweep with a note instead.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import windflutter
import windflutter.overspeed as op
from windflutter.units import RPM


def test_a_structural_instability_stops_the_sweep_with_a_note(monkeypatch):
    """Control logic, on the beam model: the structure alone declared unstable from 14 RPM on (the
    real margin of a beam blade stays positive); the sweep stops between its grid points, the note
    says where (interpolated between them) and why, and no divergence or flutter is reported
    beyond it."""
    real = op.blade_structural_margin

    def fake(ps):
        w = real(ps)
        return w if ps.omega / RPM < 14.0 else -1.0

    monkeypatch.setattr(op, "blade_structural_margin", fake)
    (p,) = windflutter.stability("nrel5mw", [11.4], model={"part": "rotor"})
    note = p.as_dict()["note"]
    assert note and "loses static stability on its own at" in note and "not aeroelastic divergence" in note
    stop = float(re.search(r"at about ([0-9.]+) RPM", note).group(1))
    assert 12.1 < stop <= 14.0 + 0.02
    assert p.divergence_rpm is None and p.flutter_rpm is None
    assert np.max(p.sweep_rpm) < 14.0
    # the note says from which rotor speed it holds, so that the verdict does not put its caution
    # on onsets found below it (a note without one concerns the whole sweep)
    from windflutter.post.verdict import _note_from_rpm

    assert _note_from_rpm(note) == pytest.approx(stop, abs=0.006)


@pytest.mark.slow
def test_nrel5mw_shell_tip_instability_is_not_divergence():
    """The real case (36 s): the shell blade at 8 m/s with its tip section left open (the
    free skin edge, ``model.tip_closure: open``), on the seed's mesh (30 span elements, the skin on
    the outer mould line), where the open tip buckles first (on the converged default mesh the
    sweep reaches divergence at 26.2 RPM first).  Measured with the complete shell initial stress
    (issue 33): 20.07 RPM, the mode largest at r/R = 0.97 (the last span element); with the
    membrane-only one 21.5-22.5 RPM at r/R = 1.00."""
    (p,) = windflutter.stability("nrel5mw", [8.0], model={"type": "shell", "tip_closure": "open", "n_aero_sections": 30,
                                                         "reference_surface": "outer"})
    note = p.as_dict()["note"]
    assert p.divergence_rpm is None, p.as_dict()
    assert note and float(re.search(r"r/R = ([0-9.]+)", note).group(1)) >= 0.95  # the open tip's last elements
    stop = float(re.search(r"at about ([0-9.]+) RPM", note).group(1))
    assert 19.5 < stop < 20.7


@pytest.mark.slow
def test_nrel5mw_shell_with_the_tip_rib_stays_structurally_stable():
    """The default closure (a rib: the tip section keeps its shape in its plane) removes that local
    instability: the structure alone with its steady stress is stable at 26 RPM, where the open tip
    had failed, and the sweep runs on to the aeroelastic onsets (no note).  Measured 2 Dec 2026 with
    one stiffness-proportional damping on the shell: 4th flap BW flutter 29.02 RPM; since the shell's
    per-direction structural damping (issue 33, 4 Dec) the first onset is the 1st edge BW + 1st flap
    BW at 20.56 RPM (0.68 Hz), the beam of the same blade's 20.37 RPM
    (test_shell_same_blade.py's slow onset check), ~110 s."""
    (p,) = windflutter.stability("nrel5mw", [8.0], model="shell")
    d = p.as_dict()
    assert d["note"] is None, d  # no structural instability anywhere in the sweep (which runs past 26 RPM)
    assert p.flutter_rpm is not None and 1.5 * 12.1 < p.flutter_rpm < 26.0
    assert "edge" in p.flutter_mode
    assert p.divergence_rpm is None or p.divergence_rpm > 26.0
