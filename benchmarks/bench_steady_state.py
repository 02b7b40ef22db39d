"""Benchmark of the deflected steady state (windflutter.steady) on the IEA 22 MW blade.

One beam blade (root clamped, global geometry), HAWC2 operating points at 9 m/s (largest
deflection) and 18 m/s (pitch 14.4 deg), 15 / 30 / 60 beam elements; the time of one
``steady_state`` call (model building and assembly excluded, printed separately), its iterations
and where the time goes (BEM share), for the co-rotational steady state (the default) and, as the
baseline of the same run, the linear structure (``corotational=False``).  Target (issue 14, H4
brief): a beam IEA 22 MW point in well under a second.

Run: ``.venv/bin/python benchmarks/bench_steady_state.py`` (``--quick``: 30 elements only).
"""

from __future__ import annotations

import dataclasses
import math
import time

from _benchutil import QUICK, header, table

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry
from windflutter.model.windio import load_turbine
from windflutter.steady import SteadyOptions, steady_state
from windflutter.structure.assembly import assemble

POINTS = ((9.0, 5.5399, -1.3268), (18.0, 7.0611, 14.4215))  # wind (m/s), rpm, pitch (deg): HAWC2


def main() -> None:
    header("deflected steady state, IEA 22 MW beam blade")
    t = load_turbine("iea22mw", validate=False)
    g = rotor_geometry(t)
    g = dataclasses.replace(g, wind_direction=g.shaft_axis)
    import windflutter.steady.state as state

    orig = state.sections_induction
    bem_time = [0.0]

    def timed_bem(*a, **k):  # the BEM share of the time: wrap the name the iteration calls
        t1 = time.perf_counter()
        try:
            return orig(*a, **k)
        finally:
            bem_time[0] += time.perf_counter() - t1

    rows = []
    state.sections_induction = timed_bem
    try:
        for n_span in ((30,) if QUICK else (15, 30, 60)):
            for V, rpm, pitch in POINTS:
                t0 = time.perf_counter()
                fe, sec = build_model(t, MeshSettings(model="beam", part="blade", n_span=n_span,
                                                      pitch=math.radians(pitch)))
                st = assemble(fe)
                t_build = time.perf_counter() - t0
                for corot in (False, True):
                    bem_time[0] = 0.0
                    t0 = time.perf_counter()
                    s = steady_state(fe, st, sec, g, V, rpm * math.pi / 30, n_blades=3,
                                     options=SteadyOptions(corotational=corot))
                    t_ss = time.perf_counter() - t0
                    rows.append(dict(n_span=n_span, V=V, structure="co-rotational" if corot else "linear",
                                     build_s=t_build, steady_s=t_ss, iterations=s.iterations,
                                     bem_share=bem_time[0] / t_ss, power_MW=s.power / 1e6, flap_m=s.tip_flap,
                                     twist_deg=math.degrees(s.tip_twist)))
    finally:
        state.sections_induction = orig
    table(rows, ["n_span", "V", "structure", "build_s", "steady_s", "iterations", "bem_share", "power_MW", "flap_m", "twist_deg"])


if __name__ == "__main__":
    main()
