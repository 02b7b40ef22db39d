"""The simulation's own equations linearized numerically about its equilibrium: eigenvalues without
integrating.

The time domain's equations of one blade on a rigid hub in the wind
(:func:`windflutter.simulate.blade.wind_blade_dynamics`: co-rotational beams in the spinning
frame, inertial loads of the current configuration, the nonlinear strips with their lag states)
are ``M q'' + f(q, q', z) = 0``, ``z' = g(q, q', z)``.  Their Jacobians at the equilibrium
(``q = q' = 0``, lags settled) by central differences of ``f`` and ``g`` -- no matrix of the
eigen-solver -- give the first-order system::

    x = (q, q', z),   x' = A x,   A = [[0, I, 0], [-M^-1 f_q, -M^-1 f_q', -M^-1 f_z], [g_q, g_q', g_z]]

whose eigenvalues are what the integration and the matrix pencil would identify (without the
scheme's period error and numerical damping).  A cheap check of the time domain against method p
at many points, and the tool that located the IEA 22 MW's 1st edge frequency difference
(docs/notes/iea22mw_edge_gap.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.errors import InputError
from windflutter.simulate.blade import wind_blade_dynamics
from windflutter.simulate.integrator import fd_jacobian

__all__ = ["Linearization", "linearize_blade_in_wind", "linearized_system"]


@dataclass(frozen=True)
class Linearization:
    """The first-order matrix ``A`` (module docstring) and its eigenvalues ``eigenvalues`` (1/s,
    the oscillatory ones, ``Im > 0``, ascending frequency); ``residual``: the largest force of the
    equations at the equilibrium (N, N m: how well it is one)."""

    A: np.ndarray
    eigenvalues: np.ndarray
    residual: float

    def nearest(self, lam: complex) -> complex:
        """The eigenvalue nearest ``lam``."""
        return complex(self.eigenvalues[np.argmin(np.abs(self.eigenvalues - lam))])


def linearized_system(dyn, step: float = 1e-6) -> Linearization:
    """:class:`Linearization` of a :class:`~windflutter.simulate.beam.SpinningBeams` (with its
    external loads and their states) about ``q = q' = 0`` and the settled lag states."""
    if not (np.isfinite(step) and step > 0):
        raise InputError("step", step, "a positive finite-difference step (m, rad)")
    n = dyn.T.shape[1]
    q0 = np.zeros(n)
    z0 = dyn.external.steady_lags(dyn.base) if dyn.external is not None else np.zeros(0)
    f0, _ = dyn.forces(0.0, q0, q0, z0)
    Jq, Jv, Jz = fd_jacobian(dyn, 0.0, q0, q0, z0, step)
    m = z0.size
    Mi = np.linalg.inv(dyn.mass)
    A = np.zeros((2 * n + m, 2 * n + m))
    A[:n, n:2 * n] = np.eye(n)
    A[n:2 * n] = -Mi @ np.hstack([Jq[:n], Jv[:n], Jz[:n]])
    A[2 * n:] = np.hstack([Jq[n:], Jv[n:], Jz[n:]])
    lam = np.linalg.eigvals(A)
    lam = lam[lam.imag > 1e-9]
    return Linearization(A=A, eigenvalues=lam[np.argsort(lam.imag)], residual=float(np.abs(f0).max()))


def linearize_blade_in_wind(turbine, wind_speed: float, rpm: float, pitch_deg: float | None = None, n_span: int = 30,
                            circulation: str = "jones", air_density: float = 1.225,
                            dynamic_stall: bool = False) -> Linearization:
    """The equations of :func:`~windflutter.simulate.blade.blade_in_wind` linearized about the
    blade's equilibrium (module docstring): its rotating-frame eigenvalues (``dynamic_stall``: with
    Oye's separation point per strip, the lags' settled values include it)."""
    dyn = wind_blade_dynamics(turbine, wind_speed, rpm, pitch_deg, n_span, circulation, air_density, dynamic_stall)
    return linearized_system(dyn)
