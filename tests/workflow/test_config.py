"""Analysis config: defaults, merging, and one clear error per bad field."""

from __future__ import annotations

import pytest
import yaml

from windflutter.cli import main
from windflutter.config import AnalysisConfig, config_from_dict, default_config, load_config
from windflutter.config.validation import bundled_config
from windflutter.errors import InputError


def test_bundled_default_equals_dataclass_defaults():
    # the commented YAML shipped with the package and the dataclass must not drift apart; the
    # defaults a run uses without reading the file pass every field check and rule (the YAML
    # reading validates them)
    assert bundled_config() == default_config() == AnalysisConfig()
    assert config_from_dict(AnalysisConfig().to_dict(), "defaults") == AnalysisConfig()


def test_partial_file_merges_over_defaults(tmp_path):
    p = tmp_path / "a.yaml"
    p.write_text("wind_speeds: {start: 4, stop: 8, step: 2}\nrotor_speed: {max_rpm: 30}\nmethod: thesis\n")
    c = load_config(p)
    assert c.wind_speeds == (4.0, 6.0, 8.0)
    assert c.rotor_speed.max_rpm == 30.0 and c.rotor_speed.min_rpm == AnalysisConfig().rotor_speed.min_rpm
    assert c.method == ("thesis",)
    assert c.aero == ("viscous",)
    assert c.cases == [("viscous", "thesis")]
    # the resolved config survives a YAML round trip
    assert config_from_dict(yaml.safe_load(c.to_yaml())) == c


def test_fingerprint_ignores_output_only():
    a = config_from_dict({"output": {"dpi": 50}})
    b = config_from_dict({})
    c = config_from_dict({"wind_speeds": [5]})
    assert a.fingerprint() == b.fingerprint() != c.fingerprint()


BAD = [
    ({"wind_sped": [4]}, "wind_sped", "unknown key"),
    ({"solver": {"nmodes": 4}}, "solver.nmodes", "unknown key"),
    ({"wind_speeds": [4, -3]}, "wind_speeds[1]", "positive wind speed"),
    ({"wind_speeds": [8, 6]}, "wind_speeds[1]", "increasing"),
    ({"rotor_speed": {"min_rpm": 20, "max_rpm": 10}}, "rotor_speed.max_rpm", "reversed"),
    ({"rotor_speed": {"max_rpm": -1}}, "rotor_speed.max_rpm", "(0, 1000] (RPM)"),
    ({"method": ["pk", "newton"]}, "method[1]", "p, pk, thesis"),
    ({"aero": "inviscid"}, "aero[0]", "potential, viscous"),
    ({"model": {"type": "solid"}}, "model.type", "shell, beam"),
    ({"damping": {"ratio": 1.5}}, "damping.ratio", "[0, 1)"),
    ({"solver": {"n_eig": 1}}, "solver.n_eig", "integer in [2, 500]"),
    ({"solver": {"n_modes": 20}}, "solver.n_modes", "renamed: solver.n_eig"),
    ({"solver": {"shift_hz": 1.0}}, "solver.shift_hz", "removed"),
    ({"solver": {"reduction": "guyan"}}, "solver.reduction", "mta, modal, none"),
    ({"solver": {"aero_distribution": "skin"}}, "solver.aero_distribution", "model.type is shell"),
    ({"solver": {"basis_modes": 10, "n_tracked": 12}}, "solver.n_tracked", "basis_modes = 10"),
    ({"damping": {"model": "modal", "ratio": 0.01}, "solver": {"reduction": "none"}}, "damping.model",
     "reduction none"),
    ({"solver": {"backend": "nonsense"}}, "solver.backend", "entry-point group 'windflutter.backends'"),
    ({"solver": {"backend": "os:system"}}, "solver.backend", "import paths are not accepted"),
    ({"air_density": "heavy"}, "air_density", "finite number in (0, 2] (kg/m^3)"),
    ({"output": {"formats": ["gif"]}}, "output.formats[0]", "png"),
    ({"rotor_speed": 5}, "rotor_speed", "mapping"),
    ({"rotor_speed": {"full_sweep": "yes"}}, "rotor_speed.full_sweep", "true or false"),
    ({"solver": {"correction_tol": 0}}, "solver.correction_tol", "[1e-16, 1)"),
    ({"solver": {"mean_loads": 1}}, "solver.mean_loads", "true or false"),
    ({"solver": {"steady_loads": True}}, "solver.steady_loads", "renamed: solver.mean_loads"),
    ({"solver": {"correction_tol": 2.0}}, "solver.correction_tol", "[1e-16, 1)"),
]


@pytest.mark.parametrize("data, field, words", BAD)
def test_bad_config_names_the_field(data, field, words):
    with pytest.raises(InputError) as ei:
        config_from_dict(data, "a.yaml")
    msg = str(ei.value)
    assert ei.value.field == field
    assert msg.startswith(f"a.yaml: {field} = ")
    assert words in msg
    assert "\n" not in msg


@pytest.mark.parametrize("text, field", [
    ("wind_speeds: [4, -2]\n", "wind_speeds[1]"),
    ("rotor_speed: {min_rpm: 30, max_rpm: 5}\n", "rotor_speed.max_rpm"),
    ("method: [newton]\n", "method[0]"),
    ("colour: red\n", "colour"),
    ("wind_speeds: [4, 6\n", "config"),
])
def test_cli_bad_config_one_line_exit_2(tmp_path, capsys, text, field):
    p = tmp_path / "bad.yaml"
    p.write_text(text)
    rc = main(["run", "nrel5mw", "-c", str(p), "-o", str(tmp_path / "out"), "-q"])
    err = capsys.readouterr().err
    assert rc == 2
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert field in lines[0] and "Traceback" not in err
    assert not (tmp_path / "out").exists()  # nothing is written for a bad config


def test_cli_missing_config_file(tmp_path, capsys):
    rc = main(["run", "nrel5mw", "-c", str(tmp_path / "none.yaml"), "-q"])
    assert rc == 2
    assert "config" in capsys.readouterr().err


def test_print_default_config(capsys):
    assert main(["run", "x", "--print-default-config"]) == 0
    assert config_from_dict(yaml.safe_load(capsys.readouterr().out)) == AnalysisConfig()


def _dotted(d, prefix=""):
    for k, v in d.items():
        if isinstance(v, dict) and k != "wind_speeds":
            yield from _dotted(v, f"{prefix}{k}.")
        else:
            yield f"{prefix}{k}"


def test_every_declared_field_is_in_the_default_file_and_the_reference():
    # one declaration per field (config.py); the commented default file and the reference table
    # must list exactly the declared fields, so a new option cannot be half-added
    import re
    from pathlib import Path

    from windflutter.config import declared_fields, default_config_text

    declared = [name for name, _, _ in declared_fields()]
    assert sorted(_dotted(yaml.safe_load(default_config_text()))) == sorted(declared)
    ref = Path(__file__).resolve().parents[2] / "docs" / "config_reference.md"
    text = ref.read_text(encoding="utf-8")
    fields_section = text[text.index("## Fields"):text.index("### Rules between fields")]
    table = re.findall(r"^\| `([a-z_.]+)` \| ", fields_section, flags=re.M)
    assert table == declared
    for name, f, spec in declared_fields():
        assert spec.doc, name        # every field documented
        spec.check(f.default, name)  # and its default inside its own bounds
