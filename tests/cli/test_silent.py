"""The cases that used to give a silent wrong or misleading result now give a clear error, or
the right result: wrong-turbine resume, run attributes after a resume, file modes, ordinals,
plug-in back-ends, the stability command's options."""

from __future__ import annotations

import dataclasses
import os

import numpy as np
import pytest

from windflutter.errors import InputError


# -- ordinals ("21th") -------------------------------------------------------------------------
def test_ordinals():
    from windflutter.structure.labels import ordinal

    expected = {1: "1st", 2: "2nd", 3: "3rd", 4: "4th", 10: "10th", 11: "11th", 12: "12th", 13: "13th",
                20: "20th", 21: "21st", 22: "22nd", 23: "23rd", 24: "24th", 101: "101st", 111: "111th",
                112: "112th", 113: "113th", 121: "121st", 1002: "1002nd"}
    assert {n: ordinal(n) for n in expected} == expected


# -- the turbine's content in the fingerprint ----------------------------------------------------
@dataclasses.dataclass
class _Part:
    name: str
    stiffness: np.ndarray
    source: str = ""


@dataclasses.dataclass
class _Machine:
    blade: _Part
    tower: _Part
    masses: dict
    notes: tuple = ()
    source: str = ""


def _machine():
    return _Machine(_Part("blade", np.array([[1e9, 2e8], [2e8, 3e9]])), _Part("tower", np.linspace(1, 2, 5)),
                    {"hub": 56780.0, "nacelle": 240000.0}, ("from ElastoDyn",), "/data/NREL-5MW.yaml")


def test_turbine_digest_follows_content_not_location():
    from windflutter.post.runfolder import turbine_digest

    a = turbine_digest(_machine())
    assert a == turbine_digest(_machine())                                # deterministic
    moved = _machine()
    moved.source, moved.blade.source, moved.notes = "/elsewhere/x.yaml", "other", ("copied",)
    assert turbine_digest(moved) == a                                     # where it came from: no
    for edit in (lambda m: m.blade.stiffness.__setitem__((1, 1), 3.000001e9),
                 lambda m: m.masses.__setitem__("hub", 56781.0),
                 lambda m: setattr(m.tower, "stiffness", m.tower.stiffness.astype(np.float32)),
                 lambda m: setattr(m.blade, "name", "blade2")):
        m = _machine()
        edit(m)
        assert turbine_digest(m) != a                                     # what it is: yes


def test_turbine_digest_hashes_a_plug_in_file_by_its_bytes(tmp_path):
    from windflutter.post.runfolder import turbine_digest

    p = tmp_path / "t.txt"
    p.write_text("a")
    a = turbine_digest(str(p))
    p.write_text("b")
    assert turbine_digest(str(p)) != a and turbine_digest("nrel5mw") != turbine_digest("iea15mw")


def test_run_record_holds_config_turbine_and_version():
    from windflutter import __version__
    from windflutter.config import AnalysisConfig, config_from_dict
    from windflutter.post.runfolder import run_record

    r = run_record(AnalysisConfig(), _machine(), "m")
    assert r["windflutter_version"] == __version__ and r["config_fingerprint"] == AnalysisConfig().fingerprint()
    other = _machine()
    other.masses["nacelle"] = 1.0
    assert run_record(AnalysisConfig(), other, "m")["fingerprint"] != r["fingerprint"]
    assert run_record(config_from_dict({"air_density": 1.2}), _machine(), "m")["fingerprint"] != r["fingerprint"]


# -- run attributes do not depend on which points this process computed ------------------------
def test_model_size_attributes_from_the_stored_points():
    from windflutter.config import AnalysisConfig
    from windflutter.post import store
    from windflutter.workflow import OperatingPoint, PointResult, assemble_dataset

    pts = {}
    for i, n in enumerate((149, 151, 150)):
        p = OperatingPoint(i, 4.0 + i, "potential", "pk", 2.0, 30.0, 0.01, (2.0, 30.0))
        pts[i] = store.point_dataset(p, PointResult(info={"n_reduced_dof": n, "n_dof": 1200}))
    info_old_process = {"turbine": "t", "n_reduced_dof": 149, "n_dof": 1200}   # what describe() said
    for order in ((0, 1, 2), (2, 1, 0), (1, 2, 0)):
        ds = assemble_dataset({i: pts[i] for i in order}, AnalysisConfig(), info_old_process, 3)
        assert ds.attrs["n_reduced_dof"] == 151 and ds.attrs["n_dof"] == 1200
    # a resumed process that computed nothing still writes the sizes
    assert assemble_dataset(pts, AnalysisConfig(), {"turbine": "t"}, 3).attrs["n_reduced_dof"] == 151


# -- result files respect the umask --------------------------------------------------------------
@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
def test_result_files_respect_the_umask(tmp_path, umask):
    import xarray as xr

    from windflutter.post import store

    old = os.umask(umask)
    try:
        nc = store.atomic_write_netcdf(xr.Dataset({"x": ("a", [1.0])}), tmp_path / "r.nc")
        txt = store.atomic_write_text("fingerprint: x\n", tmp_path / "analysis.yaml")
        fig = tmp_path / "figure.png"
        fig.write_bytes(b"png")
    finally:
        os.umask(old)
    want = 0o666 & ~umask
    assert {p.name: p.stat().st_mode & 0o777 for p in (nc, txt, fig)} == {"r.nc": want, "analysis.yaml": want,
                                                                          "figure.png": want}


# -- back-ends: a registry and an entry-point group, never an import path ------------------------
def test_backend_names_come_from_the_registry_and_entry_points(monkeypatch):
    from windflutter import backends
    from windflutter.config import config_from_dict

    assert "toy" in backends.backend_names()        # tests/workflow/*.dist-info publishes it
    for bad in ("os:system", "subprocess:run", "os.path:join", "builtins:eval", "no_such_backend"):
        with pytest.raises(InputError, match="import paths are not accepted"):
            config_from_dict({"solver": {"backend": bad}})
    called = []
    backends.register_backend("probe", lambda turbine, config: called.append(turbine) or (lambda p: None))
    try:
        from windflutter.workflow import make_analyser

        make_analyser("T", config_from_dict({"solver": {"backend": "probe"}}))
        assert called == ["T"]
    finally:
        backends.unregister_backend("probe")
    with pytest.raises(InputError):
        config_from_dict({"solver": {"backend": "probe"}})
    with pytest.raises(InputError, match="backend name"):
        backends.register_backend("a:b", lambda t, c: None)


def test_a_broken_entry_point_is_an_input_error(monkeypatch):
    from importlib import metadata

    from windflutter import backends

    broken = metadata.EntryPoint("broken", "no_such_module_xyz:factory", backends.ENTRY_POINT_GROUP)
    monkeypatch.setattr(backends, "_entry_points", lambda: {"broken": broken})
    with pytest.raises(InputError, match="loadable plug-in"):
        backends.backend_factory("broken")


# -- `windflutter stability` builds its options through the config --------------------------------
def test_stability_options_are_the_run_options():
    from windflutter.cli import build_parser
    from windflutter.cli.stability import options_from_args
    from windflutter.config import config_from_dict
    from windflutter.mesh.settings import MeshSettings
    from windflutter.frozen.turbine import TurbineOptions
    from windflutter.workflow import turbine_options

    args = build_parser().parse_args(["stability", "nrel5mw", "--basis-modes", "24", "--physics", "thesis",
                                      "--n-span", "12", "--part", "rotor", "--rpm", "4", "30", "2",
                                      "--aero", "potential", "--method", "pk"])
    cfg, opts = options_from_args(args)
    same = config_from_dict({"wind_speeds": [10], "aero": "potential", "method": "pk",
                             "rotor_speed": {"min_rpm": 4, "max_rpm": 30, "n_points": 14},
                             "model": {"n_aero_sections": 12, "part": "rotor"},
                             "solver": {"basis_modes": 24, "geometric_stiffness": False, "rigid_sections": False}})
    assert cfg == same and opts == turbine_options(same, "potential", "pk")
    assert (opts.basis_modes, opts.geometric_stiffness, opts.mesh["n_span"], opts.mesh["part"]) == (24, False, 12,
                                                                                                    "rotor")
    # the defaults are the run's: method p on the whole turbine (OperationalOptions of the config)
    from windflutter.methods import operational_options

    cfg_d, d = options_from_args(build_parser().parse_args(["stability", "nrel5mw"]))
    assert cfg_d == config_from_dict({"wind_speeds": [10], "rotor_speed": {"min_rpm": 2, "max_rpm": 40, "n_points": 20}})
    assert d == operational_options(cfg_d, "viscous")
    assert (d.part, d.drivetrain, d.deflection, d.induction, d.damping) == ("turbine", "flexible", True, True, "file")
    assert d.structure == "deflected"  # auto: beam blades are linearized about their deflected shape
    assert MeshSettings(**{"model": "beam", **d.mesh}) == MeshSettings(model="beam", part="turbine", n_span=30)


@pytest.mark.parametrize("solver, model, want", [
    ({}, "shell", "deflected"), ({"deflection": False}, "beam", "undeformed"),
    ({"deflection": False}, "shell", "undeformed"),
    ({"structure": "undeformed"}, "beam", "undeformed"), ({"structure": "deflected"}, "beam", "deflected"),
    ({"structure": "deflected"}, "shell", "deflected"), ({"structure": "deflected", "deflection": False}, "beam", None),
    ({"structure": "deflected", "deflection": False}, "shell", None)])
def test_structure_auto_and_its_limits(solver, model, want):
    # solver.structure: auto resolves by the model; an explicit deflected blade it cannot build is
    # refused naming the config field (no silent fall-back), when the config is read
    from windflutter.config import config_from_dict
    from windflutter.errors import InputError
    from windflutter.methods import operational_options

    if want is None:  # refused by the config's rules, before any solver is built
        with pytest.raises(InputError, match="solver.structure"):
            config_from_dict({"model": {"type": model}, "solver": solver})
    else:
        cfg = config_from_dict({"model": {"type": model}, "solver": solver})
        assert operational_options(cfg, "viscous").structure == want


@pytest.mark.parametrize("lo, hi, step", [(2, 40, 2), (2, 40, 3), (0, 25, 0.5), (4, 30, 7), (2, 2.5, 2)])
def test_rpm_step_gives_the_grid_of_before(lo, hi, step):
    # `--rpm MIN MAX STEP` becomes rotor_speed.n_points; the sweep is the grid the stability
    # command used before (TurbineOptions.grid: the step shortened to divide the range evenly)
    from windflutter.config import config_from_dict, n_points_for_step
    from windflutter.frozen.turbine import TurbineOptions

    cfg = config_from_dict({"rotor_speed": {"min_rpm": lo, "max_rpm": hi, "n_points": n_points_for_step(lo, hi, step),
                                            "tolerance_rpm": 0.01}})
    np.testing.assert_allclose(cfg.sweep_rpm(), TurbineOptions(min_rpm=lo, max_rpm=hi, rpm_step=step).grid(),
                               rtol=1e-14, atol=1e-12)


# -- the Python API checks like the command line ---------------------------------------------------
def test_api_configs_are_checked_before_the_run(tmp_path):
    from windflutter.config import AnalysisConfig, RotorSpeedConfig, SolverConfig, check_config
    from windflutter.workflow import run

    assert check_config(AnalysisConfig()) == AnalysisConfig()
    for bad, field in ((AnalysisConfig(rotor_speed=RotorSpeedConfig(n_points=10 ** 6)), "rotor_speed.n_points"),
                       (AnalysisConfig(air_density=float("nan")), "air_density"),
                       (AnalysisConfig(solver=SolverConfig(backend="os:system")), "solver.backend"),
                       (AnalysisConfig(rotor_speed=RotorSpeedConfig(min_rpm=30, max_rpm=5)), "rotor_speed.max_rpm")):
        with pytest.raises(InputError) as ei:
            run("toy", bad, tmp_path / "out", progress=False)
        assert ei.value.field == field
    assert not (tmp_path / "out").exists()


def test_overspeed_below_the_turbines_rated_speed_is_refused():
    from types import SimpleNamespace

    from windflutter.config import config_from_dict
    from windflutter.workflow import check_operating

    turbine = SimpleNamespace(rated_rotor_speed=12.1 * np.pi / 30)
    check_operating(turbine, config_from_dict({"operating": {"overspeed_rpm": 14.5}}))
    with pytest.raises(InputError, match="rated rotor speed 12.1 RPM"):
        check_operating(turbine, config_from_dict({"operating": {"overspeed_rpm": 10.0}}))
    check_operating(turbine, config_from_dict({"operating": {"overspeed_rpm": 10.0, "rated_rpm": 9.0}}))


def test_open_results_names_the_problem(tmp_path):
    from windflutter.post import store

    (tmp_path / "garbage.nc").write_bytes(b"not netcdf")
    (tmp_path / "run" / "results.nc").mkdir(parents=True)
    for path, words in ((tmp_path / "none.nc", "missing"), (tmp_path / "garbage.nc", "readable"),
                        (tmp_path / "run", "is a folder")):
        with pytest.raises(InputError, match=words):
            store.open_results(path)


def test_written_yaml_reads_back_equal():
    # a run record's fingerprint is hex: "0123e45678901234" is a float to a YAML-1.2 reader
    # unless the writer quotes it
    from windflutter.config import config_from_dict, load_config
    from windflutter.files import dump_yaml, parse_yaml

    data = {"fingerprint": "0123e45678901234", "title": "1e5", "x": ["2E6", 1e-8, "yes", "0x1F"]}
    assert parse_yaml(dump_yaml(data), "f", "f") == data
    cfg = config_from_dict({"title": "1e5"})
    assert config_from_dict(parse_yaml(cfg.to_yaml(), "f", "f")) == cfg
    assert load_config(None, {"title": "7e3"}).title == "7e3"


def test_a_warning_is_shown_once_per_command():
    """The command line's warnings (``cli.warn.one_line_warnings``): one line each, a text once --
    a run's workers and its Campbell build the model again and raised its layup warning three times
    (the NREL 5 MW shell run) -- distinct texts all shown."""
    import io
    import warnings

    from windflutter.cli.warn import one_line_warnings

    out = io.StringIO()
    with one_line_warnings("windflutter run", stream=out):
        warnings.simplefilter("always")
        for text in ("the blade layup is not\n  the blade of its 6x6", "another", "the blade layup is not\n  the blade of its 6x6"):
            warnings.warn(text, UserWarning, stacklevel=1)
    lines = out.getvalue().splitlines()
    assert lines == ["windflutter run: warning: the blade layup is not the blade of its 6x6",
                     "windflutter run: warning: another"]
