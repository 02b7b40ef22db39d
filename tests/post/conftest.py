"""Fixtures of the post-processing tests (builders in post_fixtures.py, on the path here)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import xarray as xr

HERE = Path(__file__).parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

from post_fixtures import DATA, synthetic_campbell  # noqa: E402


@pytest.fixture
def stable_campbell():
    return synthetic_campbell()


@pytest.fixture
def unstable_campbell():
    return synthetic_campbell(edge_bw_zeta=(0.012, -0.004, 0.010))


@pytest.fixture(scope="session")
def nrel_campbell_ds():
    with xr.open_dataset(DATA / "nrel5mw_campbell.nc") as ds:
        return ds.load()
