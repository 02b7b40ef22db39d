"""The files of examples/ run as documented: the wing config through ``windflutter wing``, the
turbine analysis config through ``windflutter run -c`` and the API, and the Python scripts.

The scripts are run in this process (their ``main(argv)``) at reduced sizes given by their own
arguments (coarser blades, a coarser rotor-speed grid, no figures); the full sizes are the *slow*
tests.  Each bundled turbine is read once (:mod:`api_support`).
"""

from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

import pytest
from api_support import cached_loading

from windflutter.cli import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
#: reduced sizes: the rotor on a fixed nacelle, 8 blade elements, rotor speeds in steps of 4 RPM, onsets
#: to 0.5 RPM (about 3 s a point instead of 10)
QUICK = ["model.part=rotor", "model.n_aero_sections=8", "rotor_speed.n_points=8", "rotor_speed.tolerance_rpm=0.5"]
SET_QUICK = [a for s in QUICK for a in ("--set", s)]


@pytest.fixture
def cached(monkeypatch):
    cached_loading(monkeypatch)


def script(name: str):
    """The example script ``examples/NAME.py`` as a module (its ``main(argv)`` is the script)."""
    spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_script(capsys, name: str, argv: list[str]) -> str:
    assert script(name).main([str(a) for a in argv]) == 0
    return capsys.readouterr().out


def test_every_example_is_tested():
    tested = {"wing_goland.yaml", "analysis_nrel5mw.yaml", "campbell_nrel5mw.py", "stability_point.py",
              "run_analysis.py", "README.md"}
    assert {p.name for p in EXAMPLES.iterdir() if not p.name.startswith((".", "__"))} == tested


def test_wing_example_is_the_goland_wing(capsys):
    # Goland (1945), continuous beam with Theodorsen strips: flutter 137.2 m/s at 70.7 rad/s,
    # divergence 252 m/s (Patil, Hodges & Cesnik 2001).  Tolerances as tests/solver/test_wing.py:
    # 1 % on speeds, 2 % on frequency (published to 3 digits; 16 elements are within 0.1 % of h -> 0)
    assert main(["wing", str(EXAMPLES / "wing_goland.yaml"), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["flutter_speed"] == pytest.approx(137.2, rel=0.01)
    assert r["flutter_frequency"] == pytest.approx(70.7, rel=0.02)
    assert r["divergence_speed"] == pytest.approx(252.0, rel=0.01)


def test_campbell_example(cached, capsys):
    out = run_script(capsys, "campbell_nrel5mw", ["--n-span", "6"])
    assert len(re.findall(r"^V = ", out, flags=re.M)) == 3  # its three wind speeds
    m = re.search(r"^least damped mode: (.+) at ([\d.]+) m/s, ([\d.]+) Hz, damping ratio ([-\d.]+) %$", out, re.M)
    assert m, out
    # in operation the edgewise modes are the least damped ones of a pitch-regulated turbine (their
    # aerodynamic damping is small: Hansen, Wind Energy 10 (2007) 551-577); positive, below 5 %
    assert "edge" in m.group(1) and 0.0 < float(m.group(4)) < 5.0


def test_analysis_config_and_stability_example_agree(cached, tmp_path, capsys):
    # the turbine analysis config through the scripted run (API), its results.nc read back with
    # xarray, and the stability example on the same config: the same onset (one solver, one config)
    out = run_script(capsys, "run_analysis", ["--wind-speeds", "11.4", "--quick", "--outdir", tmp_path / "run",
                                              *SET_QUICK])
    assert (tmp_path / "run" / "results.nc").is_file()
    line = re.search(r"V =  11\.4 m/s viscous/p: flutter ([\d.]+) rpm \((.+?), ([\d.]+) Hz\); "
                     r"divergence ([\d.]+|-) ?r?p?m?; ok", out)
    assert line, out
    point = json.loads(run_script(capsys, "stability_point", [
        "--config", EXAMPLES / "analysis_nrel5mw.yaml", "--wind-speed", "11.4", *SET_QUICK, "--json"]))["points"][0]
    assert point["flutter_rpm"] == pytest.approx(float(line.group(1)), abs=0.006)  # printed to 0.01
    assert point["flutter_mode"] == line.group(2)
    # the NREL 5 MW's first overspeed instability lies above rated (12.1 RPM) and below the
    # flap-torsion flutter near twice rated (docs/stability.md); with the deflected blade (the
    # default) it is the 1st edge BW at 1.2-1.4 x rated (docs/notes/edgewise_damping.md sec. 8)
    assert 12.1 < point["flutter_rpm"] < 2.5 * 12.1
    text = run_script(capsys, "run_analysis", ["--results", tmp_path / "run" / "results.nc"])
    assert line.group(0) in text  # reading an earlier run prints the same table


@pytest.mark.slow
def test_analysis_config_example_full_run(cached, tmp_path, capsys):
    # `windflutter run -c examples/analysis_nrel5mw.yaml` as documented, at one wind speed: report,
    # figures and animations included; the onset equals the stability example's on the same config
    rc = main(["run", "nrel5mw", "-c", str(EXAMPLES / "analysis_nrel5mw.yaml"), "--wind-speeds", "11.4",
               "-o", str(tmp_path / "full"), "-q", "--workers", "1"])
    assert rc == 0 and (tmp_path / "full" / "report.html").is_file()
    capsys.readouterr()
    import xarray as xr

    with xr.open_dataset(tmp_path / "full" / "results.nc") as ds:
        fl = float(ds["flutter_rpm"][0])
    point = json.loads(run_script(capsys, "stability_point", ["--config", EXAMPLES / "analysis_nrel5mw.yaml",
                                                              "--json"]))["points"][0]
    assert point["flutter_rpm"] == pytest.approx(fl, rel=1e-9)


@pytest.mark.slow
def test_campbell_example_full_size_equals_cli(cached, capsys):
    api = json.loads(run_script(capsys, "campbell_nrel5mw", ["--json"]))
    assert main(["campbell", "nrel5mw", "--wind-speeds", "6", "11.4", "18", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == api
