"""`windflutter section` and `windflutter simple` command-line contract."""

import json
import subprocess
import sys

import pytest

from windflutter.cli import main

HP_YAML = """\
semi_chord: 1.0
elastic_axis: -0.2
mass_ratio: 20
x_alpha: 0.1
r_alpha_squared: 0.24
omega_h: 0.4
omega_alpha: 1.0
"""

DIM_YAML = """\
semi_chord: 0.5
elastic_axis: -0.3
air_density: 1.225
mass: 12.0
static_moment: 0.6
inertia: 0.25
plunge_stiffness: 3000.0
pitch_stiffness: 4000.0
"""


def write(tmp_path, text, name="sec.yaml"):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


@pytest.mark.parametrize("method", ["k", "pk", "p"])
def test_json_output(tmp_path, capsys, method):
    cfg = write(tmp_path, HP_YAML)
    assert main(["section", cfg, "--method", method, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("flutter_speed", "flutter_frequency", "reduced_frequency", "divergence_speed"):
        assert key in out
    # HP section (b = w_a = 1): U_F = 2.18391 (p: RFA, within 0.2 %), U_D = sqrt(8)
    tol = 2e-3 if method == "p" else 1e-5
    assert out["flutter_speed"] == pytest.approx(2.18391, rel=tol)
    assert out["divergence_speed"] == pytest.approx(8**0.5, rel=1e-12)
    assert out["reduced_frequency"] == pytest.approx(
        out["flutter_frequency"] * 1.0 / out["flutter_speed"], rel=1e-9)


def test_dimensional_config_text_and_plot(tmp_path, capsys):
    cfg = write(tmp_path, DIM_YAML)
    png = tmp_path / "out" / "vg.png"
    assert main(["section", cfg, "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "flutter speed" in out and "divergence speed" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_null_divergence(tmp_path, capsys):
    cfg = write(tmp_path, HP_YAML.replace("elastic_axis: -0.2", "elastic_axis: -0.6"))
    assert main(["section", cfg, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["divergence_speed"] is None


@pytest.mark.parametrize(
    "text,field",
    [
        (HP_YAML + "colour: red\n", "colour"),
        (DIM_YAML.replace("mass: 12.0\n", ""), "mass"),
        (DIM_YAML.replace("mass: 12.0", "mass: -12.0"), "mass"),
        (DIM_YAML.replace("mass: 12.0", "mass: 0"), "mass"),
        (HP_YAML.replace("r_alpha_squared: 0.24", "r_alpha_squared: 0.005"), "r_alpha_squared"),
        (DIM_YAML.replace("inertia: 0.25", "inertia: 0.02"), "inertia"),
        (HP_YAML.replace("x_alpha: 0.1", "x_alpha: .nan"), "x_alpha"),
        (HP_YAML + "mass: 3.0\n", "mass_ratio"),
        ("semi_chord: [1\n", "CONFIG"),
        ("- 1\n- 2\n", "<config>"),
    ],
)
def test_bad_config_one_line_error(tmp_path, capsys, text, field):
    cfg = write(tmp_path, text)
    code = main(["section", cfg, "--json"])
    captured = capsys.readouterr()
    assert code == 2
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and field in lines[0] and "Traceback" not in captured.err


def test_missing_file(tmp_path, capsys):
    assert main(["section", str(tmp_path / "nope.yaml")]) == 2
    err = capsys.readouterr().err
    assert "nope.yaml" in err and len(err.strip().splitlines()) == 1


def test_bad_plot_name(tmp_path, capsys):
    cfg = write(tmp_path, HP_YAML)
    assert main(["section", cfg, "--plot", str(tmp_path / "x.jpg")]) == 2
    assert "--plot" in capsys.readouterr().err


def test_console_entry_point_subprocess(tmp_path):
    # one real process (bad input through a real process: tests/cli/test_subprocess.py and the
    # in-process tests above)
    cfg = write(tmp_path, HP_YAML, "good.yaml")
    proc = subprocess.run([sys.executable, "-m", "windflutter", "section", cfg, "--json"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0
    assert json.loads(proc.stdout)["flutter_speed"] == pytest.approx(2.18391, rel=1e-5)


def test_simple_command_json(capsys):
    assert main(["simple", "--turbine", "seed20mw", "--frozen-k", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    t = out["turbines"][0]
    assert t["turbine"] == "seed20mw" and t["method"] == "frozen-k"
    assert t["wind_speed"][0] == 4.0 and t["wind_speed"][-1] == 25.0
    assert all(r is not None and r > 0 for r in t["first_unstable_rpm"])
    assert t["thesis_reported_rpm"] == [24.5, 28.5]


def test_simple_command_plot(tmp_path, capsys, monkeypatch):
    # the plot path of the command, on three wind speeds instead of 22 (the simple model's
    # numbers are checked in test_simple_model.py and by test_simple_command_json)
    import numpy as np

    from windflutter.frozen import simple_model

    full = simple_model.run_simple_model
    monkeypatch.setattr(simple_model, "run_simple_model",
                        lambda rs, **kw: full(rs, np.array([5.0, 15.0, 25.0]), **kw))
    png = tmp_path / "simple.png"
    assert main(["simple", "--turbine", "nrel5mw", "--plot", str(png)]) == 0
    assert "NREL 5 MW" in capsys.readouterr().out
    assert png.stat().st_size > 1000


def test_unwritable_plot_location(tmp_path, capsys):
    cfg = write(tmp_path, HP_YAML)
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    assert main(["section", cfg, "--plot", str(blocker / "sub" / "vg.png")]) == 2
    err = capsys.readouterr().err
    assert "--plot" in err and len(err.strip().splitlines()) == 1
