"""windflutter.structure: finite-element assembly, constraints, prestress, damping and modes.

Public API: :func:`assemble` -> :class:`Structural`, :func:`modes` -> :class:`Modes`,
:func:`static_solve`, :func:`geometric_stiffness`, :func:`centrifugal_load`,
:func:`spin_softening`, :func:`damping_matrix`.
"""

from windflutter.structure.assembly import Structural, assemble, check_constrained, rigid_body_vectors
from windflutter.structure.modal import Modes, modes

__all__ = ["Structural", "assemble", "check_constrained", "rigid_body_vectors", "Modes", "modes"]

try:  # modules added incrementally
    from windflutter.structure.prestress import (  # noqa: F401
        centrifugal_load, geometric_stiffness, spin_softening, static_solve)
    from windflutter.structure.damping import damping_matrix  # noqa: F401

    __all__ += ["centrifugal_load", "geometric_stiffness", "spin_softening", "static_solve", "damping_matrix"]
except ImportError:  # pragma: no cover
    pass
