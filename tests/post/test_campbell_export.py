"""Campbell exports: CSV rows equal to the JSON fields bit for bit, the HAWCStab2-style .cmb
table, HAWCStab2's own .cmb layout read back, and bad files refused with a named field."""

from __future__ import annotations

import math

import numpy as np
import pytest
from post_fixtures import DATA, json_rows

from windflutter.errors import InputError
from windflutter.post.campbell_export import CSV_FIELDS, read_cmb, read_csv, write_cmb, write_csv


def test_csv_round_trip_equals_the_json_exactly(stable_campbell, tmp_path):
    path = write_csv(stable_campbell, tmp_path / "c.csv")
    rows = read_csv(path)
    assert rows == json_rows(stable_campbell)          # same order, same floats (repr round trip)
    assert path.read_text().splitlines()[0] == ",".join(CSV_FIELDS)


def test_csv_rows_in_wind_order_when_the_points_are_not(tmp_path):
    from post_fixtures import synthetic_campbell

    res = synthetic_campbell(shuffle=True)
    rows = read_csv(write_csv(res, tmp_path / "c.csv"))
    expect = sorted(json_rows(res), key=lambda r: (r["wind_speed"], r["frequency_hz"]))
    assert rows == expect


def test_cmb_round_trip_tracks_frequencies_damping_percent_and_gaps(stable_campbell, tmp_path):
    path = write_cmb(stable_campbell, tmp_path / "c.cmb", frequency="undamped")
    d = read_cmb(path)
    names = [t.name for t in stable_campbell.tracks]
    assert d.names == names and d.extra is None
    np.testing.assert_array_equal(d.wind_speed, [5.0, 11.0, 18.0])
    for t, tr in enumerate(stable_campbell.tracks):
        for i, p in enumerate(stable_campbell.points):
            k = tr.index[i]
            if k < 0:
                assert math.isnan(d.frequency[i, t]) and math.isnan(d.damping_pct[i, t])
                continue
            m = p.modes[k]
            # 10 significant digits in the file
            assert d.frequency[i, t] == pytest.approx(m.frequency_hz, rel=1e-9)
            assert d.damping_pct[i, t] == pytest.approx(100 * m.damping_ratio, rel=1e-9)
    damped = read_cmb(write_cmb(stable_campbell, tmp_path / "d.cmb"))  # the default: HAWCStab2's damped frequencies
    m = stable_campbell.points[0].modes[0]
    assert damped.frequency[0, 0] == pytest.approx(m.damped_frequency_hz, rel=1e-9)
    # the HAWCStab2 header layout: '# Wind [m/s]' then the mode numbers twice
    head = path.read_text().splitlines()[0].split()
    assert head[:3] == ["#", "Wind", "[m/s]"] and head[3:] == [str(k) for k in range(1, 6)] * 2
    # and numpy reads the table as it is (comment lines skipped)
    assert np.loadtxt(path).shape == (3, 11)


def test_cmb_names_each_modes_two_largest_participations(tmp_path):
    """Each track's two largest participations at each wind speed, in the .cmb's comment lines, are
    the mode records' own (ModeRecord.participation), in percent."""
    from post_fixtures import synthetic_campbell

    res = synthetic_campbell()
    for p in res.points:  # participations as the identification gives them
        for j, m in enumerate(p.modes):
            m.participation = [(f"identity {j}", 0.7), ("other", 0.2)]
    text = write_cmb(res, tmp_path / "p.cmb").read_text().splitlines()
    lines = [ln for ln in text if ln.startswith("# participation of mode ")]
    assert len(lines) == len([t for t in res.tracks if any(k >= 0 for k in t.index)])
    order = np.argsort([p.wind_speed for p in res.points], kind="stable")
    tr = res.tracks[0]
    expect = "; ".join(f"{res.points[i].wind_speed:g}: identity {tr.index[i]} 70 / other 20"
                       for i in order if tr.index[i] >= 0)
    assert lines[0] == f"# participation of mode 1 (wind m/s: largest % / second %): {expect}"
    assert read_cmb(tmp_path / "p.cmb").frequency.shape[0] == len(res.points)  # the reader skips them


def test_read_cmb_reads_hawcstab2_output():
    path = DATA / "iea15mw_hawcstab2_aeroelastic_head.cmb"
    d = read_cmb(path)
    assert d.frequency.shape == (5, 60) and d.extra.shape == (5, 60) and d.names == []
    # second implementation: the numbers of the file's 2nd data row split by hand
    row = [float(x) for x in path.read_text().splitlines()[2].split()]
    assert d.wind_speed[1] == row[0] == 2.0
    np.testing.assert_array_equal(d.frequency[1], row[1:61])
    np.testing.assert_array_equal(d.damping_pct[1], row[61:121])


@pytest.mark.parametrize("text, field", [
    ("wind_speed,name\n5,x\n", "columns"),
    (",".join(CSV_FIELDS) + "\n5,7,0,x,edge,one,BW,1,1,0.01\n", "line 2"),
])
def test_bad_csv_is_refused_naming_the_field(tmp_path, text, field):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    with pytest.raises(InputError) as exc:
        read_csv(p)
    assert exc.value.field == field and str(p) in str(exc.value)


@pytest.mark.parametrize("text, field", [
    ("", "header"), ("hello\n1 2 3\n", "header"),
    ("  # Wind [m/s]  1  2  1  2\n 5.0 1.0 2.0 3.0\n", "table"),
    ("  # Wind [m/s]  1  1\n 5.0 one 2.0\n", "row"),
])
def test_bad_cmb_is_refused_naming_the_field(tmp_path, text, field):
    p = tmp_path / "bad.cmb"
    p.write_text(text)
    with pytest.raises(InputError) as exc:
        read_cmb(p)
    assert exc.value.field == field


def test_exports_refuse_a_folder_or_missing_file(stable_campbell, tmp_path):
    with pytest.raises(InputError, match="--csv"):
        write_csv(stable_campbell, tmp_path)
    with pytest.raises(InputError, match="--cmb"):
        write_cmb(stable_campbell, tmp_path)
    with pytest.raises(InputError, match="frequency"):
        write_cmb(stable_campbell, tmp_path / "x.cmb", frequency="natural")
    with pytest.raises(InputError):
        read_cmb(tmp_path / "missing.cmb")
    with pytest.raises(InputError):
        read_csv(tmp_path / "missing.csv")
