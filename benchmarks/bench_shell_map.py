"""The NREL 5 MW shell stability map, one or two wind speeds: the onsets' root search, Brent vs smooth.

Issue 33 item 2: the shell map (``windflutter run nrel5mw --model shell``, 11 wind speeds) in 3 minutes
on 2 cores.  Every trial of a root search is a full operating point (steady state, deflected shell
blade, blade basis, MBC, eigen-solve: 2.5-4 s).  Baseline in the same run: Brent's method on the
bracket (``OperationalStability.root_search = "brent"``, the search before this round); new:
:func:`windflutter.overspeed.smooth_root` (the default).  Each case runs in its own process (one BLAS
thread) on the same wind speeds with the default mesh; printed per wind speed: CPU time of the
process, full operating points evaluated (sweep points, ambiguous middles, root-search trials), the
onsets and their differences (RPM; they must agree within the search's tolerance, 0.01 RPM).

    python benchmarks/bench_shell_map.py [--wind 10 22] [--beam]
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import header, isolated, map_arguments, map_rows, table  # noqa: E402

TOL = 0.01  # RPM, SearchSettings.tolerance_rpm


def run(model: str, search: str, winds: list[float]) -> list[dict]:
    import windflutter
    from windflutter import methods

    t = windflutter.load_turbine("nrel5mw")
    cfg = windflutter.analysis_config(model=model)
    aero = cfg.aero[0] if isinstance(cfg.aero, (list, tuple)) else cfg.aero
    solver = methods.stability_analysis(t, cfg, aero, "p")
    solver.root_search = search
    return map_rows(solver, winds, search=search)


def _diff(a, b):
    return None if a is None or b is None else abs(a - b)


def main(argv=None) -> int:
    model, winds = map_arguments(argv, __doc__, [10.0, 22.0])
    header(f"bench_shell_map: NREL 5 MW {model}, method p, root searches", wind=winds)
    res = {s: isolated(run, model, s, winds)[0] for s in ("brent", "smooth")}
    rows, ok = [], True
    for old, new in zip(res["brent"], res["smooth"]):
        new["d_flutter"], new["d_divergence"] = _diff(new["flutter"], old["flutter"]), _diff(new["divergence"],
                                                                                            old["divergence"])
        same = ((old["flutter"] is None) == (new["flutter"] is None) and old["mode"] == new["mode"]
                and (old["divergence"] is None) == (new["divergence"] is None))
        ok &= same and (new["d_flutter"] or 0) <= TOL and (new["d_divergence"] or 0) <= TOL
        rows += [old, new]
    exact = ("flutter", "d_flutter", "divergence", "d_divergence", "freq")
    table([{k: (f"{v:.6f}" if k in exact and v is not None else v) for k, v in r.items()} for r in rows],
          ["search", "wind", "cpu", "wall", "evaluations", "flutter", "d_flutter", "divergence", "d_divergence",
           "mode", "freq"])
    for s in ("brent", "smooth"):
        print(f"{s}: CPU {sum(r['cpu'] for r in res[s]):.1f} s, {sum(r['evaluations'] for r in res[s])} operating points")
    print("times in s (this process's CPU, one BLAS thread; wall depends on the machine's load); onsets in RPM;"
          f" same onsets within {TOL} RPM and the same modes: {ok}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
