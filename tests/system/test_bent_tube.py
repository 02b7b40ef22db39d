"""Issue 33: lateral-torsional buckling of a cantilever elliptical tube under a tip load in its stiff
direction -- the beam's linearizations against closed forms (docs/scripts/bent_tube_torsion.py,
docs/notes/shell_same_blade.md section 3 "The bent tube").

References (independent, classical): ``P_cr = 4.013 sqrt(EI_minor GJ) / L^2`` (Timoshenko & Gere,
Theory of Elastic Stability, 1961, sec. 6.3; load at the centroid of the end section, prebuckling
deflections neglected); with the prebuckling deflections the load rises by about
``1/sqrt((1 - EI_minor/EI_major)(1 - GJ/EI_major))`` (Pettersson 1952; Trahair 1993; Kirby &
Nethercot 1979), a small-deflection estimate (1.141 here).

The shell: without ribs its classical load is 0.35 x the closed form (the flat section distorts);
with a rib at every ring of nodes (the rigid section of beam theory) its classical load is the
closed form (tested below); about the bent state its route (the carried stress brought into
equilibrium with the loads on the bent geometry, system/deflected_shell.py ``balanced_stress``) gives
the rise of the beam's exact Hessian (tested below; the carried linear stress alone gave 1.03 x).
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "scripts"))
from bent_tube_torsion import buckling_load, closed_forms, lever_arm, tube  # noqa: E402


def test_ribbed_shell_classical_buckling_is_timoshenko(ribbed_shell):
    """The shell tube (20 x 24 elements) with a rib at every interior ring, undeformed with its
    complete linear initial stress: the classical load within 3 % (measured -1.4 %; the thin-walled
    section constants against the shell's wall, the discretization).  Without the ribs 0.35 x:
    the test would fail."""
    rb, (Pc, _) = ribbed_shell
    assert buckling_load(rb, "shell", "classical", Pc, rel=3e-3) == pytest.approx(Pc, rel=0.03)


def test_ribbed_shell_deflected_buckling_rises_as_the_beams(ribbed_shell, beam):
    """The ribbed shell about its bent state (the deflected route, its stress balanced on the bent
    geometry): its buckling load over its own classical one against the co-rotational beam's exact
    Hessian (a second implementation sharing no element, stress or geometry code with it: 1.209 x)
    within 3 % (measured 1.220 x, +0.9 %; the shell's bent state is its linear displacement carried
    with moderate rotations, the beam's the exact equilibrium).  The carried linear stress alone
    (the route before: 1.028 x) fails it."""
    rb, (Pc, _) = ribbed_shell
    ratio = buckling_load(rb, "shell", "deflected", Pc, rel=3e-3) / buckling_load(rb, "shell", "classical", Pc, rel=3e-3)
    brb, (bPc, _) = beam
    beam_ratio = buckling_load(brb, "beam", "deflected", bPc) / buckling_load(brb, "beam", "classical", bPc)
    print(ratio, beam_ratio)
    assert ratio == pytest.approx(beam_ratio, rel=0.03)


@pytest.fixture(scope="module")
def ribbed_shell():
    rb, consts = tube("shell", 0.01, ribs=True)
    return rb, closed_forms(*consts, lever_arm(rb))


@pytest.fixture(scope="module")
def beam():
    rb, consts = tube("beam", 0.01)
    return rb, closed_forms(*consts, lever_arm(rb))


def test_beam_classical_buckling_is_timoshenko(beam):
    """Undeformed beam with its linear initial stress: the classical load within 1.5 % (the beam's
    shear flexibility and the discretization; measured -0.1 %)."""
    rb, (Pc, _) = beam
    assert buckling_load(rb, "beam", "classical", Pc) == pytest.approx(Pc, rel=0.015)


def test_beam_deflected_buckling_has_the_prebuckling_rise(beam):
    """The co-rotational beam's exact Hessian about the bent state: the buckling load rises by the
    prebuckling-deflection effect -- within 8 % of the Pettersson estimate (an estimate derived for
    small deflections: the tube's tip moves about 0.2 L at buckling; measured +5.9 %, 1.209 x the
    classical load against 1.141 x).  A linearization without the effect gives 1.0 x (-12 %) and
    fails."""
    rb, (Pc, Pp) = beam
    got = buckling_load(rb, "beam", "deflected", Pc)
    print(got / Pc, Pp / Pc)
    assert got == pytest.approx(Pp, rel=0.08)
    assert got > 1.1 * Pc
