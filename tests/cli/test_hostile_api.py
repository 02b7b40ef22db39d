"""Hostile keywords of the Python API and hostile output paths of ``windflutter campbell``
(issue 34).  Every API keyword -- wrong type, NaN, negative, out of range, unknown -- raises one
InputError naming the keyword (or the config field it sets) before a turbine is read; every
export path that cannot be written is refused in one line naming the flag before any work, and
one that can (an existing file, a new file) is accepted."""

from __future__ import annotations

import math

import pytest

from cli_cases import CUSTOM, assert_one_line_error, bad_values
from windflutter import api
from windflutter.config import declared_fields
from windflutter.errors import InputError


def _short(v) -> str:
    return str(v)[:12]


# ------------------------------------------------------------------------------ modes keywords
MODES_CASES = [(k, v) for k, spec in {**api.MODES_OPTIONS, **api.MESH_OPTIONS}.items()
               for v in bad_values(spec) if v is not None]  # None: the default


@pytest.mark.parametrize("key, value", MODES_CASES, ids=[f"{k}={_short(v)}" for k, v in MODES_CASES])
def test_modes_keyword(no_heavy_work, key, value):
    with pytest.raises(InputError) as exc:
        api.modes("nrel5mw", **{key: value})
    assert exc.value.field == key, str(exc.value)


# --------------------------------------------- config keywords of stability / campbell / run
def _config_cases(per_field: int):
    out = []
    for path, _, spec in declared_fields():
        values = CUSTOM.get(path) or bad_values(spec)
        out += [(path, v) for v in values[:per_field]]
    return out


CONFIG_CASES = _config_cases(2)


def _call(fn, key, value, tmp_path):
    kw = {key: value}
    if fn == "stability":
        return api.stability("nrel5mw", kw.pop("wind_speeds", 10.0), **kw)
    if fn == "campbell":
        return api.campbell("nrel5mw", kw.pop("wind_speeds", None), **kw)
    return api.run("nrel5mw", outdir=tmp_path / "out", progress=False, **kw)


CALLS = [(fn, k, v) for fn in ("stability", "campbell", "run") for k, v in CONFIG_CASES
         if not (fn == "campbell" and k == "method")]  # campbell has no search method


@pytest.mark.parametrize("fn, key, value", CALLS, ids=[f"{fn}-{k}={_short(v)}" for fn, k, v in CALLS])
def test_config_keyword(no_heavy_work, tmp_path, fn, key, value):
    with pytest.raises(InputError) as exc:
        _call(fn, key, value, tmp_path)
    assert exc.value.field.split("[")[0] in (key, key.split(".")[-1]) or key in str(exc.value), str(exc.value)


@pytest.mark.parametrize("fn", ["stability", "campbell", "run", "analysis_config"])
@pytest.mark.parametrize("key, value, words", [
    ("colour", "red", "colour"), ("solver.warp_speed", 9, "warp_speed"), ("solver", 5, "solver"),
    ("rotor_speed", {"max_rpm": math.nan}, "rotor_speed.max_rpm"), ("damping", {"tower_ratio": -0.1}, "tower_ratio"),
    ("model", 5, "model"), ("solver.n_eig", True, "solver.n_eig"), ("air_density", -1.225, "air_density"),
])
def test_unknown_or_misshapen_keyword(no_heavy_work, tmp_path, fn, key, value, words):
    with pytest.raises(InputError) as exc:
        if fn == "analysis_config":
            api.analysis_config(**{key: value})
        else:
            _call(fn, key, value, tmp_path)
    assert words in str(exc.value), str(exc.value)


@pytest.mark.parametrize("config, words", [(5, "config"), ([1], "config"), ("/no/such/analysis.yaml", "analysis"),
                                           ({"wind_speeds": "fast"}, "wind_speeds")])
def test_bad_config_argument(no_heavy_work, config, words):
    with pytest.raises(InputError) as exc:
        api.stability("nrel5mw", 10.0, config=config)
    assert words in str(exc.value), str(exc.value)


@pytest.mark.parametrize("speeds", [math.nan, -4.0, "ten", [10, math.inf], [], [[10]]], ids=str)
def test_bad_wind_speeds_positional(no_heavy_work, speeds):
    with pytest.raises(InputError) as exc:
        api.stability("nrel5mw", speeds)
    assert "wind_speeds" in str(exc.value)


def test_bad_campbell_max_hz(no_heavy_work):
    for v in (math.nan, -1.0, "high", 0.0):
        with pytest.raises(InputError) as exc:
            api.campbell("nrel5mw", max_hz=v)
        assert "campbell.max_hz" in str(exc.value)


# ------------------------------------------------------------------- campbell export paths
def _paths(tmp_path):
    existing_dir = tmp_path / "adir.csv"
    existing_dir.mkdir()
    a_file = tmp_path / "file"
    a_file.write_text("x")
    return {"unwritable": "/sys/campbell{ext}", "directory": str(existing_dir), "through-a-file": str(a_file / "c{ext}"),
            "odd-suffix": str(tmp_path / "campbell.xlsx"), "no-suffix": str(tmp_path / "campbell"),
            "devnull-child": "/dev/null/c{ext}", "empty": ""}


EXPORTS = [("--csv", ".csv"), ("--cmb", ".cmb"), ("--amp", ".amp"), ("--plot", ".png"), ("--export", ".nc"),
           ("--export", ".csv")]
BAD_PATHS = ["unwritable", "directory", "through-a-file", "odd-suffix", "no-suffix", "devnull-child", "empty"]


@pytest.mark.parametrize("flag, ext", EXPORTS, ids=[e[0] for e in EXPORTS])
@pytest.mark.parametrize("case", BAD_PATHS)
def test_campbell_export_path_refused(tmp_path, monkeypatch, run_cli, no_heavy_work, flag, ext, case):
    monkeypatch.chdir(tmp_path)
    path = _paths(tmp_path)[case].format(ext=ext)
    for extra in ([], ["--json"]):
        rc, _, err = run_cli(["campbell", "nrel5mw", flag, path, *extra])
        assert_one_line_error(rc, err, flag)


@pytest.mark.parametrize("flag, ext", EXPORTS, ids=[e[0] for e in EXPORTS])
def test_campbell_export_to_existing_file_is_accepted(tmp_path, run_cli, no_heavy_work, flag, ext):
    """An existing file of the right suffix is overwritten: the checks pass and the work starts
    (stopped here by the test's stand-in for real work)."""
    target = tmp_path / f"old{ext}"
    target.write_text("old")
    with pytest.raises(BaseException) as exc:
        run_cli(["campbell", "nrel5mw", flag, str(target)])
    assert type(exc.value).__name__ == "HeavyWork"
    assert target.read_text() == "old"  # nothing written before the analysis
