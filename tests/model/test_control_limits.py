"""The windIO control block: impossible speeds are refused by name, unusual ones warned about.

A negative ``VS_maxspd`` used to be accepted by ``modes`` and ``stability`` without a word (issue
34).  Bounds (:mod:`windflutter.model.plausibility`): speeds, cut-in/out, TSR and rates positive,
cut-out above cut-in, minimum rotor speed at most the maximum, the maximum's tip speed below the
speed of sound (340 m/s) -- errors; a tip speed outside 40-130 m/s or a TSR outside 3-15 -- one
warning naming the key.
"""

from __future__ import annotations

import copy
import warnings
from pathlib import Path

import pytest
import yaml

from windflutter.errors import InputError, InputWarning
from windflutter.model.windio import read_windio_dict
from windflutter.model.yamlio import load_yaml_file

NREL = Path(__file__).resolve().parents[2] / "src/windflutter/data/turbines/NREL-5MW.yaml"


@pytest.fixture(scope="module")
def nrel():
    return load_yaml_file(NREL)


def _read(data, change):
    d = copy.deepcopy(data)
    for path, value in change.items():
        *keys, last = path.split(".")
        node = d
        for key in keys:
            node = node.setdefault(key, {})
        node[last] = value
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t, _ = read_windio_dict(d, "t.yaml", validate=False)
    return t, [str(w.message) for w in caught if issubclass(w.category, InputWarning)]


ERRORS = [
    ({"control.torque.VS_maxspd": -12.0}, "control.torque.VS_maxspd", "-12"),
    ({"control.torque.VS_maxspd": 0.0}, "control.torque.VS_maxspd", "positive"),
    ({"control.torque.VS_minspd": -1.0}, "control.torque.VS_minspd", "non-negative"),
    ({"control.torque.VS_minspd": 13.0}, "control.torque.VS_minspd", "at most the maximum"),
    ({"control.torque.tsr": -7.0}, "control.torque.tsr", "positive"),
    ({"control.torque.max_torque_rate": -1.0}, "control.torque.max_torque_rate", "positive"),
    ({"control.torque.VS_maxspd": float("nan")}, "control.torque.VS_maxspd", "finite"),
    ({"control.torque.VS_maxspd": "fast"}, "control.torque.VS_maxspd", "a number"),
    ({"control.supervisory.Vin": -3.0}, "control.supervisory.Vin", "positive"),
    ({"control.supervisory.Vout": 2.0}, "control.supervisory.Vout", "above cut-in"),
    ({"control.supervisory.maxTS": 400.0}, "control.supervisory.maxTS", "speed of sound"),
    ({"control.torque.VS_maxspd": 121.0}, "control.torque.VS_maxspd", "speed of sound"),
    ({"control.pitch.max_pitch_rate": -2.0}, "control.pitch.max_pitch_rate", "positive"),
]


@pytest.mark.parametrize("change, field, words", ERRORS, ids=[str(c[0])[:50] for c in ERRORS])
def test_impossible_control_limits_are_refused_by_name(nrel, change, field, words):
    with pytest.raises(InputError) as exc:
        _read(nrel, change)
    msg = str(exc.value)
    assert field in msg and words in msg and "t.yaml" in msg and "\n" not in msg


@pytest.mark.parametrize("change, field", [
    ({"control.torque.VS_maxspd": 3.0, "control.torque.VS_minspd": 2.0}, "control.torque.VS_maxspd"),  # 20 m/s tip
    ({"control.supervisory.maxTS": 150.0}, "control.supervisory.maxTS"),
    ({"control.torque.tsr": 25.0}, "control.torque.tsr"),
])
def test_unusual_control_limits_warn_once_by_name(nrel, change, field):
    t, warned = _read(nrel, change)
    hits = [w for w in warned if field in w]
    assert len(hits) == 1, warned
    assert any(field in w for w in t.warnings)


def test_bundled_control_blocks_are_plausible(nrel):
    """The reference turbine's own block passes without a control warning (80 m/s tip speed)."""
    _, warned = _read(nrel, {})
    assert not [w for w in warned if "control" in w]


def test_negative_max_speed_is_one_line_at_the_command_line(nrel, tmp_path, capsys):
    from windflutter.cli import main

    d = copy.deepcopy(nrel)
    d["control"]["torque"]["VS_maxspd"] = -12.0
    p = tmp_path / "t.yaml"
    p.write_text(yaml.safe_dump(d))
    for argv in (["modes", str(p)], ["stability", str(p), "--wind-speeds", "10"]):
        rc = main(argv)
        err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
        assert rc == 2 and len(err) == 1 and "control.torque.VS_maxspd = -12" in err[0], err
