"""The shell blade's section read on a periodic prism of its station (mesh/shell_section.py, issue 33
item 3): against thin-walled closed forms on a blade with a known answer."""

from __future__ import annotations

import numpy as np
import pytest

from synthetic import synthetic_turbine, tube_beam_props, tube_blade
from windflutter.errors import InputError
from windflutter.mesh.settings import MeshSettings


def _table(extraction: str, n_chord: int = 48):
    from windflutter.mesh.shell_beam import shell_beam_table

    L, c, th, t = 40.0, 2.0, 0.4, 0.01
    tb = synthetic_turbine(tube_blade(L, c, th, t))
    settings = MeshSettings(model="shell", part="blade", n_chord=n_chord, n_span=20, reference_surface="outer")
    return shell_beam_table(tb, 5, settings, extraction=extraction), tube_beam_props(L, c, th, t)


def test_elliptic_tube_sections_are_the_thin_walled_closed_forms():
    """A straight elliptical aluminium tube blade (chord 2 m, t/c 0.4, wall 10 mm; its skin on the
    ellipse), five stations read on periodic prisms, against thin-walled theory of the same ellipse
    (``tube_beam_props``: contour integrals, Bredt-Batho torsion): EA, both bending stiffnesses, GJ
    and the mass per length within 2 % (the issue's; the 48-sided polygon alone is ~0.3 % low), the
    tension, shear and mass centres at the ellipse's centre (the reference axis) within 1 % of the
    chord, at every station -- the ends, where a segment is cut off by the blade's root or tip,
    included.  Measured: EA -0.17 %, flap EI -0.67 %, edge EI -0.35 %, GJ -0.62 %, mass -0.17 %, the
    centres within 2e-5 m.  An ellipse warps in torsion: the blade segments loaded through rigid
    end rings (``extraction="segment"``, the default until now) give GJ -13 ... -14 % on this blade."""
    tab, ref = _table("section")
    K0, M0 = ref.stiffness[0], ref.mass[0]
    for i in range(len(tab.s)):
        K, S = tab.beam.stiffness[i], np.linalg.inv(tab.beam.stiffness[i])
        Kb = np.linalg.inv(S[4:, 4:])  # bending about the tension centre
        got = np.array([K[0, 0], Kb[0, 0], Kb[1, 1], 1 / S[3, 3], tab.beam.mass[i][0, 0]])
        want = np.array([K0[0, 0], K0[4, 4], K0[5, 5], K0[3, 3], M0[0, 0]])
        print(tab.s[i], got / want - 1, tab.tension_centre[i], tab.shear_centre[i], tab.mass_centre[i])
        np.testing.assert_allclose(got, want, rtol=0.02)
        for centre in (tab.tension_centre[i], tab.shear_centre[i], tab.mass_centre[i]):
            np.testing.assert_allclose(centre, 0.0, atol=0.01 * 2.0)


def test_unknown_extraction_is_refused():
    """An unknown extraction names the argument and the choices."""
    from windflutter.mesh.shell_beam import shell_beam_table

    with pytest.raises(InputError, match="extraction"):
        shell_beam_table(synthetic_turbine(tube_blade()), 5, extraction="strip")


@pytest.mark.slow
def test_iea22mw_sections_against_the_file_6x6():
    """The IEA 22 MW shell blade's sections (default mesh, 8 stations, ``extraction="section"``)
    against the windIO file's 6x6 -- PreComp-like sectional analysis of the same layup, so the
    like-for-like comparison -- over 15-92 % span, the root transition's far side included: mass 3 %,
    EA 6 %, GJ 10 %, flapwise EI 13 %, edgewise EI 8 % (measured 4 Dec 2026: mass -1 ... -3 %, EA -1
    ... -5 %, GJ -8 ... +3 %, flap EI -11 ... 0 %, edge EI -6 ... 0 %; the segment extraction there:
    GJ -9 ... +9 %, and at 10 % span flap EI -25 % against the section's -11 %).  Slow (6 s): a data
    comparison; the extraction's verification is the tube above."""
    import warnings

    from windflutter.mesh.shell_beam import shell_beam_table, table_rows
    from windflutter.model import load_turbine

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = load_turbine("iea22mw")
    rows = [r for r in table_rows(shell_beam_table(t, 8, extraction="section"), t.blade.beam) if 0.15 <= r["s"] <= 0.92]
    assert len(rows) >= 5
    for r in rows:
        got = [r[a] / r[b] - 1 for a, b in (("mass", "file_mass"), ("EA", "file_EA"), ("GJ", "file_GJ"),
                                            ("EI_flap", "file_EI_flap"), ("EI_edge", "file_EI_edge"))]
        print(round(r["s"], 3), np.round(got, 3))
        assert np.all(np.abs(got) <= [0.03, 0.06, 0.10, 0.13, 0.08])
