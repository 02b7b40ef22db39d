"""Hostile command lines of every command: exit code 2, one line on stderr naming the flag (and,
for a flag that sets a config field, the field), no traceback, nothing computed."""

from __future__ import annotations

import pytest
import yaml

from cli_cases import assert_one_line_error

NUMBERS = ["0", "-1", "nan", "inf", "-inf", "x", "1e400", "1" + "0" * 500]

# the flags run and stability share (each sets a config field); bad values and the field named
SHARED = [
    ("--wind-speeds", ["0"], "wind_speeds"), ("--wind-speeds", ["-3"], "wind_speeds"),
    ("--wind-speeds", ["nan"], "wind_speeds"), ("--wind-speeds", ["inf"], "wind_speeds"),
    ("--wind-speeds", ["1e5"], "wind_speeds"), ("--wind-speeds", ["x"], "wind_speeds"),
    ("--wind-speeds", ["8", "6"], "wind_speeds"),
    ("--rpm", ["2", "inf", "2"], "rotor_speed.max_rpm"), ("--rpm", ["2", "40", "1e-7"], "--rpm STEP"),
    ("--rpm", ["1e9", "2", "3"], "rotor_speed.min_rpm"), ("--rpm", ["2", "40", "0"], "--rpm STEP"),
    ("--rpm", ["30", "5", "1"], "rotor_speed.max_rpm"), ("--rpm", ["nan", "40", "2"], "rotor_speed.min_rpm"),
    ("--rpm", ["2", "40", "-2"], "--rpm STEP"), ("--rpm", ["a", "b", "c"], "rotor_speed.min_rpm"),
    ("--air-density", ["0"], "air_density"), ("--air-density", ["1e6"], "air_density"),
    ("--air-density", ["nan"], "air_density"),
    ("--n-span", ["2"], "model.n_aero_sections"), ("--n-span", ["1e6"], "model.n_aero_sections"),
    ("--n-span", ["12.5"], "model.n_aero_sections"),
    ("--part", ["blade"], "model.part"), ("--part", ["x"], "model.part"),
    ("--reduction", ["guyan"], "solver.reduction"),
    ("--basis-modes", ["0"], "solver.basis_modes"), ("--basis-modes", ["x"], "solver.basis_modes"),
    ("--basis-modes", ["1e9"], "solver.basis_modes"), ("--basis-modes", ["2.5"], "solver.basis_modes"),
    ("--n-tracked", ["0"], "solver.n_tracked"), ("--n-tracked", ["31"], "solver.n_tracked"),
    ("--aero-distribution", ["skin"], "solver.aero_distribution"),
    ("--aero-distribution", ["quads"], "solver.aero_distribution"),
    ("--physics", ["none"], "--physics"), ("--model", ["solid"], "model.type"),
]

CASES = []
for flag, vals, field in SHARED:
    CASES.append((["run", "nrel5mw", flag, *vals, "-q"], [flag, field]))
    CASES.append((["stability", "nrel5mw", flag, *vals], [flag, field]))
CASES += [
    (["run", "nrel5mw", "--aero", "inviscid"], ["--aero", "aero[0]"]),
    (["run", "nrel5mw", "--method", "pk", "newton"], ["--method", "method[1]"]),
    (["run", "nrel5mw", "--aero", "potential", "potential"], ["--aero"]),
    (["stability", "nrel5mw", "--aero", "inviscid"], ["--aero"]),
    (["stability", "nrel5mw", "--method", "newton"], ["--method"]),
    (["stability", "nrel5mw", "--basis-modes", "10", "--n-tracked", "12"], ["--n-tracked", "basis_modes = 10"]),
    (["stability", "nrel5mw", "--reduction", "none", "--n-tracked", "600"], ["--n-tracked"]),
    (["stability", "nrel5mw", "--plot", "campbell.gif"], ["--plot", ".png"]),
    (["stability", "nrel5mw", "--plot", "/sys/campbell.png"], ["--plot", "cannot be written"]),
    (["stability", "nrel5mw", "--plot", "/dev/null/x.png"], ["--plot", "is a file"]),
    (["stability", "nrel5mw", "--rpm", "2", "40"], ["--rpm"]),
    (["stability", "nrel5mw", "--colour", "red"], ["unrecognized arguments"]),
    (["stability"], ["turbine"]),
    (["run"], ["TURBINE"]),
    (["run", "nrel5mw", "--workers", "0"], ["--workers"]), (["run", "nrel5mw", "--workers", "two"], ["--workers"]),
    (["run", "nrel5mw", "--workers", "1.5"], ["--workers"]), (["run", "nrel5mw", "--workers", "-1"], ["--workers"]),
    (["run", "nrel5mw", "--scheduler", "tcp://nohost:abc"], ["--scheduler"]),
    (["run", "nrel5mw", "--scheduler", "udp://host:8786"], ["--scheduler"]),
    (["run", "nrel5mw", "--scheduler", ""], ["--scheduler"]),
    (["run", "nrel5mw", "--scheduler", "tcp://127.0.0.1:1"], ["--scheduler", "nothing answers"]),
    (["run", "nrel5mw", "--scheduler", "tcp://host:99999"], ["--scheduler"]),
    (["run", "nrel5mw", "-c"], ["-c"]),
    (["nonsense"], ["invalid choice"]),
    ([], ["COMMAND"]),
]

MODES = [
    ("--rpm", "-1"), ("--rpm", "1e9"), ("--rpm", "nan"), ("--rpm", "x"), ("--n", "0"), ("--n", "1e6"),
    ("--n", "x"), ("--n", "2.5"), ("--pitch", "1e9"), ("--pitch", "nan"), ("--azimuth", "inf"),
    ("--n-chord", "2"), ("--n-chord", "1e6"), ("--n-span", "3"), ("--n-span", "1000000"),
    ("--part", "hub"), ("--model", "solid"), ("--tower-model", "lattice"),
]
for flag, val in MODES:
    CASES.append((["modes", "nrel5mw", flag, val], [flag]))
    if flag not in ("--rpm", "--n"):
        CASES.append((["mesh", "nrel5mw", "--vtk", "m.vtu", flag, val], [flag]))
CASES += [
    (["mesh", "nrel5mw"], ["--vtk/--bdf"]),
    (["mesh", "nrel5mw", "--vtk", "m.txt"], ["--vtk", ".vtu"]), (["mesh", "nrel5mw", "--bdf", "m.stl"], ["--bdf"]),
    (["mesh", "nrel5mw", "--vtk", "/sys/m.vtu"], ["--vtk", "cannot be written"]),
    (["mesh", "nrel5mw", "--bdf", "/dev/null/m.bdf"], ["--bdf"]),
    (["mesh", "nrel5mw", "--vtk", "/tmp"], ["--vtk"]),
    (["simple", "--turbine", "x"], ["--turbine"]), (["simple", "--plot", "x.jpg"], ["--plot", ".png"]),
    (["simple", "--plot", "/sys/x.png"], ["--plot"]),
]


@pytest.mark.parametrize("argv, words", CASES, ids=[" ".join(c[0])[:60] for c in CASES])
def test_bad_command_line(tmp_path, monkeypatch, run_cli, no_heavy_work, argv, words):
    monkeypatch.chdir(tmp_path)  # relative output names land here
    rc, _, err = run_cli(argv)
    assert_one_line_error(rc, err, *words)
    assert list(tmp_path.iterdir()) == []  # nothing written


GOLAND = {"span": 6.096, "chord": 1.8288, "elastic_axis": 0.33, "mass_axis": 0.43,
          "bending_stiffness": 9.77e6, "torsion_stiffness": 0.987e6, "mass": 35.71, "inertia": 8.64,
          "air_density": 1.02}
SECTION = {"semi_chord": 1.0, "elastic_axis": -0.2, "mass_ratio": 20, "x_alpha": 0.1,
           "r_alpha_squared": 0.24, "omega_h": 0.4, "omega_alpha": 1.0}

# (command, base file, change, field named)
FILE_CASES = [
    ("wing", GOLAND, {"n_elements": 1000000}, "n_elements"), ("wing", GOLAND, {"n_modes": 10 ** 6}, "n_modes"),
    ("wing", GOLAND, {"basis_modes": 10 ** 6}, "basis_modes"), ("wing", GOLAND, {"basis_modes": 1}, "basis_modes"),
    ("wing", GOLAND, {"basis_modes": 8, "n_modes": 8}, "n_modes"),
    ("wing", GOLAND, {"speed_step": 1e-320}, "speed_step"), ("wing", GOLAND, {"speed_step": 1e-6}, "speed_step"),
    ("wing", GOLAND, {"span": 1e300}, "span"), ("wing", GOLAND, {"mass": 1e30}, "mass"),
    ("wing", GOLAND, {"air_density": 1e9}, "air_density"), ("wing", GOLAND, {"chord": "oops"}, "chord"),
    ("wing", GOLAND, {"mass_axis": 2.0}, "mass_axis"), ("wing", GOLAND, {"colour": "red"}, "colour"),
    ("wing", GOLAND, {"speed_max": float("inf")}, "speed_max"), ("wing", GOLAND, {"lift_slope": 1e6}, "lift_slope"),
    ("section", SECTION, {"mass_ratio": 1e300}, "mass_ratio"), ("section", SECTION, {"omega_h": 1e300}, "omega_h"),
    ("section", SECTION, {"semi_chord": -1.0}, "semi_chord"), ("section", SECTION, {"x_alpha": float("nan")}, "x_alpha"),
    ("section", SECTION, {"air_density": 1e9}, "air_density"), ("section", SECTION, {"colour": 1}, "colour"),
    ("section", SECTION, {"omega_alpha": "fast"}, "omega_alpha"),
]


@pytest.mark.parametrize("command, base, change, field", FILE_CASES,
                         ids=[f"{c[0]}-{next(iter(c[2]))}-{list(c[2].values())[0]!s:.10}" for c in FILE_CASES])
def test_bad_wing_or_section_file(tmp_path, run_cli, no_heavy_work, command, base, change, field):
    p = tmp_path / "in.yaml"
    p.write_text(yaml.safe_dump({**base, **change}))
    rc, _, err = run_cli([command, p])
    assert_one_line_error(rc, err, field)


@pytest.mark.parametrize("command", ["wing", "section"])
@pytest.mark.parametrize("content, words", [
    (b"span: 1\nspan: 2\n", "duplicate key"), (b"span: caf\xe9\n", "UTF-8"), (b"[1, 2\n", "valid YAML"),
    (b"- 1\n- 2\n", "mapping"), (None, "no such file"), ("dir", "not a folder"),
])
def test_bad_wing_or_section_path(tmp_path, run_cli, no_heavy_work, command, content, words):
    p = tmp_path / "in.yaml"
    if content == "dir":
        p = tmp_path
    elif content is not None:
        p.write_bytes(content)
    rc, _, err = run_cli([command, p])
    assert_one_line_error(rc, err, words)


def test_section_plot_checked_before_the_analysis(tmp_path, run_cli, no_heavy_work):
    p = tmp_path / "in.yaml"
    p.write_text(yaml.safe_dump(SECTION))
    for plot, words in (("vg.jpg", ".png"), ("/sys/vg.png", "cannot be written"), (str(p / "vg.png"), "is a file")):
        rc, _, err = run_cli(["section", p, "--plot", plot])
        assert_one_line_error(rc, err, "--plot", words)
