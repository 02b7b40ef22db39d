"""The NREL 5 MW operating point the sensitivity tests share (one build per session)."""

from __future__ import annotations

import pytest

from sensitivity_checks import MAX_HZ, WIND


@pytest.fixture(scope="session")
def point(nrel5mw):
    """(model, point system, named modes up to MAX_HZ, their sensitivities) at WIND m/s."""
    from windflutter.api import analysis_config
    from windflutter.operating import campbell_model
    from windflutter.sensitivity.point import point_sensitivities
    from windflutter.system.modes import point_modes

    om = campbell_model(nrel5mw, analysis_config())
    ps = om.at(WIND)
    modes = point_modes(ps, MAX_HZ)
    return om, ps, modes, point_sensitivities(om, ps, modes)
