"""The top-level Python API (windflutter.load_turbine / modes / campbell / stability / run /
analysis_config): the same results as the CLI, the same validation, one default model, and the
default output folder of a run.

The API and the CLI share their solvers, so "the same results" is checked exactly (equality of
the JSON objects, no tolerance) on small cases; what can differ between them is the way options
become a config, which the stability test checks by recording the config each one hands to the
solver.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from api_support import cached_loading

import windflutter
from windflutter.cli import main
from windflutter.errors import InputError

SRC = Path(windflutter.__file__).resolve().parent


@pytest.fixture
def cached(monkeypatch):
    cached_loading(monkeypatch)


def cli_json(capsys, argv: list[str]) -> dict:
    rc = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert rc == 0, err
    return json.loads(out)


def test_import_is_light_and_lazy():
    # `import windflutter` must stay fast: no NumPy, no API module until an API name is used;
    # windflutter.stability is the API function only (no package of that name since issue 29)
    code = ("import sys, json, windflutter; a = ['numpy' in sys.modules, 'windflutter.api' in sys.modules]; "
            "f = windflutter.modes; import windflutter.methods; "
            "print(json.dumps(a + ['windflutter.api' in sys.modules, callable(windflutter.stability), "
            "windflutter.stability.__module__, sorted(set(windflutter.__all__) - set(dir(windflutter)))]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert json.loads(out) == [False, False, True, True, 'windflutter.api', []]


def test_modes_api_equals_cli_and_defaults_to_beam(cached, capsys):
    cli = cli_json(capsys, ["modes", "nrel5mw", "--part", "blade", "--n", "4", "--json"])
    api = windflutter.modes("nrel5mw", part="blade", n=4)
    assert [float(f) for f in api.frequencies_hz] == cli["frequencies_hz"] and api.labels == cli["labels"]
    beam = windflutter.modes("nrel5mw", part="blade", n=4, model="beam")
    assert list(beam.frequencies_hz) == list(api.frequencies_hz)  # the default is the beam model
    # Jonkman et al. 2009 (NREL/TP-500-38060) / BModes: 1st flap 0.65-0.70 Hz, 1st edge ~1.08 Hz;
    # the shell model of the same file gives 0.91-0.94 Hz (its layup is another blade): the
    # default must be the beam model, as for run / stability / campbell
    assert api.labels[:2] == ["1st flap", "1st edge"] and 0.64 < api.frequencies_hz[0] < 0.70
    # the tutorial's `modes nrel5mw --part blade --rpm 12.1`: centrifugal stiffening raises the
    # flap frequency by 7.7 % (pyBmodes on the same blade data: 0.676 -> 0.729 Hz, docs/mesh.md),
    # to about 0.72 Hz here -- not the shell model's 0.94 Hz
    rot = cli_json(capsys, ["modes", "nrel5mw", "--part", "blade", "--n", "2", "--rpm", "12.1", "--json"])
    assert api.frequencies_hz[0] < rot["frequencies_hz"][0] < 0.76


def test_mesh_defaults_to_beam_and_shell_options_need_the_shell_model(cached, tmp_path, capsys):
    assert main(["mesh", "nrel5mw", "--part", "blade", "--vtk", str(tmp_path / "b.vtu")]) == 0
    out = capsys.readouterr().out
    assert "beam model" in out and " 0 quads" in out
    # a shell-only option with the (default) beam model is refused, naming the flag, before any work
    for argv in (["mesh", "nrel5mw", "--vtk", str(tmp_path / "s.vtu"), "--n-chord", "16"],
                 ["modes", "nrel5mw", "--tower-model", "beam"]):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "--model shell" in err and argv[-2] in err
    with pytest.raises(InputError) as exc:
        windflutter.modes("nrel5mw", n_chord=16)
    assert exc.value.field == "n_chord" and "model shell" in str(exc.value)
    assert not (tmp_path / "s.vtu").exists()


def test_campbell_api_equals_cli(cached, capsys):
    cli = cli_json(capsys, ["campbell", "nrel5mw", "--wind-speeds", "11.4", "--n-span", "6", "--json"])
    api = windflutter.campbell("nrel5mw", [11.4], model={"n_aero_sections": 6})
    assert api.as_dict() == cli
    assert len(cli["points"][0]["modes"]) > 10


class _Recorder:
    """A stand-in solver recording the config each caller builds (no analysis is run)."""

    configs: list = []

    def __init__(self, turbine, config, aero, method):
        self.configs.append((config, aero, method))

    def analyse_operating_point(self, v):
        class Point:
            def as_dict(self):
                return {"wind_speed": v}

        return Point()


def test_stability_api_builds_the_cli_solver(cached, monkeypatch, capsys):
    import windflutter.methods as methods

    monkeypatch.setattr(methods, "stability_analysis", _Recorder)
    _Recorder.configs = []
    cli = cli_json(capsys, ["stability", "nrel5mw", "--wind-speeds", "8", "12", "--model", "shell", "--n-span", "12",
                            "--rpm", "4", "30", "2", "--aero", "potential", "--basis-modes", "20", "--json"])
    api = windflutter.stability("nrel5mw", [8, 12], model={"type": "shell", "n_aero_sections": 12},
                                rotor_speed={"min_rpm": 4, "max_rpm": 30, "n_points": 14}, aero="potential",
                                **{"solver.basis_modes": 20})
    (c_cli, *case_cli), (c_api, *case_api) = _Recorder.configs
    assert c_api == c_cli and case_api == case_cli == ["potential", "p"]
    assert [p.as_dict() for p in api] == cli["points"]
    # defaults: those of `windflutter stability` (method p, viscous, 2-40 RPM in steps of 2)
    windflutter.stability("nrel5mw", 10)
    c_def = _Recorder.configs[-1][0]
    assert (c_def.method, c_def.aero, c_def.sweep_rpm()[:2]) == (("p",), ("viscous",), [2.0, 4.0])


@pytest.mark.slow
def test_stability_api_equals_cli_real_solve(cached, capsys):
    # the real solve of a reduced case: identical numbers (same code, same config)
    flags = ["--wind-speeds", "11.4", "--n-span", "6", "--rpm", "16", "28", "4", "--part", "rotor"]
    cli = cli_json(capsys, ["stability", "nrel5mw", *flags, "--json"])
    api = windflutter.stability("nrel5mw", [11.4], model={"n_aero_sections": 6, "part": "rotor"},
                                rotor_speed={"min_rpm": 16, "max_rpm": 28, "n_points": 4})
    assert [p.as_dict() for p in api] == cli["points"] and cli["points"][0]["flutter_rpm"] is not None


def _no_work(monkeypatch):
    """Every entry into real work fails the test: the API must refuse bad input before."""
    import windflutter.mesh.analysis
    import windflutter.methods
    import windflutter.system.operational
    import windflutter.workflow

    def stop(*a, **k):
        raise AssertionError("work started before the input was checked")

    for mod, attr in ((windflutter.mesh.analysis, "turbine_modes"), (windflutter.methods, "stability_analysis"),
                      (windflutter.system.operational, "OperationalModel"), (windflutter.workflow, "run")):
        monkeypatch.setattr(mod, attr, stop)


@pytest.mark.parametrize("call, field", [
    (lambda t: windflutter.load_turbine(3), "turbine"),
    (lambda t: windflutter.load_turbine("no_such_turbine_xyz"), "turbine"),
    (lambda t: windflutter.modes(object()), "turbine"),
    (lambda t: windflutter.modes(t, rpm=-1), "rpm"),
    (lambda t: windflutter.modes(t, n=0), "n"),
    (lambda t: windflutter.modes(t, part="hub"), "part"),
    (lambda t: windflutter.modes(t, model="solid"), "model"),
    (lambda t: windflutter.modes(t, pitch=float("nan")), "pitch"),
    (lambda t: windflutter.modes(t, n_span=2), "n_span"),
    (lambda t: windflutter.stability(t, [0]), "wind_speeds[0]"),
    (lambda t: windflutter.stability(t, [12, 8]), "wind_speeds[1]"),
    (lambda t: windflutter.stability(t, [10], aero=["viscous", "potential"]), "aero"),
    (lambda t: windflutter.stability(t, [10], model="section"), "model.type"),
    (lambda t: windflutter.stability(t, [10], solver={"basis_modes": 0}), "solver.basis_modes"),
    (lambda t: windflutter.stability(t, [10], damping={"model": "rayleigh"}), "damping.model"),
    (lambda t: windflutter.campbell(t, [10], colour="red"), "colour"),
    (lambda t: windflutter.campbell(t, max_hz=-1.0), "campbell.max_hz"),
    (lambda t: windflutter.campbell(t, **{"solver.reductionx": 1}), "solver.reductionx"),
    (lambda t: windflutter.run(t, config=42), "config"),
    (lambda t: windflutter.run(t, config="no_such_config.yaml"), "config"),
    (lambda t: windflutter.run(t, rotor_speed={"max_rpm": float("inf")}), "rotor_speed.max_rpm"),
    (lambda t: windflutter.analysis_config(wind_speeds={"start": 4}), "wind_speeds.stop"),
])
def test_bad_input_is_refused_before_any_work(cached, monkeypatch, call, field):
    turbine = windflutter.load_turbine("nrel5mw")
    _no_work(monkeypatch)
    with pytest.raises(InputError) as exc:
        call(turbine)
    assert exc.value.field == field, str(exc.value)


def test_run_folder_name():
    from windflutter.api import run_folder_name

    seed = SRC / "data" / "seed" / "seed20mw.yaml"
    assert run_folder_name("nrel5mw") == run_folder_name("NREL-5MW") == "nrel5mw"  # bundled names
    assert run_folder_name("iea15mw_openfast") == "iea15mw_openfast"
    assert run_folder_name(windflutter.load_turbine("seed20mw", validate=False)) == "seed20mw"
    assert run_folder_name(str(seed)) == "seed20mw"  # the file's stem, not its `name` field
    assert run_folder_name("models/My Turbine (v2).fst") == "My_Turbine_v2"
    assert run_folder_name("") == "turbine"


def _instant(turbine, config):
    """An instant plug-in analyser (no physics): for the run-folder tests."""
    import numpy as np

    from windflutter.workflow import PointResult

    def analyse(point, progress=None):
        rpm = np.asarray(point.sweep_rpm, float)
        return PointResult(flutter_rpm=20.0, flutter_frequency_hz=1.0, flutter_mode="1st flap",
                           divergence_rpm=float("nan"), sweep_rpm=rpm, damped_frequency_hz=np.ones((rpm.size, 1)),
                           damping_ratio=np.full((rpm.size, 1), 0.01), mode_labels=["1st flap"])

    return analyse


def test_run_names_its_folder_after_the_file(tmp_path, monkeypatch, capsys):
    from windflutter.backends import register_backend, unregister_backend

    register_backend("api_instant", _instant)
    monkeypatch.chdir(tmp_path)
    try:
        # the seed's 20 MW file: its windIO `name` is "Seed 20MW (Castillo Capponi 2010, ch. ...)"
        shutil.copy(SRC / "data" / "seed" / "seed20mw.yaml", tmp_path / "my_20mw.yaml")
        cfg = tmp_path / "a.yaml"
        cfg.write_text("wind_speeds: [10]\nsolver: {backend: api_instant}\ncampbell: {enabled: false}\n"
                       "output: {plots: false, report: false, animations: false}\n")
        assert main(["run", "my_20mw.yaml", "-c", str(cfg), "-q", "--workers", "1"]) == 0
        assert "results: out/my_20mw/results.nc" in capsys.readouterr().out
        ds = windflutter.run("my_20mw.yaml", str(cfg), progress=False, wind_speeds=[12])  # the API's default
        assert float(ds["wind_speed"][0]) == 12.0
        assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["my_20mw"]
    finally:
        unregister_backend("api_instant")


@pytest.mark.parametrize("call", [lambda w: w.modes("nrel5mw", colour=1), lambda w: w.simulate("nrel5mw", 10.0, colour=1),
                                  lambda w: w.confirm_onset("nrel5mw", 8.0, colour=1)])
def test_an_unknown_keyword_is_an_input_error_naming_it(call):
    """Issue 34: every API keyword -- an unknown one too -- gives InputError naming it, not TypeError."""
    import windflutter.api
    from windflutter.errors import InputError

    with pytest.raises(InputError, match="colour"):
        call(windflutter.api)


def test_the_methods_registry_builds_each_methods_solver():
    """Issue 29: one registry of search methods (p, pk, thesis) in the composition root, instead of
    ``if method == "p"`` branches in the API, the command line and the run."""
    from windflutter.api import analysis_config
    from windflutter.errors import InputError
    from windflutter.methods import METHODS, case_options, method
    from windflutter.system.operational import OperationalOptions
    from windflutter.frozen.turbine import TurbineOptions

    assert set(METHODS) == {"p", "pk", "thesis"}
    cfg = analysis_config()
    assert isinstance(case_options(cfg, "viscous", "p"), OperationalOptions)
    assert isinstance(case_options(cfg, "viscous", "pk"), TurbineOptions)
    assert case_options(cfg, "viscous", "thesis").method == "thesis"
    assert not method("p").config_grid and method("pk").config_grid
    with pytest.raises(InputError, match="method"):
        method("k")
