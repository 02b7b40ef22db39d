"""windflutter.model: turbine description (dataclasses) and readers.

``load_turbine(path_or_name)`` reads windIO v1/v2 files, OpenFAST decks (``.fst``), HAWC2 models
(``.htc``), the seed thesis turbines and the bundled reference turbines, choosing the reader by
file type (:mod:`windflutter.model.registry`); see ``docs/turbine_input.md``.
"""

from windflutter.model.beamprops import blade_beam_sections, tower_beam_sections
from windflutter.model.bundled import bundled_turbines
from windflutter.model.registry import TurbineReader, load_turbine, readers, register_reader, unregister_reader
from windflutter.model.turbine import (
    Airfoil,
    BeamProperties,
    Blade,
    BladeDamping,
    ControlSettings,
    Hub,
    Layer,
    Layup,
    Nacelle,
    OperatingCurve,
    Tower,
    TowerDamping,
    TowerLayer,
    Turbine,
    Web,
)

__all__ = [
    "Airfoil", "BeamProperties", "Blade", "BladeDamping", "ControlSettings", "Hub", "Layer", "Layup", "Nacelle",
    "OperatingCurve", "Tower", "TowerDamping", "TowerLayer", "Turbine", "TurbineReader", "Web", "load_turbine",
    "bundled_turbines", "readers", "register_reader", "unregister_reader", "blade_beam_sections", "tower_beam_sections",
]
