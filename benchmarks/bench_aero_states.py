"""Method p with each blade's aerodynamic lag states reduced by balanced truncation (NREL 5 MW).

Issue 33 item 2 (the shell map in 3 minutes): since 6 Dec 2026 (17th session) the lag states of each
blade -- two per strip, 200 on the 100-strip shell blade -- are reduced by balanced truncation
(``solver.aero_state_tol``, default 1e-7; docs/campbell.md sec. 1).  Baseline measured in the same run:
the same wind speeds with every state (``aero_state_tol: null``).  Each case runs in its own process
(one BLAS thread); printed per wind speed: CPU time, operating points evaluated, the onsets; and the
states of the whole-turbine system at the 10 m/s operating point.  Every onset of the baseline must be
the reduced model's (same mode, the rotor speed within ``TOL``: the search's tolerance).

    python benchmarks/bench_aero_states.py [--wind 10 22] [--beam]
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import header, isolated, map_arguments, map_rows, nrel5mw_solver, pair_table  # noqa: E402

TOL = 0.01  # RPM, SearchSettings.tolerance_rpm


def run(model: str, tol, winds: list[float]) -> list[dict]:
    import warnings

    solver = nrel5mw_solver(model, solver={"aero_state_tol": tol})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ps = solver.model.at(10.0)
    states = int(ps.mbc.A.shape[0] + 2 * ps.mbc.M.shape[0])
    case = "every state [baseline]" if tol is None else f"aero_state_tol {tol:g}"
    return [dict(r, states=states) for r in map_rows(solver, winds, case=case)]


def _same(a: dict, b: dict) -> bool:
    for k in ("flutter", "divergence"):
        if (a[k] is None) != (b[k] is None) or (a[k] is not None and abs(a[k] - b[k]) > TOL):
            return False
    return a["flutter"] is None or a["mode"] == b["mode"]


def main(argv=None) -> int:
    model, winds = map_arguments(argv, __doc__, [10.0, 22.0])
    header(f"bench_aero_states: NREL 5 MW {model}, method p, lag states reduced", wind=winds)
    base = isolated(run, model, None, winds)[0]
    new = isolated(run, model, 1e-7, winds)[0]
    ok = all(_same(a, b) for a, b in zip(base, new))
    cn, cb = pair_table(base, new, ["case", "wind", "states", "cpu", "evaluations", "flutter", "mode", "divergence"])
    print(f"CPU {cn:.1f} s against {cb:.1f} s ({cn / cb:.2f} x); states of the 10 m/s operating point "
          f"{new[0]['states']} against {base[0]['states']}")
    print(f"times in s (this process's CPU, one BLAS thread); rotor speeds in RPM; every onset the baseline's "
          f"(within {TOL} RPM, same mode): {ok}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
