"""Mesh dependence of a shell blade's static stability in operation (docs/verification.md, 14th session).

The blade alone (rotating-frame and steady-stress terms, hub clamped, no aerodynamic stiffness) at one
wind speed and a list of rotor speeds: the count of negative eigenvalues of its full-order stiffness
(``PointSystem.blade_negative``, the inertia of the factorization the blade basis makes anyway; 0: stable).

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/shell_stability_mesh.py TURBINE V N_CHORD N_SPAN RPM...
e.g.  ... iea22mw 10 40 100 7.5 8   (the default mesh: 40 around, 100 along the span; 5-90 s a point,
more for the finer meshes).
"""

from __future__ import annotations

import dataclasses
import sys
import time
import warnings

import windflutter
from windflutter.methods import operational_options
from windflutter.model import load_turbine
from windflutter.system.operational import OperationalModel


def main(name: str, wind: float, n_chord: int, n_span: int, rpms: list[float]) -> None:
    opts = operational_options(windflutter.analysis_config(model="shell"), "viscous")
    opts = dataclasses.replace(opts, mesh={**opts.mesh, "n_chord": n_chord, "n_span": n_span})
    model = OperationalModel(load_turbine(name), opts)
    for rpm in rpms:
        t0 = time.time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ps = model.at(wind, rpm=rpm)
        print(f"{name} V = {wind:g} m/s, {n_chord} around x {n_span} along the span, {rpm:g} RPM: "
              f"negative eigenvalues {ps.blade_negative} ({time.time() - t0:.0f} s)", flush=True)


if __name__ == "__main__":
    a = sys.argv[1:]
    main(a[0], float(a[1]), int(a[2]), int(a[3]), [float(x) for x in a[4:]])
