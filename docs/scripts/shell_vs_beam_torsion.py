"""Shell vs thin-walled beam of the same layup (seed 5 MW, UpWind layup): where the torsion gap comes from.

Run:  OPENBLAS_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/shell_vs_beam_torsion.py [--quick]
(about 2 minutes on one core; --quick skips the finest meshes).  Results: docs/verification.md
("Shell vs beam of the same layup") and docs/mesh.md.

Three studies, each changing one thing:

1. Shell mesh convergence, along the span (n_span 15 ... 180 at n_chord 40) and around the
   section (n_chord 24 / 40 / 64 at n_span 120), with a Richardson extrapolation of the spanwise
   sequence 30 / 60 / 120 (observed order from the three).
2. Reference surface: the shell skin on the outer mould line (the default, the seed's choice)
   against the skin moved to the laminate midsurface (``blade_shell_mesh(...,
   reference_surface="midsurface")``); the beam's wall midline offset inwards by t/2 (default)
   against no offset (outer mould line), by replacing the offset function of the section
   calculator for that run only.
3. Beam convergence: beam elements, section stations and contour points.
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import time
import warnings

import numpy as np

import windflutter.mesh.parts as parts
import windflutter.model.section as section
from windflutter.mesh.analysis import turbine_modes
from windflutter.mesh.blade_shell import blade_shell_mesh
from windflutter.mesh.section_props import thin_walled_properties
from windflutter.mesh.settings import MeshSettings
from windflutter.model.windio import load_turbine

KEYS = ("1st flap", "1st edge", "2nd flap", "1st torsion")


def frequencies(turbine, settings, n_modes=10):
    """First flap, edge, second flap and first torsion frequencies (Hz) of the clamped blade."""
    r = turbine_modes(turbine, settings, n_modes=n_modes)
    return np.array([r.frequencies_hz[r.labels.index(k)] for k in KEYS])


def shell(turbine, nc, ns, surface="outer"):
    parts.blade_shell_mesh = functools.partial(blade_shell_mesh, reference_surface=surface)
    try:
        return frequencies(turbine, MeshSettings(model="shell", part="blade", n_chord=nc, n_span=ns))
    finally:
        parts.blade_shell_mesh = blade_shell_mesh


def beam(turbine, n_el=30, n_sec=40, n_contour=240, offset=True):
    original = section._offset_inwards
    if not offset:
        section._offset_inwards = lambda yz, *a, **k: yz
    try:
        bp = thin_walled_properties(turbine, n_span=n_sec, n_contour=n_contour)
    finally:
        section._offset_inwards = original
    tb = dataclasses.replace(turbine, blade=dataclasses.replace(turbine.blade, beam=bp))
    return frequencies(tb, MeshSettings(model="beam", part="blade", n_span=n_el))


def richardson(f1, f2, f3):
    """Limit and observed order of a sequence with the element length halved each time."""
    r = (f1 - f2) / (f2 - f3)
    p = np.log(r) / np.log(2.0)
    return f3 - (f2 - f3) / (r - 1.0), p


def row(tag, f, t0):
    print(f"{tag:42s} " + " ".join(f"{v:7.4f}" for v in f) + f"   ({time.time() - t0:4.1f} s)", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="skip the meshes finer than 40x120")
    quick = ap.parse_args().quick
    warnings.simplefilter("ignore")
    tb = load_turbine("seed5mw")
    print(f"{'model':42s} " + " ".join(f"{k[:7]:>7s}" for k in ("flap1", "edge1", "flap2", "tors1")))
    res = {}
    for surface in ("outer", "midsurface"):
        spans = (15, 30, 60, 120) + (() if quick else (180,))
        for ns in spans:
            t0 = time.time()
            res[surface, 40, ns] = shell(tb, 40, ns, surface)
            row(f"shell {surface} 40 x {ns}", res[surface, 40, ns], t0)
        for nc in (24, 64) if not quick or surface == "outer" else (24,):
            t0 = time.time()
            res[surface, nc, 120] = shell(tb, nc, 120, surface)
            row(f"shell {surface} {nc} x 120", res[surface, nc, 120], t0)
        lim, p = richardson(res[surface, 40, 30], res[surface, 40, 60], res[surface, 40, 120])
        print(f"{'  Richardson along (30/60/120), limit':42s} " + " ".join(f"{v:7.4f}" for v in lim))
        print(f"{'  observed order':42s} " + " ".join(f"{v:7.2f}" for v in p))
    for tag, kw in (("beam 30 el, 40 sections, 240 pts (default)", {}),
                    ("beam 60 el, 80 sections, 480 pts", dict(n_el=60, n_sec=80, n_contour=480)),
                    ("beam 120 el, 120 sections, 240 pts", dict(n_el=120, n_sec=120)),
                    ("beam, midline = outer mould line", dict(offset=False))):
        t0 = time.time()
        row(tag, beam(tb, **kw), t0)


if __name__ == "__main__":
    main()
