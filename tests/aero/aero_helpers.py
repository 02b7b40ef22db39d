"""Shared builders for the aerodynamic-operator tests: one strip on a rigid section, the
typical section's structure, and a p-method onset search on a first-order system."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy import optimize

from windflutter.aero.flow import OperatingPoint
from windflutter.aero.operators import StateSpaceAero
from windflutter.aero.sections import AeroSections, Polar


def one_strip(b: float, a: float, alpha0: float = 0.0, polar: Polar | None = None, width: float = 1.0):
    """One strip (chord 2b, elastic axis a) in a wind along +x, span +y, lift +z, with its chord
    at alpha0 (nose up) to the wind; motion map = identity on its 6 DOFs."""
    chord = np.array([[np.cos(alpha0), 0.0, -np.sin(alpha0)]])  # trailing edge low: nose up
    pol = [polar] if polar is not None else []
    return AeroSections(blade=np.array([0]), radius=np.array([1.0]), width=np.array([width]),
                        chord=np.array([2 * b]), elastic_axis=np.array([a]), origin=np.zeros((1, 3)),
                        e_chord=chord, e_span=np.array([[0, 1.0, 0]]), airfoil=np.array([0]), polars=pol,
                        twist=np.zeros(1), motion_map=sp.identity(6, format="csr"))


def stall_polar() -> Polar:
    """Piecewise-linear polar with nodes every 2 deg: attached slope ~6.1/rad to 10 deg, peak at
    14 deg, falling lift (negative slope) beyond; drag rising in stall; Cm nose-down growing."""
    a = np.arange(-10.0, 32.0, 2.0)
    cl = np.interp(a, [-10, -2, 10, 14, 18, 24, 30], [-0.85, 0.0, 1.28, 1.42, 1.18, 1.05, 1.02])
    cd = np.interp(a, [-10, 0, 8, 12, 16, 20, 30], [0.03, 0.008, 0.012, 0.03, 0.12, 0.25, 0.45])
    cm = np.interp(a, [-10, 0, 10, 14, 18, 30], [0.0, -0.05, -0.07, -0.08, -0.12, -0.16])
    return Polar(np.radians(a), cl, cd, cm, name="stall")


#: (h_down, alpha) of the typical section -> the strip's 6 DOFs (uz = -h_down, ry = alpha)
SECTION_BASIS = np.zeros((6, 2))
SECTION_BASIS[2, 0] = -1.0
SECTION_BASIS[4, 1] = 1.0


def section_state_matrix(sec, U: float, options, basis=SECTION_BASIS):
    """First-order state matrix of a TypicalSection (its M, K; h down) with the state-space
    strip operator at speed U."""
    from windflutter.section import structural_matrices

    M, K = structural_matrices(sec)
    strip = one_strip(sec.semi_chord, sec.elastic_axis)
    op = StateSpaceAero(strip, OperatingPoint(U, 0.0, sec.air_density, None), options)
    pss = op.projected(basis)
    return pss.state_matrix(M, np.zeros_like(M), K)


def max_oscillatory_real(A: np.ndarray, omega_min: float) -> float:
    """Largest real part of the eigenvalues of A with |Im| > omega_min (the aero lag roots are real)."""
    lam = np.linalg.eigvals(A)
    osc = lam[np.abs(lam.imag) > omega_min]
    return float(osc.real.max())


def p_onset(state_matrix_of, speeds, omega_min: float, xtol: float = 1e-12) -> float:
    """First speed where the largest real part of the oscillatory roots crosses zero (grid bracket,
    then Brent)."""
    f = [max_oscillatory_real(state_matrix_of(U), omega_min) for U in speeds]
    for i in range(len(speeds) - 1):
        if f[i] < 0 <= f[i + 1]:
            return optimize.brentq(lambda U: max_oscillatory_real(state_matrix_of(U), omega_min),
                                   speeds[i], speeds[i + 1], xtol=xtol * speeds[i + 1])
    return None
