"""Output folders and ``--resume`` states of ``windflutter run``.

Refused in one line (exit 2) before any work: an output path that cannot be a writable folder,
names of the run's files taken by the wrong kind of entry, and a resume of anything but the same
run (no or an unusable ``analysis.yaml``, another config, another turbine *content*, another
windflutter version).  Point files that cannot be read are computed again instead (that is not
an error: the run completes and equals an uninterrupted one)."""

from __future__ import annotations

import os

import pytest
import yaml

from cli_cases import RESUME_CONFIG, assert_one_line_error, recorded_run
from helpers import assert_same_results  # tests/workflow/helpers.py

CFG = RESUME_CONFIG


@pytest.fixture
def setup(tmp_path):
    return recorded_run(tmp_path)


def _resume(run_cli, cfg, turbine, out, *extra):
    return run_cli(["run", turbine, "-c", cfg, "-o", out, "-q", "--workers", "1", "--resume", *extra])


def _edit_record(out, **changes):
    path = out / "analysis.yaml"
    rec = yaml.safe_load(path.read_text())
    rec.update(changes)
    path.write_text(yaml.safe_dump(rec))


RECORDS = [
    ("binary", b"\x80\x81\xfe\xff" * 10, "UTF-8"), ("syntax", b"fingerprint: [1, 2\n", "valid YAML"),
    ("list", b"- fingerprint\n- abc\n", "fingerprint"), ("scalar", b"42\n", "fingerprint"),
    ("empty", b"", "fingerprint"), ("no-fingerprint", b"config: {}\n", "fingerprint"),
    ("fingerprint-int", b"fingerprint: 5\n", "fingerprint"),
    ("duplicate", b"fingerprint: a\nfingerprint: b\n", "duplicate key"),
    ("deep", b"fingerprint: " + b"[" * 80 + b"]" * 80 + b"\n", "nesting"),
]


@pytest.mark.parametrize("case, content, words", RECORDS, ids=[r[0] for r in RECORDS])
def test_resume_refuses_an_unusable_record(setup, run_cli, no_heavy_work, case, content, words):
    cfg, turbine, out = setup
    (out / "analysis.yaml").write_bytes(content)
    rc, _, err = _resume(run_cli, cfg, turbine, out)
    assert_one_line_error(rc, err, "--resume", words)


def test_resume_refuses_a_folder_without_record(setup, run_cli, no_heavy_work, tmp_path):
    cfg, turbine, out = setup
    for folder in (tmp_path / "never_made", tmp_path / "empty"):
        if folder.name == "empty":
            folder.mkdir()
        rc, _, err = _resume(run_cli, cfg, turbine, folder)
        assert_one_line_error(rc, err, "--resume", "no analysis.yaml")
        assert not (folder / "analysis.yaml").exists()


@pytest.mark.parametrize("what, change, words", [
    ("config", lambda cfg, t, out: cfg.write_text(yaml.safe_dump({**CFG, "wind_speeds": [4, 10, 17]})), "analysis config"),
    ("config-density", lambda cfg, t, out: cfg.write_text(yaml.safe_dump({**CFG, "air_density": 1.1})), "analysis config"),
    ("turbine-content", lambda cfg, t, out: t.write_text("toy rotor, radius 41 m\n"), "turbine"),
    ("version", lambda cfg, t, out: _edit_record(out, windflutter_version="0.0.1"), "windflutter version"),
    ("fingerprint", lambda cfg, t, out: _edit_record(out, fingerprint="0123456789abcdef"), "run fingerprint"),
])
def test_resume_refuses_another_run(setup, run_cli, no_heavy_work, what, change, words):
    cfg, turbine, out = setup
    change(cfg, turbine, out)
    rc, _, err = _resume(run_cli, cfg, turbine, out)
    assert_one_line_error(rc, err, "--resume", words)


OUTDIRS = [
    ("devnull", lambda d: "/dev/null", "existing file or device"),
    ("file", lambda d: _file(d / "f"), "existing file"),
    ("through-file", lambda d: _file(d / "f") / "sub", "is a file"),
    ("unwritable", lambda d: "/sys", "cannot be written"),
    ("unwritable-parent", lambda d: "/sys/windflutter/out", "cannot be written"),
    ("empty", lambda d: "", "folder path"),
    ("results-folder", lambda d: _entry(d, "results.nc", folder=True), "results.nc"),
    ("points-file", lambda d: _entry(d, "points", folder=False), "points"),
    ("record-folder", lambda d: _entry(d, "analysis.yaml", folder=True), "analysis.yaml"),
    ("report-folder", lambda d: _entry(d, "report.html", folder=True), "report.html"),
    ("figures-file", lambda d: _entry(d, "figures", folder=False), "figures"),
    ("animations-file", lambda d: _entry(d, "animations", folder=False), "animations"),
]


def _file(p):
    p.write_text("x")
    return p


def _entry(d, name, folder):
    out = d / "out_entry"
    out.mkdir(exist_ok=True)
    (out / name).mkdir() if folder else (out / name).write_text("x")
    return out


@pytest.mark.parametrize("resume", [False, True], ids=["fresh", "resume"])
@pytest.mark.parametrize("case, make, words", OUTDIRS, ids=[o[0] for o in OUTDIRS])
def test_bad_output_folder(setup, run_cli, no_heavy_work, tmp_path, case, make, words, resume):
    cfg, turbine, _ = setup
    rc, _, err = run_cli(["run", turbine, "-c", cfg, "-o", make(tmp_path), "-q"] + (["--resume"] if resume else []))
    assert_one_line_error(rc, err, "-o", words)


# ------------------------------------------------------------------------------------------
# a complete toy run, then resumes of copies of it
# ------------------------------------------------------------------------------------------
RUN = {**CFG, "wind_speeds": [4, 10, 16, 20, 25], "rotor_speed": {"min_rpm": 2, "max_rpm": 26, "n_points": 5}}


@pytest.fixture(scope="module")
def toy_run(tmp_path_factory):
    from windflutter.cli import main

    d = tmp_path_factory.mktemp("toy_run")
    cfg, turbine = d / "analysis.yaml", d / "turbine.txt"
    cfg.write_text(yaml.safe_dump(RUN))
    turbine.write_text("toy rotor\n")
    assert main(["run", str(turbine), "-c", str(cfg), "-o", str(d / "ref"), "-q", "--workers", "1"]) == 0
    return cfg, turbine, d / "ref"


def _copy(ref, tmp_path):
    import shutil

    return shutil.copytree(ref, tmp_path / "run")


def test_output_only_settings_do_not_block_resume(toy_run, run_cli, tmp_path):
    # output options and the title are not in the fingerprint: a resume may change them
    from windflutter.post import store

    cfg, turbine, ref = toy_run
    out = _copy(ref, tmp_path)
    cfg2 = tmp_path / "cfg2.yaml"
    cfg2.write_text(yaml.safe_dump({**RUN, "output": {**RUN["output"], "dpi": 50}, "title": "again"}))
    rc, _, err = run_cli(["run", turbine, "-c", cfg2, "-o", out, "-q", "--resume"])
    assert rc == 0 and err == "", err
    assert store.open_results(out).attrs["title"] == "again"


def _corrupt(path, how, folder):
    data = path.read_bytes()
    if how == "empty":
        path.write_bytes(b"")
    elif how == "truncated":
        path.write_bytes(data[: len(data) // 2])
    elif how == "garbage":
        path.write_bytes(os.urandom(2000))
    elif how == "not-a-point":
        import xarray as xr

        xr.Dataset({"x": ("a", [1.0])}).to_netcdf(path)
    elif how == "other-index":
        path.write_bytes((folder / "p0000.nc").read_bytes())


CORRUPT = {1: "empty", 2: "truncated", 3: "garbage", 4: "not-a-point"}


def test_unreadable_point_files_are_computed_again(toy_run, run_cli, tmp_path):
    # p0000 stays good; p0001..p0004 are spoilt in four ways (the last one by copying p0000 in,
    # too, in a second round): each is computed again and the results equal the reference
    from windflutter.post import store

    cfg, turbine, ref = toy_run
    out = _copy(ref, tmp_path)
    for rnd, corrupt in enumerate((CORRUPT, {4: "other-index"})):
        for i, how in corrupt.items():
            _corrupt(out / "points" / f"p{i:04d}.nc", how, out / "points")
        rc, _, err = run_cli(["run", turbine, "-c", cfg, "-o", out, "-q", "--workers", "1", "--resume"])
        assert rc == 0, err
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert len(lines) == len(corrupt), err
        for (i, _), line in zip(sorted(corrupt.items()), lines):
            assert f"points/p{i:04d}.nc" in line and "computed again" in line, line
        assert "Traceback" not in err
        assert_same_results(store.open_results(ref), store.open_results(out))
        assert sorted(store.read_points(out)) == [0, 1, 2, 3, 4]
