"""windflutter.mesh: Turbine -> FE model (shell or beam) + aerodynamic strips.

Public API: :class:`MeshSettings`, :func:`build_model` -> ``(FEModel, AeroSections)``,
:func:`turbine_modes` (labelled natural modes, optionally rotating),
:func:`thin_walled_properties` (6x6 beam properties from a layup).  See ``docs/mesh.md``.
"""

from windflutter.mesh.analysis import ModesResult, turbine_modes
from windflutter.mesh.section_props import thin_walled_properties
from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry

__all__ = ["MeshSettings", "build_model", "rotor_geometry", "turbine_modes", "ModesResult", "thin_walled_properties"]
