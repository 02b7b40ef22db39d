"""Support of tests/test_api.py and tests/test_examples.py: each bundled turbine read once.

:func:`cached_loading` makes every turbine reader entry (the API's, the CLI's and the workflow's)
return a turbine read once per session for the same arguments: reading and validating the NREL
5 MW takes 2-3 s, and these tests call the API, the CLI and the example scripts on it many times.
The turbine dataclasses are not changed by an analysis, so sharing one object is safe.
"""

from __future__ import annotations

_CACHE: dict = {}


def cached_loading(monkeypatch) -> None:
    """Patch ``windflutter.model.load_turbine`` (and its registry and windIO aliases) to read
    each ``(path_or_name, validate, fmt)`` once per session."""
    import windflutter.model
    import windflutter.model.registry as registry
    import windflutter.model.windio as windio

    real = _CACHE.setdefault("real", registry.load_turbine)

    def load(path_or_name, validate=True, fmt=None):
        key = (str(path_or_name), bool(validate), fmt)
        if key not in _CACHE:
            _CACHE[key] = real(path_or_name, validate=validate, fmt=fmt)
        return _CACHE[key]

    for module in (windflutter.model, registry, windio):
        monkeypatch.setattr(module, "load_turbine", load)
