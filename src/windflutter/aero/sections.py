"""The aerodynamic strip types, importable here; they live in :mod:`windflutter.aero_types` (the
bottom layer), so the model, mesh and rotor layers need not import the aero layer."""

from windflutter.aero_types import AeroSections, Polar, RotorGeometry

__all__ = ["AeroSections", "Polar", "RotorGeometry"]
