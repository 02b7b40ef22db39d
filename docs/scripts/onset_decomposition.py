"""The NREL 5 MW overspeed flutter onset at 10 m/s: the seed's model and defaults against the new ones,
one physical ingredient at a time (docs/stability.md, "From the seed's onset to the new defaults").

    python docs/scripts/onset_decomposition.py [--n-span 30] [--wind 10]

Prints one line per configuration: flutter RPM, frequency, mode, divergence RPM.
"""

from __future__ import annotations

import argparse
import time

from windflutter.config import config_from_dict
from windflutter.model import load_turbine
from windflutter.methods import stability_analysis

SEED = {"solver": {"induction": False, "mean_loads": False, "deflection": False}, "damping": {"model": "none"},
        "model": {"drivetrain": "locked"}}


def steps():
    """(label, config overrides, aero, method): from the seed's model to the new defaults."""
    p_seed = {**SEED, "solver": {**SEED["solver"], "circulation": "rfa", "n_lag": 4}}
    return [
        ("seed: p-k, frozen azimuth, potential", SEED, "potential", "pk"),
        ("seed: p-k, frozen azimuth, viscous", SEED, "viscous", "pk"),
        ("p: multi-blade, locked rotor, undeformed, viscous, Roger 4 poles", p_seed, "viscous", "p"),
        ("  + Jones' 2 poles (the default)", SEED, "viscous", "p"),
        ("  + flexible drivetrain", {**SEED, "model": {"drivetrain": "flexible"}}, "viscous", "p"),
        ("  + files' structural damping", {**SEED, "model": {"drivetrain": "flexible"}, "damping": {"model": "file"}},
         "viscous", "p"),
        ("  + BEM induction", {"solver": {"mean_loads": False, "deflection": False}}, "viscous", "p"),
        ("  + mean-load terms", {"solver": {"deflection": False}}, "viscous", "p"),
        ("  + deflected steady state (= the new defaults)", {}, "viscous", "p"),
        ("new defaults, p-k on the seed's frozen model", {}, "viscous", "pk"),
    ]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--n-span", type=int, default=30)
    ap.add_argument("--wind", type=float, default=10.0)
    args = ap.parse_args(argv)
    tb = load_turbine("nrel5mw")
    for label, over, aero, method in steps():
        cfg = config_from_dict({**over, "model": {**over.get("model", {}), "n_aero_sections": args.n_span},
                                "rotor_speed": {"tolerance_rpm": 0.01}})
        t = time.time()
        s = stability_analysis(tb, cfg, aero, method).analyse_operating_point(args.wind)
        fl = "-" if s.flutter_rpm is None else f"{s.flutter_rpm:7.2f}"
        fq = "-" if s.flutter_frequency_hz is None else f"{s.flutter_frequency_hz:5.2f}"
        dv = "-" if s.divergence_rpm is None else f"{s.divergence_rpm:7.2f}"
        print(f"{label:62s} flutter {fl} RPM {fq} Hz  divergence {dv} RPM  {s.flutter_mode or ''}  "
              f"({time.time() - t:.0f} s)", flush=True)


if __name__ == "__main__":
    main()
