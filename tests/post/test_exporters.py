"""The exporter registry (:mod:`windflutter.exporters`): ``windflutter campbell --export FILE``, its
aliases ``--csv/--cmb/--amp/--plot``, ``output.exports`` of a run's config, and plug-in formats.

The analysis is replaced by the synthetic Campbell result of ``post_fixtures`` (every number
chosen there), so each test checks only the routing: the file a format writes is read back with
the format's own reader (CSV, ``.cmb``, NetCDF) and compared with the result, or compared byte for
byte with the writer called directly (``.amp``), or checked to be the image its suffix says.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest
from post_fixtures import json_rows, synthetic_campbell

from windflutter import exporters
from windflutter.errors import InputError


@pytest.fixture
def cli(monkeypatch, capsys):
    """``windflutter ...`` in this process, the Campbell analysis replaced by the synthetic result."""
    import windflutter.api
    from windflutter.cli import main

    res = synthetic_campbell()
    monkeypatch.setattr(windflutter.api, "campbell", lambda *a, **k: res)

    def call(*argv):
        rc = main(["campbell", "nrel5mw", *[str(a) for a in argv]])
        out, err = capsys.readouterr()
        return rc, out, err

    call.result = res
    return call


def test_builtin_names_and_suffixes():
    assert exporters.exporter_names()[:5] == ["csv", "cmb", "amp", "figure", "netcdf"]
    assert exporters.exporter_for("a.CSV").name == "csv"
    assert exporters.exporter_for("a.svg").name == "figure"
    assert exporters.exporter_for("a.nc").name == "netcdf"
    with pytest.raises(InputError, match="--format"):  # .txt: cmb and amp both write it
        exporters.exporter_for("a.txt")
    assert exporters.exporter_for("a.txt", "amp").name == "amp"
    with pytest.raises(InputError, match=r"--format.*'xlsx'.*csv, cmb, amp, figure, netcdf"):
        exporters.exporter_for("a.xlsx", "xlsx")


def test_every_builtin_through_export_round_trips(cli, tmp_path):
    from windflutter.post.campbell_amp import write_amp
    from windflutter.post.campbell_data import campbell_dataset
    from windflutter.post.campbell_export import read_cmb, read_csv
    from windflutter.post.store import open_campbell

    files = {k: tmp_path / f"c.{k}" for k in ("csv", "cmb", "amp", "png", "nc")}
    rc, out, err = cli(*[a for f in files.values() for a in ("--export", f)], "--json")
    assert rc == 0, err
    res = cli.result
    assert read_csv(files["csv"]) == json_rows(res)      # repr floats: exact
    cmb = read_cmb(files["cmb"])
    assert cmb.names == [t.name for t in res.tracks]
    np.testing.assert_array_equal(cmb.wind_speed, [5.0, 11.0, 18.0])
    m = res.points[0].modes[0]
    t0 = next(t for t, tr in enumerate(res.tracks) if tr.index[0] == 0)
    assert cmb.frequency[0, t0] == pytest.approx(m.damped_frequency_hz, rel=1e-8)   # 9 digits written
    assert cmb.damping_pct[0, t0] == pytest.approx(100 * m.damping_ratio, rel=1e-8)
    assert open_campbell(files["nc"]).identical(open_campbell_like(campbell_dataset(res), tmp_path))
    assert files["png"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert files["amp"].read_text() == write_amp(res, tmp_path / "direct.amp").read_text()


def open_campbell_like(ds, tmp_path):
    """The dataset as a NetCDF round trip gives it (the stored file's own encoding)."""
    from windflutter.post.store import atomic_write_netcdf, open_campbell

    return open_campbell(atomic_write_netcdf(ds, tmp_path / "reference.nc"))


@pytest.mark.parametrize("flag, fmt, name", [("--csv", "csv", "c.csv"), ("--cmb", "cmb", "c.txt"),
                                             ("--amp", "amp", "c.amp"), ("--plot", "figure", "c.svg")])
def test_old_flags_are_aliases_of_export(cli, tmp_path, flag, fmt, name):
    old, new = tmp_path / "old" / name, tmp_path / "new" / name
    assert cli(flag, old)[0] == 0
    assert cli("--export", new, "--format", fmt)[0] == 0
    if fmt == "figure":  # an SVG carries its creation date; the drawing is the same
        assert old.read_text().count("<path") == new.read_text().count("<path") > 0
    else:
        assert old.read_bytes() == new.read_bytes()


@pytest.mark.parametrize("argv, words", [
    (["--export", "c.xlsx"], ["--export", "c.xlsx", ".csv", ".nc"]),
    (["--export", "c.txt"], ["--export", "--format", "cmb", "amp"]),
    (["--export", "c.csv", "--format", "bogus"], ["--format", "bogus", "csv, cmb, amp, figure, netcdf"]),
    (["--export", "c.csv", "--format", "cmb"], ["--export", ".cmb"]),
    (["--csv", "c.cmb"], ["--csv", ".csv"]),
    (["--plot", "c.gif"], ["--plot", ".png"]),
])
def test_bad_export_is_one_line_naming_the_flag(cli, tmp_path, monkeypatch, argv, words):
    monkeypatch.chdir(tmp_path)
    rc, _, err = cli(*argv)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert rc == 2 and len(lines) == 1 and "Traceback" not in err, err
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert list(tmp_path.iterdir()) == []


def _toy_writer(campbell, path, *, field, dpi):
    """A plug-in format: the least damped mode in one line (the test's own reading of the result)."""
    p, m = campbell.least_damped()
    path.write_text(f"{m.name};{p.wind_speed:g};{m.damping_ratio!r};{field};{dpi}\n")
    return path


TOY = exporters.Exporter("toy", (".toy",), _toy_writer, "test plug-in")


def _expected_toy(res, field):
    p, m = res.least_damped()
    return f"{m.name};{p.wind_speed:g};{m.damping_ratio!r};{field};110\n"


def test_registered_plugin_is_reachable_from_the_cli(cli, tmp_path):
    exporters.register_exporter(TOY)
    try:
        assert "toy" in exporters.exporter_names()
        assert cli("--export", tmp_path / "a.toy")[0] == 0
        assert (tmp_path / "a.toy").read_text() == _expected_toy(cli.result, "--export")
    finally:
        exporters.unregister_exporter("toy")
    rc, _, err = cli("--export", tmp_path / "b.toy")
    assert rc == 2 and "--export" in err and ".toy" not in exporters.exporter_for("a.csv").suffixes


def test_entry_point_plugin_is_reachable_from_the_cli_and_the_config(cli, tmp_path, monkeypatch):
    """A package publishing ``[windflutter.exporters] toy = ...`` (a distribution on sys.path)."""
    pkg = tmp_path / "plugins"
    (pkg / "toy_export_plugin-0.dist-info").mkdir(parents=True)
    (pkg / "toy_export_plugin-0.dist-info" / "METADATA").write_text(
        "Metadata-Version: 2.1\nName: toy-export-plugin\nVersion: 0\n")
    (pkg / "toy_export_plugin-0.dist-info" / "entry_points.txt").write_text(
        "[windflutter.exporters]\ntoy = toy_export_plugin:EXPORTER\nbare = toy_export_plugin:write\n")
    (pkg / "toy_export_plugin.py").write_text(textwrap.dedent("""
        from windflutter.exporters import Exporter
        def write(campbell, path, *, field, dpi):
            path.write_text(f"{len(campbell.points)} points;{field};{dpi}\\n")
        EXPORTER = Exporter("toy", (".toy",), write)
    """))
    monkeypatch.syspath_prepend(str(pkg))
    assert {"toy", "bare"} <= set(exporters.exporter_names())
    assert cli("--export", tmp_path / "a.toy")[0] == 0
    assert (tmp_path / "a.toy").read_text() == "3 points;--export;110\n"
    assert cli("--export", tmp_path / "b.dat", "--format", "bare")[0] == 0  # no suffixes: by name
    assert (tmp_path / "b.dat").read_text() == "3 points;--export;110\n"

    from windflutter.config import load_config
    from windflutter.workflow import write_exports

    config = load_config(None, {"output": {"exports": ["toy", "csv", "netcdf"], "dpi": 80}})
    written = write_exports(cli.result, config, tmp_path / "run")
    assert (tmp_path / "run" / "campbell.toy").read_text() == "3 points;output.exports;80\n"
    assert written["csv"] == tmp_path / "run" / "campbell.csv" and written["csv"].is_file()
    assert not (tmp_path / "run" / "campbell.nc").exists()  # the run's own store writes campbell.nc


@pytest.mark.parametrize("value", ["bogus", ["csv", "csv"], ["csv", 3], {"a": 1}])
def test_bad_config_exports_name_the_field_value_and_registered_formats(value):
    from windflutter.config import load_config

    with pytest.raises(InputError) as exc:
        load_config(None, {"output": {"exports": value}})
    msg = str(exc.value)
    assert "output.exports" in msg
    if value == "bogus":
        assert "'bogus'" in msg and "csv, cmb, amp, figure, netcdf" in msg and "windflutter.exporters" in msg


def test_config_exports_without_a_campbell_warn_and_write_nothing(tmp_path):
    from windflutter.config import load_config
    from windflutter.errors import InputWarning
    from windflutter.workflow import write_exports

    config = load_config(None, {"output": {"exports": ["csv"]}})
    with pytest.warns(InputWarning, match="output.exports"):
        assert write_exports(None, config, tmp_path) == {}
    assert list(tmp_path.iterdir()) == []
    assert math.isfinite(config.output.dpi)
