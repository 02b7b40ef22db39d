"""The shape of one command at run time (issue 29): which of our modules and packages
``windflutter campbell TURBINE --wind-speeds V`` passes through, and how often a call crosses from
one of our packages into another.

Only function calls count (a module body executed on import is not a call).  A *package change*
is a call event (``sys.setprofile``) whose caller and callee are both in
windflutter and whose top-level units differ (``windflutter.system.campbell`` calling
``windflutter.structure.modal`` is one; a call inside ``system`` is none).  The issue's baseline,
measured on 2 Dec 2026 the same way at one wind speed of the IEA 15 MW: 117 modules, 22 packages,
1,988 package changes, and the command did not pass through ``windflutter.api``.

Run: ``python benchmarks/bench_call_trace.py [--baseline REV] [TURBINE] [WIND]`` (default iea15mw 10;
``--baseline 971fc0f``: the same trace of the tree the issue was filed on, run beside this one).
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


def summary(res: dict) -> dict:
    return {"modules": len(res["modules"]), "packages": len(res["packages"]),
            "changes": sum(res["changes"].values()), "edges": len(res["changes"]),
            "api": "windflutter.api" in res["modules"], "seconds": res["seconds"]}


def baseline(rev: str, turbine: str, wind: str) -> dict:
    """The same trace of the tree at git revision ``rev`` (extracted by ``git archive`` into a
    temporary folder and run in a child process with that tree's ``src`` first on the path)."""
    import json
    import os
    import subprocess
    import tempfile
    from pathlib import Path

    repo = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(repo), "archive", rev, "src"], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        env = dict(os.environ, PYTHONPATH=str(Path(tmp) / "src"))
        out = subprocess.run([sys.executable, __file__, "--summary", turbine, wind], env=env, check=True,
                             capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def report(args: list[str]) -> None:
    import contextlib
    import io
    import json

    if args and args[0] == "--summary":  # the child of baseline(): one JSON line
        with contextlib.redirect_stdout(io.StringIO()):
            res = trace(["campbell", args[1], "--wind-speeds", args[2], "--json"])
        print(json.dumps(summary(res)))
        return
    rev = None
    if args and args[0] == "--baseline":
        rev, args = args[1], args[2:]
    turbine = args[0] if args else "iea15mw"
    wind = args[1] if len(args) > 1 else "10"
    with contextlib.redirect_stdout(io.StringIO()):
        res = trace(["campbell", turbine, "--wind-speeds", wind, "--json"])
    now = summary(res)
    rows = [("this tree", now)] + ([(rev, baseline(rev, turbine, wind))] if rev else [])
    print(f"\nwindflutter campbell {turbine} --wind-speeds {wind} (issue 29's count on 2 Dec: 117 modules, "
          "22 packages, 1,988 package changes, not through windflutter.api)")
    print(f"{'tree':>12s} {'modules':>8s} {'packages':>9s} {'changes':>8s} {'edges':>6s} {'via api':>8s} {'traced s':>9s}")
    for name, r in rows:
        print(f"{name:>12s} {r['modules']:8d} {r['packages']:9d} {r['changes']:8d} {r['edges']:6d} "
              f"{str(r['api']):>8s} {r['seconds']:9.1f}")
    if rev:
        print(f"package changes: {now['changes'] / rows[1][1]['changes']:.2f} x the baseline's")
    print("largest package edges of this tree:")
    for (a, b), c in res["changes"].most_common(12):
        print(f"  {a:>12s} -> {b:<12s} {c}")


if __name__ == "__main__":
    report(sys.argv[1:])
