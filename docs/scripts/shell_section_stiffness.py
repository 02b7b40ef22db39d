"""Section stiffness of a turbine's shell blade, extracted from the shell FE model, against the file's 6x6.

A segment of the shell blade (the elements between two stations) is cut out at 30, 50 and 70 % span;
:func:`windflutter.structure.equivalent_beam.segment_stiffness` clamps its root ring, loads its tip
ring and reads EA, GJ and the two bending stiffnesses between two interior rings (about the strips'
reference points, section axes: the span, the chord, their normal).  Printed beside the turbine
file's 6x6 at the same span.  docs/steady_state.md ("Shell blades") quotes it for the IEA 22 MW.

    python docs/scripts/shell_section_stiffness.py [--turbine iea22mw] [--n-span 30]
"""

from __future__ import annotations

import argparse
import warnings

import numpy as np

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.shell_beam import shell_segment as segment
from windflutter.mesh.shell_beam import station_planes as stations
from windflutter.mesh.turbine import build_model
from windflutter.model import load_turbine
from windflutter.structure.equivalent_beam import segment_stiffness


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--turbine", default="iea22mw")
    ap.add_argument("--n-span", type=int, default=30)
    args = ap.parse_args(argv)
    t = load_turbine(args.turbine)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fe, sec = build_model(t, MeshSettings(model="shell", part="blade", n_span=args.n_span))
    P0, st, on = stations(fe, sec)
    ns, bp = args.n_span, t.blade.beam
    half, gap = max(3, ns // 10), max(2, ns // 15)
    print(f"{args.turbine}, {ns} span elements: shell segment / file 6x6 - 1")
    print("   s      EA     GJ  EI flap  EI edge")
    for frac in (0.3, 0.5, 0.7):
        k0 = int(frac * ns) - half
        k1 = k0 + 2 * half
        seg, ring = segment(fe, st, on, k0, k1)
        ka, kb = k0 + gap, k1 - gap
        j = (ka + kb) // 2
        s = segment_stiffness(seg, ring(k0), ring(k1), (ring(ka), ring(kb)), (P0[ka], P0[kb]), axis=P0[kb] - P0[ka],
                              e2=np.asarray(sec.e_chord)[j])
        r = 0.5 * (ka + kb) / ns
        f = [np.interp(r, bp.s, bp.stiffness[:, i, i]) for i in (0, 3, 5, 4)]  # EA, GJ, flap (about z), edge
        ours = (s.EA, s.GJ, s.EI2, s.EI3)  # EI2: about the chord (flapwise bending), EI3: edgewise
        print(f"{r:5.2f} " + " ".join(f"{o / v - 1:+7.1%}" for o, v in zip(ours, f)))


if __name__ == "__main__":
    main()
