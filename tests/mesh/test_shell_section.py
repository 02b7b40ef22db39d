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
