import numpy as np
import pytest

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry
from windflutter.structure.assembly import assemble
from windflutter.system.blade import RotorBlade
from windflutter.system.support import support_model


@pytest.fixture(scope="session")
def nrel5mw_turbine(nrel5mw):
    return nrel5mw  # tests/conftest.py: one load per session


@pytest.fixture(scope="session")
def nrel_rotor_blade(nrel5mw_turbine):
    """NREL 5 MW beam blade (10 elements) on its clamped hub, full order."""
    tb = nrel5mw_turbine
    g = rotor_geometry(tb)
    fe, sec = build_model(tb, MeshSettings(model="beam", part="rotor_blade", n_span=10))
    return RotorBlade(fe, assemble(fe), sec, g.hub_center, g.shaft_axis)


@pytest.fixture(scope="session")
def nrel_support(nrel5mw_turbine):
    fe, _ = build_model(nrel5mw_turbine, MeshSettings(model="beam", part="support", n_tower_axial=10))
    return support_model(fe, assemble(fe))
