"""The solver's aeroelastic model with the seed's skin-quad distribution of the strips.

The distribution itself is a pure function of the aero layer
(:func:`windflutter.aero.skin.skin_distribution`: (fe, strips) -> sub-strip AeroSections + parent
map) that any aerodynamic operator consumes (:func:`windflutter.aero.operators.make_operator`
with ``parent``).  This module keeps the model class that the current turbine analysis builds
(moved here from ``aero/skin.py``: the aero layer must not import the solver).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.skin import SkinOptions, SkinStripAero, skin_distribution
from windflutter.aero.sections import AeroSections
from windflutter.aero.strip import StripAero
from windflutter.solve.aeroelastic import AeroelasticModel

__all__ = ["SkinAeroelasticModel", "skin_aeroelastic_model"]


@dataclass
class SkinAeroelasticModel(AeroelasticModel):
    """:class:`~windflutter.solve.aeroelastic.AeroelasticModel` whose ``sections`` are skin
    sub-strips (:func:`skin_distribution`) with their ``parent`` strips; identical results to
    the plain model with the same sections, faster projected aerodynamics (:class:`SkinStripAero`).
    """

    parent: np.ndarray | None = None

    def strip(self, wind_speed: float, omega_rot: float) -> StripAero:
        if self.parent is None:
            return super().strip(wind_speed, omega_rot)
        return SkinStripAero(self.sections, self.operating_point(wind_speed, omega_rot), self.aero, parent=self.parent)


def skin_aeroelastic_model(fe, sections: AeroSections, skin: SkinOptions | None = None, **model_kwargs
                           ) -> SkinAeroelasticModel:
    """The aeroelastic model with the seed's skin-quad distribution.

    ``model_kwargs`` are those of :class:`~windflutter.solve.aeroelastic.AeroelasticModel`
    (``structure``, ``rotor``, ``rotor_geometry``, ``aero``, ``air_density``, ``n_modes``,
    ``omega_ref``, ``pitch``); ``sections`` are the model's strips (spline map not used).
    """
    d = skin_distribution(fe, sections, skin)
    return SkinAeroelasticModel(sections=d.sections, parent=d.parent, **model_kwargs)
