"""Method p's overspeed search bounded by the tips' Mach 0.5 against the search to 40 RPM (NREL 5 MW).

Issue 33 item 2 (the shell map in 3 minutes): since 6 Dec 2026 each wind speed's sweep ends where the
blade tip's speed relative to the wind reaches Mach 0.5 (``rotor_speed.max_tip_mach``, 25.5-25.8 RPM on
this rotor), where the incompressible strips end.  Baseline measured in the same run: the same wind
speeds searched to ``max_rpm`` 40 (``max_tip_mach: null``, the search before).  The grids differ
above the last common grid speed, so an onset there is bracketed differently and agrees to the
search's tolerance (0.01 RPM), not bit for bit.  Each case runs in its own
process (one BLAS thread); printed per wind speed: CPU time, operating points evaluated (sweep points,
refined steps' middles, root-search trials), where the sweep ended, the onsets.  Every onset of the
baseline below the bound must be the bounded search's (same mode, the rotor speed within ``TOL``).

    python benchmarks/bench_search_range.py [--wind 14 22] [--beam]
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import header, isolated, map_arguments, map_rows, nrel5mw_solver, pair_table  # noqa: E402

TOL = 0.01  # RPM, SearchSettings.tolerance_rpm


def run(model: str, tip_mach, winds: list[float]) -> list[dict]:
    solver = nrel5mw_solver(model, rotor_speed={"max_tip_mach": tip_mach})
    return map_rows(solver, winds, case="to 40 RPM [baseline]" if tip_mach is None else f"to tip Mach {tip_mach:g}")


def _kept(old: float | None, new: float | None, end: float) -> bool:
    """An onset of the baseline below the bounded search's end is the bounded search's; one above it
    is gone."""
    if old is None or old > end:
        return new is None
    return new is not None and abs(new - old) <= TOL


def main(argv=None) -> int:
    model, winds = map_arguments(argv, __doc__, [14.0, 22.0])
    header(f"bench_search_range: NREL 5 MW {model}, method p, the search's end", wind=winds)
    base = isolated(run, model, None, winds)[0]
    new = isolated(run, model, 0.5, winds)[0]
    ok = all(_kept(a["flutter"], b["flutter"], b["end"]) and _kept(a["divergence"], b["divergence"], b["end"])
             and (b["flutter"] is None or a["mode"] == b["mode"]) for a, b in zip(base, new))
    cn, cb = pair_table(base, new, ["case", "wind", "cpu", "wall", "evaluations", "end", "flutter", "mode", "divergence"])
    print(f"CPU {cn:.1f} s against {cb:.1f} s ({cn / cb:.2f} x), {sum(r['evaluations'] for r in new)} operating "
          f"points against {sum(r['evaluations'] for r in base)}")
    print(f"times in s (this process's CPU, one BLAS thread); rotor speeds in RPM; the baseline's onsets below "
          f"the bound kept (within {TOL} RPM), those above it gone: {ok}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
