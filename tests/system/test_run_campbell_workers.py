"""The run's operating-point Campbell on the run's local workers for a shell model (issue 33 item 2: the
shell map's time; the Campbell after the map's points was serial in the parent), in this process for a
beam model.  The 2-worker Campbell itself equals the serial one (test_campbell_workers.py)."""

from __future__ import annotations

import pytest

from windflutter import analysers
from windflutter.api import analysis_config, load_turbine


@pytest.mark.parametrize("model, workers, expected", [("beam", 2, 1), ("shell", 2, 2), ("shell", 1, 1),
                                                      ("shell", 8, 2)])
def test_run_campbell_workers(monkeypatch, model, workers, expected):
    seen = {}

    def service(turbine, config, winds, model=None, workers=1, prepared=None):
        seen["workers"] = workers
        return None

    monkeypatch.setattr(analysers, "service", service)
    cfg = analysis_config(wind_speeds=[8.0, 10.0], model=model)
    analysers.operating_campbell(load_turbine("nrel5mw"), cfg, workers=workers)
    assert seen["workers"] == expected  # at most one per wind speed
