"""Comparison of two runs' datasets (everything but wall-clock times)."""

from __future__ import annotations

import xarray as xr

#: attributes that legitimately differ between two runs of the same analysis
VOLATILE_ATTRS = {"finished_utc"}


def assert_same_results(a: xr.Dataset, b: xr.Dataset, ignore_attrs: tuple[str, ...] = ()) -> None:
    a = a.drop_vars("elapsed")
    b = b.drop_vars("elapsed")
    # exact equality: the analysis is deterministic, a resumed run must give the same numbers
    xr.testing.assert_equal(a, b)
    for name in a.variables:
        assert a[name].attrs == b[name].attrs, name
    ka = {k: v for k, v in a.attrs.items() if k not in VOLATILE_ATTRS and k not in ignore_attrs}
    kb = {k: v for k, v in b.attrs.items() if k not in VOLATILE_ATTRS and k not in ignore_attrs}
    assert ka.keys() == kb.keys()
    for k in ka:
        assert str(ka[k]) == str(kb[k]), k
