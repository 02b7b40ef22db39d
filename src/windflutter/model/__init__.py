"""windflutter.model: turbine description (dataclasses) and readers.

``load_turbine(path_or_name)`` reads windIO v1/v2 files, the seed thesis turbines and the bundled
reference turbines; see ``docs/turbine_input.md``.
"""

from windflutter.model.beamprops import blade_beam_sections, tower_beam_sections
from windflutter.model.bundled import bundled_turbines
from windflutter.model.turbine import (
    Airfoil,
    BeamProperties,
    Blade,
    ControlSettings,
    Hub,
    Layer,
    Layup,
    Nacelle,
    OperatingCurve,
    Tower,
    TowerLayer,
    Turbine,
    Web,
)
from windflutter.model.windio import load_turbine

__all__ = [
    "Airfoil", "BeamProperties", "Blade", "ControlSettings", "Hub", "Layer", "Layup", "Nacelle",
    "OperatingCurve", "Tower", "TowerLayer", "Turbine", "Web", "load_turbine", "bundled_turbines",
    "blade_beam_sections", "tower_beam_sections",
]
