"""The shape of one command at run time (issue 29): which of our modules and packages
``windflutter campbell TURBINE --wind-speeds V`` passes through, and how often a call crosses from
one of our packages into another.

Only function calls count (a module body executed on import is not a call).  A *package change*
is a call event (``sys.setprofile``) whose caller and callee are both in
windflutter and whose top-level units differ (``windflutter.system.campbell`` calling
``windflutter.structure.modal`` is one; a call inside ``system`` is none).  The issue's baseline,
measured on 2 Dec 2026 the same way at one wind speed of the IEA 15 MW: 117 modules, 22 packages,
1,988 package changes, and the command did not pass through ``windflutter.api``.

Run: ``python benchmarks/bench_call_trace.py [TURBINE] [WIND]`` (default iea15mw 10).
"""

from __future__ import annotations

import sys
import time
from collections import Counter


def unit(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def trace(argv: list[str]) -> dict:
    from windflutter.cli import main

    modules: set[str] = set()
    changes: Counter = Counter()

    def prof(frame, event, arg):
        if event != "call" or frame.f_code.co_name == "<module>":  # a module body runs on import: not a call
            return
        callee = frame.f_globals.get("__name__", "")
        if not callee.startswith("windflutter"):
            return
        modules.add(callee)
        back = frame.f_back
        caller = back.f_globals.get("__name__", "") if back is not None and back.f_code.co_name != "<module>" else ""
        if caller.startswith("windflutter") and unit(caller) != unit(callee):
            changes[(unit(caller), unit(callee))] += 1

    t0 = time.perf_counter()
    sys.setprofile(prof)
    try:
        rc = main(argv)
    finally:
        sys.setprofile(None)
    return {"rc": rc, "seconds": time.perf_counter() - t0, "modules": sorted(modules),
            "packages": sorted({unit(m) for m in modules}), "changes": changes}


def report(args: list[str]) -> None:
    turbine = args[0] if args else "iea15mw"
    wind = args[1] if len(args) > 1 else "10"
    res = trace(["campbell", turbine, "--wind-speeds", wind, "--json"])
    n = sum(res["changes"].values())
    print(f"\nwindflutter campbell {turbine} --wind-speeds {wind}: {res['seconds']:.1f} s traced", file=sys.stderr)
    print(f"modules {len(res['modules'])}, packages {len(res['packages'])}, package changes {n} "
          f"(issue 29 baseline: 117, 22, 1988)", file=sys.stderr)
    print(f"passes through windflutter.api: {'windflutter.api' in res['modules']}; distinct package edges "
          f"{len(res['changes'])}", file=sys.stderr)
    for (a, b), c in res["changes"].most_common(12):
        print(f"  {a:>12s} -> {b:<12s} {c}", file=sys.stderr)


if __name__ == "__main__":
    report(sys.argv[1:])
