"""Co-rotational beams in a spinning frame: the nonlinear equations of motion for the time domain.

Coordinates: the free DOFs ``q`` of the model's constraint map (``u = T q``), a displacement from
a base configuration ``(x_b, R_b)`` (the steady state): node positions ``x = x_b + u_t`` and
rotations ``R = expm(u_r) R_b`` (rotation vectors relative to the base, exact for any rotation
below pi).  The equations, in the frame spinning with the rotor::

    T^T M T q'' + T^T J^T (f_int(x, R) - f_inertial(x, R, x', omega) - f_ext) = 0

* ``f_int``: the co-rotational beam's internal forces (:func:`~windflutter.structure.corotational.
  beam_internal_forces`, the element kernel of the steady state), evaluated at the current
  configuration -- no tangent or geometric-stiffness matrix;
* ``f_inertial``: centrifugal and Coriolis loads of the current configuration
  (:class:`~windflutter.simulate.inertia.SpinningMass`);
* ``f_ext``: other loads (aerodynamic strips), a callback;
* ``J``: block-diagonal, identity on translations and the left Jacobian of SO(3) ``J_l(u_r)``
  on rotations (``omega = J_l(u_r) u_r'``; its transpose maps the moments, conjugate to spatial
  spins, to the rotation-vector coordinates);
* ``M``: the model's consistent mass matrix at the base configuration, constant (the relative
  accelerations; the rotating-frame terms are all in ``f_inertial``).

The iteration matrix (not the solution) uses the beam's tangent at the base configuration.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.linalg_tools import skew
from windflutter.simulate.inertia import SpinningMass
from windflutter.simulate.integrator import fd_jacobian
from windflutter.structure.corotational import (
    BeamConfiguration,
    beam_elements,
    beam_internal_forces,
    beam_tangent,
    displaced,
    solve_equilibrium,
)

__all__ = ["SpinningBeams", "left_jacobian", "spin_equilibrium"]


def left_jacobian(theta: np.ndarray) -> np.ndarray:
    """(..., 3, 3) left Jacobian of SO(3): ``d/dt expm(theta) expm(theta)^T = S(J_l theta')``."""
    th = np.asarray(theta, float)
    t2 = np.einsum("...i,...i->...", th, th)
    t = np.sqrt(t2)
    small = t < 1e-4
    ts = np.where(small, 1.0, t)
    a = np.where(small, 0.5 - t2 / 24.0, (1.0 - np.cos(ts)) / ts**2)
    b = np.where(small, 1.0 / 6.0 - t2 / 120.0, (ts - np.sin(ts)) / ts**3)
    S = skew(th)
    return np.eye(3) + a[..., None, None] * S + b[..., None, None] * (S @ S)


def spin_equilibrium(fe, T, inertia: SpinningMass, start: BeamConfiguration | None = None,
                     external: Callable | None = None, load_steps: int = 1) -> BeamConfiguration:
    """The static configuration of ``fe`` under its centrifugal loads (and ``external(config)``,
    full numbering) by the co-rotational Newton iteration."""

    def loads(config, factor):
        f = inertia.loads(config.x, config.R).reshape(-1)
        if external is not None:
            f = f + external(config)
        return factor * f, None

    return solve_equilibrium(fe, T, loads, start=start, tol=1e-10, max_iterations=80, load_steps=load_steps,
                             final=False).config


class SpinningBeams:
    """:class:`~windflutter.simulate.integrator.Dynamics` of a beam model in the spinning frame.

    Parameters
    ----------
    fe : beam model (no springs).  T : (n_dof, nq) constraint map.  M : (n_dof, n_dof) mass matrix
        at the base configuration.
    base : the base (steady) configuration.  inertia : its spinning mass.
    external : optional ``external(t, config, xdot, omega, z) -> (f (n_dof,), zdot (m,))``: more
        loads (aerodynamics) and the rates of their ``m`` states.
    n_states : ``m``.  outputs : ``outputs(config, u, udot) -> (k,)`` recorded channels.
    """

    def __init__(self, fe, T, M, base: BeamConfiguration, inertia: SpinningMass, external=None, n_states: int = 0,
                 outputs: Callable | None = None):
        if fe.springs:
            raise InputError("fe.springs", len(fe.springs), "a model without springs (beams and masses)")
        self.fe, self.base, self.inertia = fe, base, inertia
        self.T = sp.csr_matrix(T)
        self.mass = np.asarray((self.T.T @ (M @ self.T)).todense()) if sp.issparse(M) else self.T.T @ M @ self.T
        self.mass = 0.5 * (self.mass + self.mass.T)
        self.el = beam_elements(fe)
        self.external, self.n_states = external, int(n_states)
        self._outputs = outputs
        self.evaluations = 0
        #: Newton floor (m, rad): the round-off of the internal forces (central differences) is
        #: ~1e-15 of the model size in displacement
        self.atol = 1e-12 * max(float(np.ptp(np.asarray(fe.nodes, float), axis=0).max()), 1.0)

    def set_outputs(self, outputs: Callable | None) -> None:
        """The recorded channels: ``outputs(config, u, udot) -> (k,)`` (None: all displacements)."""
        self._outputs = outputs

    def configuration(self, q) -> BeamConfiguration:
        return displaced(self.base, np.asarray(self.T @ q).reshape(-1))

    def forces(self, t, q, v, z):
        self.evaluations += 1
        u = (self.T @ q).reshape(-1, 6)
        ud = (self.T @ v).reshape(-1, 6)
        Jl = left_jacobian(u[:, 3:])
        omega = np.einsum("nij,nj->ni", Jl, ud[:, 3:])
        cfg = self.configuration(q)
        f = beam_internal_forces(self.fe, cfg, self.el).reshape(-1, 6)
        f = f - self.inertia.loads(cfg.x, cfg.R, ud[:, :3], omega)
        zdot = np.zeros(0)
        if self.external is not None:
            fe_, zdot = self.external(t, cfg, ud[:, :3], omega, z)
            f = f - np.asarray(fe_).reshape(-1, 6)
        f[:, 3:] = np.einsum("nji,nj->ni", Jl, f[:, 3:])
        return self.T.T @ f.reshape(-1), np.asarray(zdot, float).reshape(-1)

    def jacobian(self, t, q, v, z):
        """An iteration matrix: with external loads, central differences of the forces (once per
        rebuild); else the beam's tangent at the configuration (inertial loads left out).  The
        Newton iteration converges to the same step with either."""
        if self.external is not None:

            return fd_jacobian(self, t, q, v, z, 1e-7)
        K = beam_tangent(self.fe, self.configuration(q), elements=self.el).K
        n, m = self.T.shape[1], self.n_states
        Jq = np.zeros((n + m, n))
        Jq[:n] = np.asarray((self.T.T @ K @ self.T).todense())
        return Jq, np.zeros((n + m, n)), np.zeros((n + m, m))

    def outputs(self, t, q, v, z):
        u = self.T @ q
        return self._outputs(self.configuration(q), u, self.T @ v) if self._outputs else u
