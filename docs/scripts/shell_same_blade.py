"""The shell against the beam of the same blade (issue 33): the numbers of docs/notes/shell_same_blade.md.

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/shell_same_blade.py [static] [onsets]
(static: the steady tip flap and twist at rated, IEA 22 MW and NREL 5 MW, about 2 minutes; onsets:
the NREL 5 MW overspeed onsets at 8 and 10 m/s of the shell and of four beams, about 15 minutes
single thread on an idle machine).

The beam "of the same blade" is the beam model on the shell's own section properties
(``windflutter.mesh.shell_beam.with_shell_blade_properties``, 40 stations of the default shell mesh).
"""

from __future__ import annotations

import dataclasses
import sys
import time
import warnings

import numpy as np

import windflutter.api as api
from windflutter.mesh.shell_beam import with_shell_blade_properties
from windflutter.model import load_turbine
from windflutter.system.operational import OperationalModel, OperationalOptions


def shell_damping(turbine):
    """``turbine`` whose beam blade gets the shell's earlier structural damping (until 4 Dec 2026:
    beta K, beta the larger bending coefficient, in every direction)."""
    d = turbine.blade.damping
    mu = np.full(6, float(max(d.mu[4], d.mu[5])))
    return dataclasses.replace(turbine, blade=dataclasses.replace(turbine.blade, damping=dataclasses.replace(d, mu=mu)))


def static():
    for name, V in (("iea22mw", 11.0), ("nrel5mw", 11.4)):
        t = load_turbine(name)
        ts = with_shell_blade_properties(t, 40)
        rows = (("shell", t, "shell"), ("beam, shell's properties", ts, "beam"), ("beam, file 6x6", t, "beam"))
        for label, tb, model in rows:
            om = OperationalModel(tb, OperationalOptions(model=model, part="rotor"))
            omega, pitch = om.operating_point(V)
            st = om.steady(om.blade(pitch), V, omega)
            print(f"{name} {V} m/s {label}: tip flap {st.tip_flap:.3f} m, tip twist {np.degrees(st.tip_twist):.3f} deg")


def onsets():
    t = load_turbine("nrel5mw")
    ts = with_shell_blade_properties(t, 40)
    rows = (("shell", t, "shell", {}), ("beam, shell's properties, shell's damping", shell_damping(ts), "beam", {}),
            ("beam, shell's properties, file damping", ts, "beam", {}),
            ("beam, shell's properties, no damping", ts, "beam", {"damping": {"model": "none"}}),
            ("beam, file 6x6", t, "beam", {}))
    for label, tb, model, kw in rows:
        for V in (8.0, 10.0):
            t0 = time.time()
            d = api.stability(tb, V, model=model, **kw)[0].as_dict()
            print(f"{label}, {V} m/s: first {d['first_instability']}; flutter {d['flutter_rpm']:.2f} RPM "
                  f"({d['flutter_frequency_hz']:.3f} Hz, {d['flutter_mode']}); divergence {d['divergence_rpm']:.2f} RPM"
                  f"  [{time.time() - t0:.0f} s]", flush=True)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the NREL 5 MW layup is not the tables' blade (known, warned)
        if not argv or "static" in argv:
            static()
        if not argv or "onsets" in argv:
            onsets()


if __name__ == "__main__":
    main()
