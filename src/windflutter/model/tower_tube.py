"""A tubular tower equivalent to distributed tower properties (ElastoDyn, HAWC2 st files).

windflutter's tower is a circular tube of one wall material (:class:`~windflutter.model.turbine.Tower`).
Given the mass per length ``m`` and the bending stiffness ``EI`` of each station with the wall's
``E`` and density ``rho``, the area ``A = m / rho`` and area moment ``I = EI / E`` fix the tube
exactly: ``Ro^2 - Ri^2 = A / pi`` and ``Ro^2 + Ri^2 = 4 I / A``.  Mass and bending stiffness are
then reproduced exactly at every station; torsion (``GJ = G 2I``) and the rotary inertia follow
from the tube.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.model.plausibility import station
from windflutter.model.turbine import IsotropicMaterial, Tower, TowerDamping, TowerLayer

#: Steel of the NREL 5 MW tower (Jonkman 2009 sec. 6: E 210 GPa, G 80.8 GPa, effective density
#: 8500 kg/m^3 for paint, bolts, welds and flanges): the defaults when a file gives only m and EI.
STEEL = {"E": 2.1e11, "G": 8.08e10, "rho": 8500.0}


def equivalent_tube(z: np.ndarray, m: np.ndarray, EI: np.ndarray, E: float, G: float, rho: float,
                    field: str, source: str | None, damping: TowerDamping | None = None,
                    material_name: str = "tower_wall") -> tuple[Tower, IsotropicMaterial]:
    """The tube tower with mass ``m`` (kg/m) and bending stiffness ``EI`` (N m^2) at heights
    ``z`` (m, increasing), of a wall with ``E``, ``G`` (Pa) and ``rho`` (kg/m^3).

    Raises
    ------
    InputError
        Where no tube has that mass and stiffness (the section would be more compact than a
        solid disc), naming the station.
    """
    z = np.asarray(z, dtype=float)
    A = np.asarray(m, dtype=float) / rho
    inner2 = 2.0 * np.asarray(EI, dtype=float) / (E * A) - A / (2.0 * np.pi)
    outer2 = inner2 + A / np.pi
    if np.any(inner2 < -1e-12 * outer2):
        i = int(np.argmax(inner2 < -1e-12 * outer2))
        s = (z - z[0]) / (z[-1] - z[0])
        raise InputError(f"{field} at {station(s, i)}", f"m = {m[i]:.6g} kg/m, EI = {EI[i]:.6g} N m^2",
                         f"a mass and stiffness a tube of E = {E:.3g} Pa, rho = {rho:.4g} kg/m^3 can have: "
                         "EI >= E m^2 / (4 pi rho^2), the solid disc", source)
    ro, ri = np.sqrt(outer2), np.sqrt(np.maximum(inner2, 0.0))
    mat = IsotropicMaterial(E=E, nu=E / (2.0 * G) - 1.0, rho=rho, name=material_name)
    tower = Tower(s=(z - z[0]) / (z[-1] - z[0]), z=z, outer_diameter=2 * ro,
                  layers=(TowerLayer(name="wall", material=material_name, thickness=ro - ri),),
                  outfitting_factor=1.0, damping=damping)
    return tower, mat
