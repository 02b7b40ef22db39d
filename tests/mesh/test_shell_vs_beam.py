"""Shell model against the thin-walled beam of the same layup (seed 5 MW, UpWind layup).

The two share the layup, the airfoils and the material data and nothing else: the shell is
pyfe3d Quad4 laminates on a lofted skin with webs; the beam's 6x6 come from classical
thin-walled theory (model/section.py).  The full study is docs/scripts/shell_vs_beam_torsion.py
and docs/verification.md ("Shell vs beam of the same layup").  Measured (study, Nov 2026):

=========================  =====  =====  ======  =====
model (seed 5 MW blade)    flap1  edge1  flap2   tors1
=========================  =====  =====  ======  =====
shell 40x30 (default)      0.754  1.018  2.113   6.266
shell 40x60                0.739  1.008  2.083   5.913
shell 40x120               0.729  1.002  2.066   5.773
shell 40x180               0.725  0.999  2.060   5.726
shell, Richardson along    -      -      -       5.68
shell midsurface 40x120    0.682  0.993  1.933   5.518
beam (default, converged)  0.737  1.052  2.032   5.651
beam, midline on the OML   0.789  1.059  2.161   5.959
=========================  =====  =====  ======  =====

The default shell's +11 % in torsion is a mesh effect: its skin quads are 2.05 m along the span
and 0.2 m around (median aspect ratio 10), and the torsion frequency converges at observed order
1.3 in the spanwise element length (bending converges more slowly still, order ~0.6,
so only the torsion limit is extrapolated).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from windflutter.mesh.analysis import turbine_modes
from windflutter.mesh.settings import MeshSettings


@functools.lru_cache(maxsize=None)
def _seed():
    from windflutter.model.windio import load_turbine

    return load_turbine("seed5mw")


def _torsion(settings, turbine=None, reference_surface="outer"):
    import windflutter.mesh.parts as parts
    from windflutter.mesh.blade_shell import blade_shell_mesh

    tb = turbine or _seed()
    original = parts.blade_shell_mesh
    parts.blade_shell_mesh = functools.partial(blade_shell_mesh, reference_surface=reference_surface)
    try:
        r = turbine_modes(tb, settings, n_modes=8)
    finally:
        parts.blade_shell_mesh = original
    return float(r.frequencies_hz[r.labels.index("1st torsion")])


def _beam_torsion(offset=True, monkeypatch=None):
    from windflutter.mesh.section_props import thin_walled_properties

    tb = _seed()
    if not offset:  # the wall midline left on the outer mould line (study of the reference surface)
        import windflutter.model.section as section

        monkeypatch.setattr(section, "_offset_inwards", lambda yz, *a, **k: yz)
    bp = thin_walled_properties(tb)
    tb = dataclasses.replace(tb, blade=dataclasses.replace(tb.blade, beam=bp))
    return _torsion(MeshSettings(model="beam", part="blade"), tb)


def test_seed5mw_shell_torsion_converges_to_the_beam_along_the_span():
    """Reduced version of the study: the default shell's 6.27 vs 5.65 Hz is the spanwise mesh.
    24 x 30 quads (aspect ratio ~10): +11.6 %; 24 x 90: +3.7 % (measured 6.306 / 5.863 vs beam
    5.651 Hz).  Asserted: refining along the span lowers the shell torsion by more than 5 %, and
    the 24 x 90 shell is within 5 % of the beam (the issue's target; the converged shell is
    within 1 %, see the slow test)."""
    fb = _beam_torsion()
    f30 = _torsion(MeshSettings(model="shell", part="blade", n_chord=24, n_span=30))
    f90 = _torsion(MeshSettings(model="shell", part="blade", n_chord=24, n_span=90))
    print("beam", fb, "shell 24x30", f30, "24x90", f90)
    assert f90 < 0.95 * f30
    assert f90 == pytest.approx(fb, rel=0.05)


@pytest.mark.slow
def test_seed5mw_shell_vs_beam_torsion_convergence_and_reference_surface(monkeypatch):
    """Full study (~1 min).  (1) The shell sequence 40 x 30 / 60 / 120 converges monotonically
    (observed order 1-2) to a Richardson limit within 2 % of the converged beam (measured 5.68 vs
    5.65 Hz).  (2) Moving the shell skin to the laminate midsurface lowers the torsion by the
    same factor as moving the beam's wall midline from the outer mould line to the midline
    (measured 0.956 shell at 40 x 120 vs 0.948 beam): within 2 points, so the reference surface
    acts alike in both models.  (3) What remains, shell of a given surface ~4-5 % softer than the
    thin-walled beam of the same surface (midsurface 5.52 at 40 x 120 vs 5.65), is the section
    theory: rigid contour (no in-plane section deformation), no transverse shear of the sandwich
    panels.  Asserted band for it: 0-8 % (a shell can only be softer than a rigid-contour beam
    of the same walls, up to discretisation)."""
    fb = _beam_torsion()
    f = {ns: _torsion(MeshSettings(model="shell", part="blade", n_chord=40, n_span=ns)) for ns in (30, 60, 120)}
    r = (f[30] - f[60]) / (f[60] - f[120])
    order = np.log(r) / np.log(2.0)
    limit = f[120] - (f[60] - f[120]) / (r - 1.0)
    mid = _torsion(MeshSettings(model="shell", part="blade", n_chord=40, n_span=120), reference_surface="midsurface")
    fb_oml = _beam_torsion(offset=False, monkeypatch=monkeypatch)
    print("beam", fb, "beam OML", fb_oml, "shell", f, "order", order, "limit", limit, "mid 40x120", mid)
    assert f[30] > f[60] > f[120] and 1.0 < order < 2.2
    assert limit == pytest.approx(fb, rel=0.02)
    assert mid / f[120] == pytest.approx(fb / fb_oml, abs=0.02)
    assert 0.0 < 1.0 - mid / fb < 0.08


def _onset(model, capsys):
    import json

    from windflutter.cli import main

    # options pinned (p-k, potential flow): the defaults of `stability` changed on main (fa95a52);
    # the measured numbers are without induction and mean loads (both on by default since):
    # beam 20.5435 / 26.0094 RPM reproduced with these flags on 2 Dec 2026
    assert main(["stability", "seed5mw", "--model", model, "--part", "rotor", "--aero", "potential",
                 "--method", "pk", "--no-induction", "--no-mean-loads", "--json"]) == 0
    return json.loads(capsys.readouterr().out)["points"][0]


@pytest.mark.slow
def test_seed5mw_rotor_onsets_shell_vs_beam(capsys):
    """Overspeed onsets at 10 m/s, rotor (hub clamped), p-k, potential flow, 30 strips (~3 min),
    with the default rigid-section rotating-frame terms (solver.rigid_sections), the shell tips
    closed by a rib (model.tip_closure: rib) and the beam sections' shear and torsion stiffness at
    their shear centre (model/section.py), all defaults.

    Measured (2 Dec 2026): beam flutter 20.43 RPM at 3.93 Hz, divergence 25.63 RPM (20.40 / 25.60
    with 90 elements); shell 40x30 flutter 23.22 RPM at 4.49 Hz, divergence 27.98 RPM (+13.7 % /
    +9.2 %).  The convergence study (docs/verification.md section 11, item 4; docs/scripts/
    shell_vs_beam_onsets.py) traces the gap: along the span 40x60 21.88 / 27.12, 40x90 21.59 / 26.84,
    40x120 21.65 / 26.91 RPM; with the skin on the laminate midsurface (the beam's wall midline)
    40x90 gives 20.25 / 25.11, within 2 % of the beam.  Two former causes were fixed: the open tip
    section (tip_closure: open gave the shell 16.99 / 25.90 at 40x30, its local buckling driving the
    onsets) and the beam sections' shear centre on the reference axis (the beam then gave 20.57 /
    23.97).  The default shell mesh is now the converged one (issue 33: the blade length / 100 along
    the span, 40 around, the skin on the laminate midsurface; docs/mesh.md): measured 4 Dec 2026
    shell flutter 20.30 RPM at 3.94 Hz, divergence 25.21 RPM (-0.6 % / -1.6 % of the beam), the same
    flap-torsion flutter.  Required: both onsets and the flutter frequency within 3 % of the beam's
    (issue 33's band for a converged default; the seed's 40x30 outer-surface mesh gave +14 % / +9 %)."""
    beam, shell = _onset("beam", capsys), _onset("shell", capsys)
    print("beam", beam, "shell", shell)
    assert abs(shell["divergence_rpm"] / beam["divergence_rpm"] - 1) < 0.03
    assert abs(shell["flutter_rpm"] / beam["flutter_rpm"] - 1) < 0.03
    # the same flap-torsion flutter
    assert "torsion" in shell["flutter_mode"] and "3rd flap" in shell["flutter_mode"]
    assert abs(shell["flutter_frequency_hz"] / beam["flutter_frequency_hz"] - 1) < 0.03
