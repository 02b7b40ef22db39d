"""Typical-section (2-DOF plunge/pitch) flutter and divergence with Theodorsen aerodynamics.

Model (Theodorsen 1935; Bisplinghoff, Ashley & Halfman 1955 ch. 5; Hodges & Pierce 2011 ch. 5)::

    m h'' + S a'' + K_h h     = -L
    S h'' + I a'' + K_a alpha =  M_ea

with the plunge ``h`` positive DOWN inside this package (Theodorsen's convention), pitch
``alpha`` nose-up about the elastic axis at ``a b`` aft of mid-chord, ``S`` the static moment (CG
aft of EA positive) and, for harmonic motion, Theodorsen's (1935) lift and moment::

    L    = pi rho b^2 (h'' + U alpha' - b a alpha'')
         + Cla rho U b C(k) [h' + U alpha + b(1/2 - a) alpha']
    M_ea = pi rho b^2 [b a h'' - U b (1/2 - a) alpha' - b^2 (1/8 + a^2) alpha'']
         + Cla rho U b^2 (a + 1/2) C(k) [h' + U alpha + b(1/2 - a) alpha']

(``Cla`` = lift slope, 2 pi for the flat plate; only the circulatory part is scaled).  The
public results report the flutter mode with ``h`` positive along the lift (up), as in the
project's conventions.

An optional ``plunge_angle`` (rad) is the angle between the plunge DOF and the lift direction:
the aerodynamics sees the plunge ``h cos(plunge_angle)`` and the lift acts on the plunge DOF with
the same factor (used by the seed's rotor "simple model", thesis eq. 4.3).

Modules
-------
* :mod:`.model` -- :class:`TypicalSection` (dimensional and nondimensional forms, checked);
  :mod:`.input` -- :func:`section_from_config` for the ``windflutter section`` YAML.
* :mod:`.matrices` -- structural and aerodynamic matrices, the companion form, divergence:
  closed form ``sqrt(K_a / (Cla rho b^2 (a + 1/2)))`` and from ``K_s x = U^2 K_aero x``.
* :mod:`.results` -- :class:`SectionResult`, :class:`StabilityCurves`, the speed grid.
* :mod:`.kmethod` -- V-g method: artificial structural damping ``g`` for harmonic motion,
  eigenproblem in ``(1 + i g)/omega^2`` for each k, flutter where ``g`` of a branch crosses 0.
* :mod:`.pk` -- p-k: for each speed and each mode, k is iterated to the mode's own frequency
  ``k = omega b / U``; flutter where the tracked mode's ``sigma`` crosses 0 (bracket on a speed
  grid + Brent root-finding); :func:`locate_pk_onset` also serves the rotor simple model.
* :mod:`.pmethod` -- exact eigenvalues of the state-space model built with a Roger
  rational-function approximation of C(k) (aero lag states); same bracket + root-find.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.section.input import section_from_config
from windflutter.section.kmethod import k_method
from windflutter.section.matrices import (
    aero_matrices,
    divergence_speed,
    divergence_speed_numerical,
    natural_frequencies,
    structural_matrices,
)
from windflutter.section.model import TWO_PI, TypicalSection
from windflutter.section.pk import locate_pk_onset, pk_eigen, pk_method
from windflutter.section.pmethod import p_method, rfa_state_matrix
from windflutter.section.results import SectionResult, StabilityCurves

__all__ = [
    "TypicalSection",
    "StabilityCurves",
    "SectionResult",
    "section_from_config",
    "structural_matrices",
    "aero_matrices",
    "k_method",
    "pk_method",
    "p_method",
    "analyse",
    "divergence_speed",
    "divergence_speed_numerical",
    "pk_eigen",
    "rfa_state_matrix",
    "natural_frequencies",
    "locate_pk_onset",
]


def analyse(sec: TypicalSection, method: str = "pk", speeds: np.ndarray | None = None) -> SectionResult:
    """Run one of ``"k"``, ``"pk"``, ``"p"`` (``speeds`` in m/s; ignored by the k-method)."""
    if method == "k":
        return k_method(sec)
    if method == "pk":
        return pk_method(sec, speeds)
    if method == "p":
        return p_method(sec, speeds)
    raise InputError("method", method, "one of 'k', 'pk', 'p'")
