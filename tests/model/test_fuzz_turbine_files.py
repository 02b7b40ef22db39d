"""Hostile turbine files (tests/model/fuzz_cases.py, 120+ mutations of the bundled windIO,
OpenFAST and HAWC2 models): every one ends in an InputError naming the field (and the station
where a table is concerned) or, for unusual data, an InputWarning kept on the Turbine - never
another exception, a hang or a silent number.  All fail while the files are read, before any
mesh or FE work (the whole suite runs in a few seconds)."""

from __future__ import annotations

import copy
import functools
import shutil
import warnings

import pytest

from fuzz_cases import ALL, Case
from windflutter.errors import InputError, InputWarning
from windflutter.model import load_turbine
from windflutter.model.bundled import DATA_DIR
from windflutter.model.consistency import finish_turbine
from windflutter.model.supplement import apply_supplement
from windflutter.model.windio import read_windio_dict
from windflutter.model.yamlio import load_yaml_file

_WINDIO = {"windio2": ("turbines/NREL-5MW.yaml", "turbines/NREL-5MW.windflutter.yaml"),
           "windio1": ("turbines/windIO_v1/IEA-15-240-RWT.yaml", "turbines/IEA-15-240-RWT.windflutter.yaml")}
_DECKS = {"openfast15": ("iea15mw/openfast", "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile.fst"),
          "openfast5": ("nrel5mw", "NREL-5MW_Onshore.fst"), "hawc2": ("nrel5mw/hawc2", "htc/NREL_5MW.htc")}


@functools.lru_cache(maxsize=None)
def _raw(rel: str) -> dict:
    return load_yaml_file(DATA_DIR / rel)


def _load(case: Case, tmp_path):
    """Apply the case's mutation and read the result as the readers do."""
    if case.base in _WINDIO:
        f, s = _WINDIO[case.base]
        d, supp = copy.deepcopy(_raw(f)), copy.deepcopy(_raw(s)["windflutter"])
        supp.pop("blade_beam", None)  # the file's own 6x6 is the one under test
        case.mutate(d, supp)
        src = str(tmp_path / "fuzz.yaml")
        t, raw = read_windio_dict(d, source=src, validate=False)
        t = apply_supplement(t, raw, supp, base_dir=DATA_DIR / "turbines", source=src)
        return finish_turbine(t, (src,))
    if case.base == "yaml":
        p = tmp_path / "fuzz.yaml"
        case.mutate(p)
        return load_turbine(p)
    folder, main = _DECKS[case.base]
    root = tmp_path / "model"
    shutil.copytree(DATA_DIR / folder, root, ignore=shutil.ignore_patterns("*.yaml") if case.base != "openfast5" else None)
    if case.base == "hawc2":  # its htc names ../NREL5MW_hawc2_operational_data.opt
        shutil.copy(DATA_DIR / "nrel5mw" / "NREL5MW_hawc2_operational_data.opt", tmp_path)
    case.mutate(root)
    return load_turbine(root / main)


@pytest.mark.parametrize("case", [c for c in ALL if c.error], ids=lambda c: c.id)
def test_hostile_file_is_refused_by_name(case, tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputWarning)
        with pytest.raises(InputError) as exc:
            _load(case, tmp_path)
    assert case.error in str(exc.value), str(exc.value)


@pytest.mark.parametrize("case", [c for c in ALL if c.warn], ids=lambda c: c.id)
def test_unusual_file_warns_and_records(case, tmp_path):
    with pytest.warns(InputWarning) as rec:
        t = _load(case, tmp_path)
    assert any(case.warn in str(w.message) for w in rec), [str(w.message) for w in rec]
    assert any(case.warn in w for w in t.warnings)


def test_count_of_cases():
    assert len(ALL) >= 100 and len({c.id for c in ALL}) == len(ALL)


@pytest.mark.parametrize("case_id", ["K66-negative-station-17", "beamdyn-main-without-kp_zr", "st-E-negative-station-7"])
def test_cli_prints_one_line_and_exits_2(case_id, tmp_path, capsys):
    """Through the command line (in-process): exit code 2, one line on stderr naming the field,
    no traceback."""
    import yaml

    from windflutter.cli import main

    case = next(c for c in ALL if c.id == case_id)
    if case.base in _WINDIO:
        f, s = _WINDIO[case.base]
        d, supp = copy.deepcopy(_raw(f)), copy.deepcopy(_raw(s)["windflutter"])
        supp.pop("blade_beam", None)
        supp.pop("operating_curve", None)
        supp.pop("tower", None)
        case.mutate(d, supp)
        d["windflutter"] = supp
        path = tmp_path / "bad.yaml"
        path.write_text(yaml.safe_dump(d))
    else:
        folder, main_file = _DECKS[case.base]
        shutil.copytree(DATA_DIR / folder, tmp_path / "model")
        shutil.copy(DATA_DIR / "nrel5mw" / "NREL5MW_hawc2_operational_data.opt", tmp_path)
        case.mutate(tmp_path / "model")
        path = tmp_path / "model" / main_file
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputWarning)
        code = main(["modes", str(path), "--part", "blade", "--model", "beam"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and case.error in err[0] and "Traceback" not in err[0], err
