"""The number of negative eigenvalues of a symmetric structural matrix, read off its factorization.

A shell blade under its steady stress can lose definiteness in a local mode of the mesh far above the
lowest modes its basis holds (found on the NREL 5 MW shell blade at 16 m/s and 28 RPM: one eigenvalue
of ``K phi = w^2 M phi`` at -1.64e5 1/s^2, a skin mode at r/R 0.65-0.8, while the lowest stayed at
+35.6).  :func:`~windflutter.solve.symmetric.factor_with_inertia` counts the negative pivots of the
factorization (Sylvester's law of inertia); the reference here is a dense eigen-solve of the same
matrix, which shares nothing with it.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import scipy.sparse as sp

import windflutter.overspeed as op
import windflutter.solve.symmetric as sym
from windflutter.structure import linalg


def _laplacian_2d(n: int) -> sp.csc_matrix:
    """The 5-point Laplacian on an n x n grid (eigenvalues 4 - 2 cos(i pi/(n+1)) - 2 cos(j pi/(n+1)))."""
    T = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])
    return (sp.kron(T, sp.eye(n)) + sp.kron(sp.eye(n), T)).tocsc()


@pytest.mark.parametrize("cholmod", [True, False])
@pytest.mark.parametrize("shift", [0.0, 0.1, 0.4])
def test_negative_eigenvalues_are_counted(shift, cholmod, monkeypatch):
    """Shifted Laplacians with 0, a few and many negative eigenvalues; with CHOLMOD (where installed)
    and without it (the LU path).  Exact: the shifts lie well between eigenvalues."""
    if not cholmod:
        monkeypatch.setattr(sym, "SPDFactor", _no_cholmod)
    A = _laplacian_2d(14) - shift * sp.eye(14 * 14)
    w = np.linalg.eigvalsh(A.toarray())
    assert np.min(np.abs(w)) > 1e-3  # the shifts sit between eigenvalues
    solve, negative = sym.factor_with_inertia(A)
    assert negative == int(np.sum(w < 0))
    b = np.random.default_rng(1).standard_normal((A.shape[0], 3))
    assert np.abs(A @ solve(b) - b).max() < 1e-9 * np.abs(solve(b)).max() * np.abs(w).max()


def _no_cholmod(A, backend="auto"):
    raise ImportError("kvxopt is not installed (test)")


def test_a_negative_mode_outside_the_basis_makes_the_structural_margin_negative():
    """The margin of the reduced structure is positive, the full-order count says 1: the blade is
    statically unstable on its own (-inf: its eigenvalue is not computed); 0 or None keep the margin."""
    M, K = np.eye(8), np.diag([1e9] * 6 + [35.0, 50.0])  # six hub coordinates, two elastic modes
    for negative, expected in [(None, 35.0), (0, 35.0), (1, -np.inf)]:
        ps = SimpleNamespace(blade_structure=(M, K), blade_negative=negative)
        assert op.blade_structural_margin(ps) == pytest.approx(expected)


def test_the_sweep_stops_where_the_full_stiffness_turned_indefinite():
    """The note names both sweep points, holds from the last definite one, and is not divergence."""
    from windflutter.post.verdict import _note_from_rpm
    from windflutter.results import Onset

    on = Onset(method="p")
    stopped = op.OperationalStability._structure_lost(None, None, (26.0, 35.0), (28.0, -np.inf), on)
    assert stopped and "not positive definite at 28.00 RPM" in on.reason and "not aeroelastic divergence" in on.reason
    assert _note_from_rpm(on.reason) == pytest.approx(26.0)
    assert not op.OperationalStability._structure_lost(None, None, (26.0, 35.0), (28.0, 20.0), on)


def test_spd_factor_of_an_indefinite_matrix_is_refused():
    """What the count relies on: CHOLMOD (or the diagonal-pivot LU) refuses an indefinite matrix."""
    A = _laplacian_2d(6) - 1.0 * sp.eye(36)
    with pytest.raises(linalg.NotPositiveDefinite):
        linalg.SPDFactor(A, backend="superlu")


def test_the_campbell_warns_of_a_structure_unstable_at_its_operating_point():
    """A Campbell point whose blade structure is statically unstable on its own -- a negative mode of
    the basis (the IEA 15 MW shell's outboard skin) or negative eigenvalues of the full-order stiffness
    outside it -- is named with a ValidityWarning; a stable one is not."""
    import warnings

    from windflutter.errors import ValidityWarning
    from windflutter.system.campbell import warn_indefinite_blade

    def point(k, negative):
        return SimpleNamespace(blade_structure=(np.eye(8), np.diag([1e9] * 6 + [k, 50.0])), blade_negative=negative,
                               wind_speed=8.0, omega=0.6)

    for k, negative, said in [(-20.0, None, "a mode of its basis with a negative stiffness"),
                              (35.0, 2, "2 negative eigenvalue(s) of its full-order stiffness")]:
        with pytest.warns(ValidityWarning, match="statically unstable at the operating point") as got:
            warn_indefinite_blade(point(k, negative))
        assert said in str(got[0].message) and "at V = 8.0 m/s" in str(got[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warn_indefinite_blade(point(35.0, 0))
        warn_indefinite_blade(SimpleNamespace(blade_negative=None))  # a point source without a blade structure
