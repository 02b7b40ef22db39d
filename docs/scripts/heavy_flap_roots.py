"""Issue 33: the IEA 22 MW shell's heavily damped 1st flap roots against the beam of the same blade
(docs/notes/shell_same_blade.md section 4, "The heavily damped flap roots one by one").

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/heavy_flap_roots.py shell|beam [V ...]
(default 10 13 15 m/s; the shell about 40 s to build and 5 s a wind speed single thread, the beam
a few seconds).

The whole turbine at the operating point (the Campbell's defaults, method p), the shell model or
the beam on the shell's extracted properties (40 stations).  Printed per wind speed: every named
mode with a flap name, ``lambda / 2 pi`` (Hz), ``|lambda| / 2 pi`` (the Campbell's frequency) and
its damping ratio; and for each whirl the invariants of the pair of heavily damped flap roots
("1st flap W" and "2nd flap W + 1st flap W"): their sum and the square root of their product's
modulus, which do not depend on how the two roots share frequency and damping.  With ``--parts``
(one wind speed) also the deflected and undeformed structure with the deflected strips and the
undeformed one (``solver.structure: undeformed``).
"""

from __future__ import annotations

import dataclasses
import sys
import warnings

import numpy as np

import windflutter
from windflutter.mesh.shell_beam import with_shell_blade_properties
from windflutter.methods import operational_options
from windflutter.model import load_turbine
from windflutter.system.modes import point_modes
from windflutter.system.operational import OperationalModel


def model(which: str, **change) -> OperationalModel:
    t = load_turbine("iea22mw")
    if which == "beam":
        t = with_shell_blade_properties(t, 40)
    o = operational_options(windflutter.analysis_config(model=which), "viscous")
    return OperationalModel(t, dataclasses.replace(o, **change))


def flap_roots(ps) -> dict:
    return {m.name: m for m in point_modes(ps, max_hz=2.5) if "flap" in m.name and "edge" not in m.name}


def show(which: str, label: str, roots: dict) -> None:
    for name, m in sorted(roots.items(), key=lambda x: x[1].frequency_hz):
        lam = m.eigenvalue / (2 * np.pi)
        print(f"{which} {label} {name:36s} {lam.real:+.4f}{lam.imag:+.4f}i Hz  |f| {m.frequency_hz:.4f}"
              f"  zeta {m.damping_ratio:.3f}")
    for w in ("BW", "FW", "collective"):
        a, b = roots.get(f"1st flap {w}"), roots.get(f"2nd flap {w} + 1st flap {w}")
        if a is not None and b is not None:
            s, p = (a.eigenvalue + b.eigenvalue) / (2 * np.pi), a.eigenvalue * b.eigenvalue / (2 * np.pi) ** 2
            print(f"{which} {label} pair {w}: sum {s.real:+.4f}{s.imag:+.4f}i Hz, sqrt|product| {np.sqrt(abs(p)):.4f} Hz")


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    which, parts = argv[0], "--parts" in argv
    winds = [float(v) for v in argv[1:] if v != "--parts"] or [10.0, 13.0, 15.0]
    om = model(which)
    for V in winds:
        show(which, f"V={V:g}", flap_roots(om.at(V)))
    if parts:
        V = winds[0]
        und = model(which, structure="undeformed")
        show(which, f"V={V:g} undeformed", flap_roots(und.at(V)))
        und._linearized_strips = lambda rb, st: st.sections  # the deflected strips on the undeformed structure
        show(which, f"V={V:g} undeformed structure, deflected strips", flap_roots(und.at(V)))


if __name__ == "__main__":
    main(sys.argv[1:])
