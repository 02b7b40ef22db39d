"""windflutter.structure: finite-element assembly, constraints, prestress, damping and modes.

Public API: :func:`assemble` -> :class:`Structural`, :func:`modes` -> :class:`Modes`,
:func:`static_solve`, :func:`geometric_stiffness`, :func:`centrifugal_load`,
:func:`spin_softening`, :func:`buckling_factors`, :func:`damping_matrix`,
:func:`rayleigh_coefficients`.  See ``docs/structure.md``.
"""

from windflutter.structure.assembly import Structural, assemble, check_constrained, rigid_body_vectors
from windflutter.structure.damping import damping_matrix, rayleigh_coefficients
from windflutter.structure.modal import Modes, modes
from windflutter.structure.prestress import (
    buckling_factors,
    centrifugal_load,
    geometric_stiffness,
    spin_softening,
    static_solve,
)

__all__ = [
    "Structural", "assemble", "check_constrained", "rigid_body_vectors", "Modes", "modes",
    "buckling_factors", "centrifugal_load", "geometric_stiffness", "spin_softening", "static_solve",
    "damping_matrix", "rayleigh_coefficients",
]
