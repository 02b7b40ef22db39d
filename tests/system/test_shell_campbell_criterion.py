"""Issue 33's criterion on the IEA 22 MW shell Campbell, 3-25 m/s at the defaults (slow; about 3 minutes on
2 cores): no mode below 5 Hz negatively damped (rigid-body modes left out), and at least 90 % of the
first-family pairs (1st and 2nd flap and edge, 1st torsion; BW, FW, collective: 345) within 5 % of the
beam's frequency and within 1 point or 35 % of its damping -- against the beam of the same blade, its 6x6
extracted from the shell itself (40 stations, mesh/shell_beam.py), so that the comparison is of the
solvers and not of the file's section data (docs/notes/shell_same_blade.md).  The pairing is the
criterion script's (docs/scripts/shell_campbell_criteria.py).  Measured: 323 of 345 (93.6 %), no
negative damping (14th session; 309 before the exchange rule of the names, 305 with the one-point shear)."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "scripts"))
from shell_campbell_criteria import negative, pairs  # noqa: E402


@pytest.mark.slow
def test_iea22mw_shell_campbell_against_the_beam_of_the_same_blade():
    import windflutter.api as api
    from windflutter.mesh.shell_beam import with_shell_blade_properties
    from windflutter.model import load_turbine

    t = load_turbine("iea22mw")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        shell = api.campbell(t, model="shell", workers=2).as_dict()
        beam = api.campbell(with_shell_blade_properties(t, 40), model="beam").as_dict()
    assert not negative(shell)
    ok, total, misses = pairs(beam, shell)
    assert total == 23 * 15
    assert ok >= 0.9 * total, f"{ok} of {total}:\n" + "\n".join(map(str, misses))
