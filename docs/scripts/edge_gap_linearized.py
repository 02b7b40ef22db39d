"""The 1st edge gap between the time domain and method p, without integrating (docs/notes/iea22mw_edge_gap.md).

For one blade on a rigid hub at an operating point: method p's rotating-frame eigenvalues (rotor on a
clamped hub, full order, no structural damping: the mean of each BW/FW pair) beside the simulation's
own equations linearized by central differences about its equilibrium
(:func:`windflutter.simulate.linearize.linearize_blade_in_wind`), with the strip loads moved to the
nodes through the current lever arms (the code) and through the steady configuration's (``--steady-arms``,
the former transfer).

Usage::

    python docs/scripts/edge_gap_linearized.py iea22mw 10 --n-span 10 20 30 [--steady-arms]

About 5-30 s per case on one core.
"""

from __future__ import annotations

import argparse
import warnings

import numpy as np

from windflutter import api
from windflutter.simulate.linearize import linearize_blade_in_wind
from windflutter.simulate.rotor_aero import BladeAero


def method_p(turbine, wind, n_span):
    """``({(family, order): rotating-frame eigenvalue}, rpm, pitch_deg)`` of method p at full order."""
    res = api.campbell(turbine, [wind], model={"part": "rotor", "n_aero_sections": n_span},
                       damping={"model": "none"}, solver={"reduction": "none"})
    p = res.points[0]
    pairs = {}
    for m in p.modes:
        if m.whirl in ("BW", "FW"):
            pairs.setdefault((m.family, m.order), {})[m.whirl] = complex(m.eigenvalue)
    return {k: 0.5 * (v["BW"] + v["FW"]) for k, v in pairs.items() if len(v) == 2}, p.rotor_speed_rpm, p.pitch_deg


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("turbine")
    ap.add_argument("wind", type=float)
    ap.add_argument("--n-span", type=int, nargs="+", default=[10])
    ap.add_argument("--steady-arms", action="store_true", help="the former load transfer (steady lever arms)")
    a = ap.parse_args()
    if a.steady_arms:
        BladeAero.nodal_loads = lambda self, config, loads: self.W.T @ loads.reshape(-1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        turbine = api.load_turbine(a.turbine)
        for n in a.n_span:
            ref, rpm, pitch = method_p(turbine, a.wind, n)
            lin = linearize_blade_in_wind(turbine, a.wind, rpm, pitch_deg=pitch, n_span=n)
            print(f"{a.turbine} {a.wind:g} m/s, {rpm:.3f} RPM, pitch {pitch:.2f} deg, {n} elements")
            for key, lam in sorted(ref.items(), key=lambda kv: kv[1].imag):
                if lam.imag / (2 * np.pi) > 4.0:
                    continue
                got = lin.nearest(lam)
                f_p, f_s = lam.imag / (2 * np.pi), got.imag / (2 * np.pi)
                print(f"  {key[0]:8s} {key[1]}  method p {f_p:.5f} Hz {-100 * lam.real / abs(lam):7.3f} %   "
                      f"simulation {f_s:.5f} Hz ({100 * (f_s / f_p - 1):+.3f} %) {-100 * got.real / abs(got):7.3f} %")


if __name__ == "__main__":
    main()
