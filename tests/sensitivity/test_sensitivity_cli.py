"""``windflutter sensitivity``: the ranked table, the NetCDF dataset and the plot; bad input refused
in one line before any analysis."""

from __future__ import annotations

import numpy as np
import pytest

from windflutter.cli import main


def _run(argv, capsys):
    rc = main(argv)
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.mark.slow
def test_table_dataset_and_plot(tmp_path, capsys):
    """One wind speed, one mode: the table's sentences, the dataset's dimensions and units, the
    figure; the sentence's number is the dataset's segment sum for +1 %."""
    import xarray as xr

    nc, png = tmp_path / "s.nc", tmp_path / "s.png"
    rc, out, err = _run(["sensitivity", "nrel5mw", "--wind-speeds", "15", "--max-hz", "1.0", "--modes",
                         "1st edge BW", "--out", str(nc), "--plot", str(png), "--top", "40"], capsys)
    assert rc == 0, err
    lines = [ln.strip() for ln in out.splitlines()[1:]]
    assert len(lines) == 40 and all("the 1st edge BW damping at 15 m/s by" in ln for ln in lines)
    assert png.stat().st_size > 10_000
    ds = xr.open_dataset(nc)
    assert dict(ds["ddamping"].sizes) == {"mode": 1, "wind_speed": 1, "parameter": 9, "station": 30}
    assert ds["ddamping"].attrs["units"] == "1" and ds["dfrequency"].attrs["units"] == "Hz"
    assert ds["wind_speed"].attrs["units"] == "m/s" and list(ds["mode"].values) == ["1st edge BW"]
    st = ds["station"].values
    dz = ds["ddamping"].sel(mode="1st edge BW", parameter="edge_stiffness").values[0]
    seg = dz[(st >= 0.2) & (st < 0.4)].sum() * 0.01 * 100
    line = next(ln for ln in lines if ln.startswith("+1 % edge stiffness at r/R 0.2-0.4"))
    value = float(line.split(" by ")[1].split(" points")[0])
    assert value == pytest.approx(abs(seg), rel=2e-3)
    assert ("raises" in line) == (seg > 0)
    assert np.all(ds["defined"].values == 1)


@pytest.mark.parametrize("argv, words", [
    pytest.param(["--modes", "99th edge BW"], ["modes", "99th edge BW"], marks=pytest.mark.slow),
    (["--out", "x.csv"], ["--out", ".nc"]),
    (["--wind-speeds", "-3"], ["wind"]),
    (["--top", "0"], ["--top"]),
    (["--onset", "--wind-speeds", "12", "15"], ["--wind-speeds", "one wind speed"]),
    (["--rpm", "16.9"], ["--rpm", "--onset"]),
    (["--onset", "--modes", "1st edge BW", "2nd flap BW", "--rpm", "16.9"], ["--modes", "one mode"]),
    (["--onset", "--rpm", "16.9"], ["--modes"]),
    (["--onset", "--modes", "1st edge BW", "--rpm", "-2"], ["--rpm", "positive"]),
    (["--onset", "--modes", "1st edge BW", "--rpm", "16", "--plot", "x.png"], ["--plot"]),
])
def test_bad_input_is_one_line(argv, words, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rc, out, err = _run(["sensitivity", "nrel5mw", "--wind-speeds", "15", "--max-hz", "0.5"] + argv
                        if "--wind-speeds" not in argv else ["sensitivity", "nrel5mw"] + argv, capsys)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert rc == 2 and len(lines) == 1, err
    assert "Traceback" not in err
    for w in words:
        assert w in lines[0], (w, lines[0])


def test_unknown_parameter_names_the_keyword():
    from windflutter.errors import InputError
    from windflutter.sensitivity.parameters import BLADE_PROPERTIES, check_parameters

    with pytest.raises(InputError) as exc:
        check_parameters(["flap_stifness"], BLADE_PROPERTIES, "blade_properties")
    assert "blade_properties" in str(exc.value) and "flap_stiffness" in str(exc.value)


@pytest.mark.slow
def test_onset_table_and_dataset(tmp_path, capsys):
    """``--onset``: the onset of the 1st edge BW of the NREL 5 MW at 12 m/s (16.865 RPM,
    tests/sensitivity/test_sensitivity_onset.py) and its ranked shifts; the NetCDF dataset's
    ``drpm_unit_change`` is the printed shift (the mass centre's -0.0868 RPM per cm first)."""
    import xarray as xr

    nc = tmp_path / "onset.nc"
    rc, out, err = _run(["sensitivity", "nrel5mw", "--onset", "--wind-speeds", "12", "--modes", "1st edge BW",
                         "--rpm", "16.9", "--max-hz", "1.5", "--out", str(nc)], capsys)
    assert rc == 0, err
    lines = out.splitlines()
    assert lines[0].startswith("onset of the 1st edge BW at 12 m/s: 16.86")
    assert lines[1].strip().startswith("+1 cm mass centre (aft along the chord) (whole blade) lowers the onset by 0.08")
    ds = xr.open_dataset(nc)
    assert ds.attrs["onset_rpm"] == pytest.approx(16.865, abs=2e-3)
    shift = float(ds["drpm_unit_change"].sel(parameter="mass_offset"))
    assert shift == pytest.approx(-float(lines[1].split(" by ")[1].split(" RPM")[0]), rel=2e-3)
    assert ds["drpm"].attrs["units"] == "rpm"
