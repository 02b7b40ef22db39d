"""The co-rotational static iteration's step limit (``solve_equilibrium(..., damped=True)``, the default).

Reference: the elastica of a cantilever under a dead tip force normal to it (Bisshopp & Drucker 1945,
Q. Appl. Math. 3(3); the closed form in elliptic integrals, ``test_deflected_beam.elastica_tip``), a
second implementation that shares nothing with the solver.  At ``P L^2 / EI = 10`` in one load step
plain Newton's first step (the linear tip deflection, 3.3 L) lands far from the solution and the
iteration wanders (measured: no convergence in 40 iterations); the step limit converges to the elastica.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_deflected_beam import EI_F, L, blade_like, elastica_tip, tip_load

from windflutter.errors import ModelError
from windflutter.structure import assemble
from windflutter.structure.corotational import solve_equilibrium


def _tip_error(eq, alpha: float) -> float:
    x, z = elastica_tip(alpha)
    return float(np.abs(eq.config.x[-1] / L - [x, 0.0, z]).max())


@pytest.mark.parametrize("alpha", [10.0, 20.0])
def test_a_large_load_in_one_step_reaches_the_elastica(alpha):
    """40 elements; tolerance 5e-5 L: the discretization error of the element at these curvatures
    (measured 7.9e-6 L and 1.7e-5 L, the same with 2 and 4 load steps)."""
    fe = blade_like(ne=40)
    P = np.array([0.0, 0.0, alpha * EI_F / L**2])
    eq = solve_equilibrium(fe, assemble(fe).T, tip_load(fe, P), max_iterations=40)
    assert _tip_error(eq, alpha) < 5e-5


def test_plain_newton_fails_where_the_limited_step_converges():
    """What the limit is for: the same case with ``damped=False`` does not converge."""
    fe = blade_like(ne=40)
    P = np.array([0.0, 0.0, 10.0 * EI_F / L**2])
    with pytest.raises(ModelError, match="damped iteration"):
        solve_equilibrium(fe, assemble(fe).T, tip_load(fe, P), max_iterations=40, damped=False)


@pytest.mark.parametrize("alpha", [1.5, 3.0, 5.0])
def test_where_plain_newton_converges_the_iterates_are_its_own(alpha):
    """Near a solution the increments shrink and no step is limited: the same configuration to
    round-off and the same number of iterations as plain Newton."""
    fe = blade_like(ne=40)
    P = np.array([0.0, 0.0, alpha * EI_F / L**2])
    T = assemble(fe).T
    a = solve_equilibrium(fe, T, tip_load(fe, P), max_iterations=40)
    b = solve_equilibrium(fe, T, tip_load(fe, P), max_iterations=40, damped=False)
    assert a.iterations == b.iterations
    np.testing.assert_array_equal(a.config.x, b.config.x)
    assert _tip_error(a, alpha) < 5e-5
