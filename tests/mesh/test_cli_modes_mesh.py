"""`windflutter modes` and `windflutter mesh` end to end (bundled NREL 5 MW, small models)."""

import json

from windflutter.cli import main


def test_modes_json_beam_blade(capsys):
    rc = main(["modes", "nrel5mw", "--part", "blade", "--model", "beam", "--n", "4", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0
    assert len(out["frequencies_hz"]) == 4 and out["labels"][:2] == ["1st flap", "1st edge"]
    # Jonkman 2009 / BModes: flap 1 0.65-0.70 Hz (Timoshenko 6x6: -1 %)
    assert 0.64 < out["frequencies_hz"][0] < 0.70


def test_modes_rotating_table(capsys):
    rc = main(["modes", "nrel5mw", "--part", "blade", "--model", "beam", "--n", "3", "--rpm", "12.1"])
    text = capsys.readouterr().out
    assert rc == 0 and "12.1 rpm" in text and "1st flap" in text


def test_modes_bad_input_exit_2(capsys):
    assert main(["modes", "nrel5mw", "--part", "tower", "--rpm", "5"]) == 2
    assert "rpm" in capsys.readouterr().err
    assert main(["modes", "no_such_turbine_xyz"]) == 2
    assert main(["modes", "nrel5mw", "--n-chord", "2"]) == 2


def test_mesh_exports(tmp_path, capsys):
    vtu, bdf = tmp_path / "m.vtu", tmp_path / "m.bdf"
    rc = main(["mesh", "nrel5mw", "--part", "blade", "--model", "shell", "--n-chord", "16", "--n-span", "6", "--vtk", str(vtu), "--bdf", str(bdf)])
    assert rc == 0
    assert vtu.stat().st_size > 1000 and bdf.stat().st_size > 1000
    assert "CQUAD4" in bdf.read_text()
    assert main(["mesh", "nrel5mw"]) == 2  # no output requested
