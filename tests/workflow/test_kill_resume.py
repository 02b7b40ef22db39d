"""A real ``windflutter run`` process is interrupted (SIGINT = Ctrl-C) and killed (SIGKILL);
``--resume`` completes it and the results equal those of an uninterrupted run."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from helpers import assert_same_results
from windflutter.config import load_config
from windflutter.post import store
from windflutter.workflow import run

HERE = Path(__file__).parent

CFG = {"wind_speeds": [4, 8, 12, 16, 20, 25], "aero": ["potential"],
       "rotor_speed": {"min_rpm": 2, "max_rpm": 26, "n_points": 7},
       "solver": {"backend": "toy", "n_tracked": 2},
       "output": {"plots": False, "report": False}}


def _env(delay):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(HERE), env.get("PYTHONPATH", "")])
    env["TOY_DELAY"] = str(delay)
    env.pop("TOY_FAIL_WIND", None)
    return env


def _start(cfg_path, outdir, delay, resume=False):
    cmd = [sys.executable, "-m", "windflutter", "run", "toy", "-c", str(cfg_path), "-o", str(outdir), "-q"]
    if resume:
        cmd.append("--resume")
    return subprocess.Popen(cmd, env=_env(delay), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _n_points(outdir):
    return len(list((Path(outdir) / "points").glob("p*.nc")))


def _wait_for_points(proc, outdir, n, timeout=300.0):
    t0 = time.monotonic()
    while _n_points(outdir) < n:
        if proc.poll() is not None:
            out, err = proc.communicate()
            pytest.fail(f"run ended early (rc {proc.returncode}): {err[-2000:]}")
        if time.monotonic() - t0 > timeout:
            proc.kill()
            pytest.fail("no progress")
        time.sleep(0.05)


def test_sigint_then_sigkill_then_resume_equals_uninterrupted(tmp_path):
    cfg_path = tmp_path / "analysis.yaml"
    cfg_path.write_text(yaml.safe_dump(CFG))
    out = tmp_path / "out"

    # 1) Ctrl-C after two points: exit 130, finished points kept, a hint to resume
    p = _start(cfg_path, out, delay=0.3)
    _wait_for_points(p, out, 2)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=300)
    assert p.returncode == 130, err
    assert "--resume" in err and "Traceback" not in err
    n1 = _n_points(out)
    assert 2 <= n1 < 6
    assert store.open_results(out).sizes["point"] == n1

    # 2) resume, then SIGKILL (no chance to clean up) once more points are stored
    p = _start(cfg_path, out, delay=0.3, resume=True)
    _wait_for_points(p, out, n1 + 1)
    p.send_signal(signal.SIGKILL)
    p.communicate(timeout=300)
    assert p.returncode == -signal.SIGKILL
    n2 = _n_points(out)
    assert n1 < n2 < 6

    # 3) resume to the end, with the report on (output options do not change results)
    cfg2 = dict(CFG, output={"plots": True, "report": True, "dpi": 30})
    cfg2_path = tmp_path / "analysis_report.yaml"
    cfg2_path.write_text(yaml.safe_dump(cfg2))
    p = _start(cfg2_path, out, delay=0.0, resume=True)
    stdout, err = p.communicate(timeout=300)
    assert p.returncode == 0, err
    assert f"report: {(out / 'report.html').resolve()}" in stdout
    assert "6 operating points, 0 failed" in stdout

    # the uninterrupted reference, computed in this process
    ref = run("toy", load_config(None, CFG), tmp_path / "ref", progress=False)
    resumed = store.open_results(out)
    assert resumed.attrs["complete"] == 1
    # config_yaml records the output options of the last invocation (report on); the
    # config_fingerprint (compared) covers everything that changes results
    assert_same_results(resumed, store.open_results(tmp_path / "ref"), ignore_attrs=("config_yaml",))
    assert_same_results(resumed, ref, ignore_attrs=("config_yaml",))
    assert not list(out.rglob("*.tmp"))


def test_ctrl_c_while_storing_is_held_until_the_files_are_written():
    # A Ctrl-C that landed inside a NetCDF write left xarray's file lock held, and the
    # interrupt handler's final write then hung (1 run in 4 of the test above).  The point's
    # files are now written with SIGINT held: the block runs to its end, then the interrupt.
    import os

    from windflutter.workflow import _sigint_deferred

    steps = []
    # Python's own Ctrl-C handler for the test, whatever the runner installed (a runner that ignores
    # SIGINT would otherwise swallow the interrupt); the guard must restore the handler it found
    saved = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            with _sigint_deferred():
                os.kill(os.getpid(), signal.SIGINT)
                time.sleep(0.05)
                steps.append("written")
        assert steps == ["written"]
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    finally:
        signal.signal(signal.SIGINT, saved)
