"""``windflutter run`` with the operating points in parallel: 2 local worker processes and a Dask
``LocalCluster`` give the same dataset as a serial run; failures, Ctrl-C + resume and progress
keep working; bad ``--workers`` values are refused by name.

Tolerance: none. Each point is a pure function of its input and runs the same code with the
same BLAS threading wherever it runs, so the datasets must be *equal* (``xr.testing.assert_equal``
via ``helpers.assert_same_results``), apart from the wall-clock times.
"""

from __future__ import annotations

import io

import numpy as np
import pytest

import toy_analyser
from helpers import assert_same_results
from windflutter.cli import main
from windflutter.errors import InputError
from windflutter.post import store
from windflutter.workflow import RunInterrupted, run


@pytest.fixture
def cluster(dask_cluster):
    # tests/conftest.py: its spawned workers find the toy analyser of this folder through
    # PYTHONPATH, as a user's plug-in module would be installed on a cluster
    return dask_cluster


@pytest.fixture
def serial_ref(toy_config, tmp_path):
    def make(cfg):
        return run(None, cfg, tmp_path / "serial", progress=False, workers=1)
    return make


def test_two_local_workers_equal_serial(toy_config, tmp_path, serial_ref):
    cfg = toy_config(output={"animations": True, "animation_frames": 4})
    ref = serial_ref(cfg)
    par = run(None, cfg, tmp_path / "par", progress=False, workers=2)
    assert par.sizes["point"] == 8 and par.attrs["complete"] == 1
    assert np.isfinite(par["flutter_rpm"].values).any()     # the comparison is not vacuous
    assert_same_results(par, ref)
    assert_same_results(store.open_results(tmp_path / "par"), store.open_results(tmp_path / "serial"))
    # every stored point is on disk as its own file, animations written by the workers
    assert len(list((tmp_path / "par" / "points").glob("p*.nc"))) == 8
    anims = sorted(p.name for p in (tmp_path / "par" / "animations").glob("*.pvd"))
    assert anims == sorted(p.name for p in (tmp_path / "serial" / "animations").glob("*.pvd"))
    assert anims


def test_dask_local_cluster_equals_serial(toy_config, tmp_path, serial_ref, cluster):
    cfg = toy_config(wind_speeds=[4, 16, 25], aero=["potential"])
    ref = serial_ref(cfg)
    out = tmp_path / "dask"
    ds = run(None, cfg, out, progress=False, scheduler=cluster.scheduler_address)
    assert_same_results(ds, ref)
    assert_same_results(store.open_results(out), store.open_results(tmp_path / "serial"))


def test_failed_point_recorded_in_parallel(toy_config, tmp_path, monkeypatch):
    monkeypatch.setenv("TOY_FAIL_WIND", "10")
    ds = run(None, toy_config(aero=["potential"]), tmp_path, progress=False, workers=2)
    assert list(ds["status"].values) == ["ok", "failed", "ok", "ok"]
    assert "ConvergenceError" in ds["reason"].values[1] and "10.0 m/s" in ds["reason"].values[1]


class InterruptAt(toy_analyser.ToyAnalyser):
    """Raises KeyboardInterrupt (as Ctrl-C does in a worker) at one wind speed."""

    def __init__(self, wind):
        super().__init__()
        self.wind = wind

    def __call__(self, point, progress=None):
        if point.wind_speed == self.wind:
            raise KeyboardInterrupt
        return super().__call__(point, progress)


def test_interrupt_in_a_worker_then_resume_in_parallel_equals_serial(toy_config, tmp_path, serial_ref):
    cfg = toy_config(wind_speeds=[4, 10, 16, 25], aero=["potential"])
    ref = serial_ref(cfg)
    out = tmp_path / "cut"
    with pytest.raises(RunInterrupted) as ei:
        run(None, cfg, out, progress=False, workers=2, analyser=InterruptAt(16.0))
    n = ei.value.done
    assert n < 4 and ei.value.total == 4
    assert len(list((out / "points").glob("p*.nc"))) == n
    if n:
        assert store.open_results(out).sizes["point"] == n
    res = run(None, cfg, out, resume=True, progress=False, workers=2)
    assert_same_results(res, ref)


def test_progress_advances_per_finished_point(toy_config, tmp_path):
    buf = io.StringIO()
    run(None, toy_config(wind_speeds=[4, 10, 16], aero=["potential"]), tmp_path, progress=True,
        stream=buf, workers=2)
    out = buf.getvalue()
    assert "3/3" in out and "local worker processes" in out


@pytest.mark.parametrize("bad", [0, -2, 1.5, "2", True])
def test_bad_workers_is_an_input_error(toy_config, tmp_path, bad):
    with pytest.raises(InputError, match="workers"):
        run(None, toy_config(), tmp_path / "x", progress=False, workers=bad)
    assert not (tmp_path / "x").exists()           # refused before anything is written


@pytest.mark.parametrize("bad", ["0", "two", "1.5", "-1"])
def test_cli_bad_workers_names_the_flag(tmp_path, capsys, bad):
    rc = main(["run", "nrel5mw", "-o", str(tmp_path / "x"), "-q", "--workers", bad])
    err = capsys.readouterr().err
    assert rc == 2
    assert "--workers" in err and bad in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.slow  # 10 s; the default suite's real runs on workers: workflow/test_campbell_from_map.py,
# system/test_campbell_workers.py (the same model, serial = parallel); the toy runs below
def test_nrel5mw_beam_two_workers_equal_serial(tmp_path):
    """Reduced real run through the CLI: bundled NREL 5 MW beam model (coarse: 10 strips and
    elements per blade, 15 modes per reference speed), two wind speeds, 4 rotor speeds; the
    whole dataset (Campbell frequencies and damping of every tracked mode, onsets) must be equal."""
    cfg = tmp_path / "analysis.yaml"
    cfg.write_text("""
wind_speeds: [8, 12]
aero: [potential]
rotor_speed: {min_rpm: 14, max_rpm: 36, n_points: 4, tolerance_rpm: 0.1}
model: {type: beam, n_aero_sections: 10}
solver: {reduction: modal, basis_modes: 15, n_eig: 12}
output: {plots: false, report: false, animations: false, mode_shapes: false}
campbell: {enabled: false}   # the run loop in parallel is the check (campbell: tests/system, tests/cli)
""")
    for name, workers in (("serial", "1"), ("par", "2")):
        assert main(["run", "nrel5mw", "-c", str(cfg), "-o", str(tmp_path / name), "-q",
                     "--workers", workers]) == 0
    a, b = store.open_results(tmp_path / "serial"), store.open_results(tmp_path / "par")
    assert list(a["status"].values) == ["ok", "ok"]
    f = a["frequency"].values
    assert (f[np.isfinite(f)] > 0).sum() >= 8             # a real Campbell diagram was compared
    assert_same_results(b, a)
    assert a.attrs["n_dof"] == b.attrs["n_dof"] > 0         # model size reported by the workers


def test_cli_unreachable_scheduler_names_the_flag(tmp_path, capsys):
    # nothing listens on port 9 (discard): refused with one line, before OUTDIR is created
    rc = main(["run", "nrel5mw", "-o", str(tmp_path / "x"), "-q", "--scheduler", "tcp://127.0.0.1:9"])
    err = capsys.readouterr().err
    assert rc == 2 and "--scheduler" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "x").exists()
