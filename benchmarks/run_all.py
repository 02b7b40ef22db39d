"""Run every ``benchmarks/bench_*.py`` (any engineer's) and print its output, then a summary.

Each script runs in its own Python process (same interpreter), so one failing benchmark does not
stop the others and peak memories do not mix. ``--quick`` is forwarded through the environment
variable ``WINDFLUTTER_BENCH_QUICK=1`` (and as an argument to scripts whose source mentions
``--quick``), so scripts that support a reduced size use it.

Usage: python benchmarks/run_all.py [--quick] [--only PATTERN] [--timeout SECONDS]
"""

from __future__ import annotations

import argparse
import fnmatch
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def machine() -> str:
    """The machine the timings are from: CPU model, cores usable, OS, Python (printed first)."""
    import platform

    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            cpu = next((ln.split(":", 1)[1].strip() for ln in fh if ln.startswith("model name")), cpu)
    except OSError:
        pass
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return (f"machine: {cpu}, {usable} of {os.cpu_count()} cores usable, {platform.platform()}, "
            f"Python {platform.python_version()}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="reduced problem sizes where supported")
    ap.add_argument("--only", default="*", help="glob on the script name, e.g. 'bench_lin*'")
    ap.add_argument("--timeout", type=float, default=3600.0, help="per-script limit (s)")
    args = ap.parse_args(argv)

    scripts = sorted(p for p in HERE.glob("bench_*.py") if fnmatch.fnmatch(p.name, args.only)
                     or fnmatch.fnmatch(p.stem, args.only))
    if not scripts:
        print(f"no benchmarks/bench_*.py matches {args.only!r}")
        return 1
    env = dict(os.environ)
    src = HERE.parent / "src"
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(src), env.get("PYTHONPATH", "")]))
    if args.quick:
        env["WINDFLUTTER_BENCH_QUICK"] = "1"
    print(machine(), flush=True)
    summary = []
    for script in scripts:
        cmd = [sys.executable, str(script)]
        if args.quick and "--quick" in script.read_text(errors="replace"):
            cmd.append("--quick")
        print(f"\n##### {script.name} #####", flush=True)
        t0 = time.perf_counter()
        try:
            proc = subprocess.run(cmd, env=env, cwd=HERE.parent, timeout=args.timeout)
            status = "ok" if proc.returncode == 0 else f"exit {proc.returncode}"
        except subprocess.TimeoutExpired:
            status = f"timeout after {args.timeout:.0f} s"
        summary.append((script.name, status, time.perf_counter() - t0))
    print("\n##### summary #####")
    w = max(len(s[0]) for s in summary)
    for name, status, dt in summary:
        print(f"{name.ljust(w)}  {status:<22} {dt:8.1f} s")
    return 0 if all(s[1] == "ok" for s in summary) else 1


if __name__ == "__main__":
    sys.exit(main())
