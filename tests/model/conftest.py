"""Shared, session-cached turbine loading for the model tests (validation of the big windIO files
takes ~1 s each; every file is parsed once per session)."""

from __future__ import annotations

import pytest

from windflutter.model import load_turbine

_CACHE: dict = {}


@pytest.fixture(scope="session")
def turbine():
    def get(name: str):
        if name not in _CACHE:
            _CACHE[name] = load_turbine(name)
        return _CACHE[name]

    return get
