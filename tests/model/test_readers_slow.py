"""Overspeed flutter onset of the NREL 5 MW read by each reader (``windflutter stability TURBINE
--wind-speeds 10``: beam model, potential aero, p-k, whole turbine).  Slow: four searches of
about 30 s each.

Measured (Dec 2026): windIO 21.99 RPM, OpenFAST deck 24.34 RPM (+10.7 %), HAWC2 model 19.13 RPM
(-13 %).  The structure of the windIO and OpenFAST models is the same (BeamDyn 6x6; frequencies
equal to 1e-4), so the OpenFAST difference is aerodynamic, and it is one input: WISDEM's windIO
file puts the reference axis at 0.40 chord (0.50 at the root) where Jonkman's ElastoDyn
PitchAxis (and AeroDyn's AC offsets) put it at 0.375 (0.25 at the root).  With the windIO pitch
axis the deck-built model flutters at 21.985 RPM (0.03 % from the windIO model).  The HAWC2 data
differ in more than one input (chordwise CG offsets up to 0.35 m aft of the elastic centre,
shear factors 0.5, a 0.96 m tip chord where AeroDyn has 1.42 m, their own polars); its onset is
not traced to 2 % (docs/verification.md).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from windflutter.stability.turbine import TurbineOptions, TurbineStability


def _onset(turbine):
    p = TurbineStability(turbine, TurbineOptions()).analyse_operating_point(10.0)
    return p.flutter_rpm


@pytest.mark.slow
def test_flutter_onset_by_reader(turbine):
    w = turbine("nrel5mw")
    deck = turbine("nrel5mw_openfast")
    f_w, f_deck = _onset(w), _onset(deck)
    assert f_w == pytest.approx(21.99, rel=0.01)
    assert 1.05 < f_deck / f_w < 1.15  # the pitch-axis difference of the two data sets (docstring)
    pa = np.interp(deck.blade.s, w.blade.s, w.blade.pitch_axis)
    same_axis = dataclasses.replace(deck, blade=dataclasses.replace(deck.blade, pitch_axis=pa,
                                                                      section_offset_y=pa * deck.blade.chord))
    assert _onset(same_axis) == pytest.approx(f_w, rel=0.02)  # the 2 %; measured 0.03 %
    f_h2 = _onset(turbine("nrel5mw_hawc2"))
    assert f_h2 is not None and 0.75 < f_h2 / f_w < 1.0  # CG aft of the elastic axis lowers it (docstring)
