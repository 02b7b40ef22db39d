"""The post-processing on a real Campbell result (the system's own output, NREL 5 MW beam, two
wind speeds, coarse mesh; about 4 s): the dataset, the CSV equal to the JSON, the CF rules."""

from __future__ import annotations

import pytest
from post_fixtures import assert_cf_rules, json_rows

from windflutter.post import store
from windflutter.post.campbell_data import campbell_dataset
from windflutter.post.campbell_export import read_cmb, read_csv, write_cmb, write_csv
from windflutter.post.verdict import headline


@pytest.fixture(scope="module")
def nrel_result():
    from windflutter.model import load_turbine
    from windflutter.system.campbell import campbell
    from windflutter.system.operational import OperationalOptions

    return campbell(load_turbine("nrel5mw"), [6, 18], OperationalOptions(mesh={"n_span": 6}), max_hz=1.4)


def test_real_campbell_result_exports_and_stores(nrel_result, tmp_path):
    res = nrel_result
    ds = campbell_dataset(res)
    assert int((ds["frequency"].notnull()).sum()) == sum(len(p.modes) for p in res.points)
    assert read_csv(write_csv(res, tmp_path / "c.csv")) == json_rows(res)
    cmb = read_cmb(write_cmb(res, tmp_path / "c.cmb"))
    assert cmb.frequency.shape == (2, ds.sizes["track"])
    assert_cf_rules(store.write_campbell(tmp_path, res))
    text = headline(None, res)
    ld = res.least_damped()
    assert f"least damped mode in operation: {ld[1].name}, ζ = {100 * ld[1].damping_ratio:.2f} %" in text
