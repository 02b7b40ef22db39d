"""The assembly's cached COO -> CSR map (``assembly.symmetric_csr``) against SciPy's conversion.

The deflected shell re-assembles the same mesh at every operating point; the CSR pattern of the
first assembly is reused for the next ones.  Checked against a path that shares nothing with the
cache: SciPy's ``coo_matrix(...).tocsr()``, duplicate sum and ``(A + A^T) / 2``, on a shell tube
whose nodes are moved between assemblies (so the values change and the pattern does not), and on a
second pattern of the same size that must not be mistaken for the first.
"""

import dataclasses

import numpy as np
import scipy.sparse as sp

from windflutter.structure import assembly
from windflutter.structure.shell import shell_coo

from shellmodels import iso, tube


def _scipy(r, c, v, n):
    A = sp.coo_matrix((v, (r, c)), shape=(n, n)).tocsr()
    A.sum_duplicates()
    return ((A + A.T) * 0.5).tocsr()


def test_cached_pattern_matches_scipy_on_moved_shell():
    fe, _ = tube(12, 6, 0.5, 3.0, iso(70e9, 0.3, 2700.0, 0.004))
    rng = np.random.default_rng(3)
    n = fe.n_dof
    for k in range(3):  # the first call builds the map, the next two reuse it
        moved = fe if k == 0 else dataclasses.replace(fe, nodes=fe.nodes + 0.01 * rng.standard_normal(fe.nodes.shape))
        (r, c, v), _ = shell_coo(moved)
        A, B = assembly.symmetric_csr(r, c, v, n), _scipy(r, c, v, n)
        scale = abs(B).max()
        assert A.shape == B.shape and A.has_sorted_indices
        assert abs(A - B).max() <= 1e-14 * scale  # summation order only
        assert (A != A.T).nnz == 0
        # SciPy's sum drops the entries that cancel to exactly 0 (MITC4's shear on the unmoved tube),
        # where the cached pattern keeps them with their round-off (the values are checked above)
        assert A.nnz >= B.nnz


def test_same_size_other_pattern_is_not_reused():
    rng = np.random.default_rng(5)
    n, m = 50, 400
    r, c = rng.integers(0, n, m), rng.integers(0, n, m)
    v = rng.standard_normal(m)
    v[:5] = 0.0
    assembly.symmetric_csr(r, c, v, n)
    c2 = c.copy()
    c2[7] = (c2[7] + 1) % n  # one entry elsewhere: the cached map must not apply
    A, B = assembly.symmetric_csr(r, c2, v, n), _scipy(r, c2, v, n)
    assert abs(A - B).max() == 0.0 and A.nnz == B.nnz
    A, B = assembly.symmetric_csr(r, c, -v, n), _scipy(r, c, -v, n)  # the first pattern again
    assert abs(A - B).max() == 0.0 and A.nnz == B.nnz


def test_given_shell_blocks_are_the_pyfe3d_assembly_and_are_checked():
    """``assemble(fe, shell_blocks=...)`` with the elements' own blocks (``shell_element_blocks``)
    is the pyfe3d assembly (1e-13: summation order); blocks of the wrong shape or not finite are an
    InputError naming ``shell_blocks``."""
    import pytest

    from windflutter.errors import InputError
    from windflutter.structure.shell import shell_element_blocks

    fe, _ = tube(12, 6, 0.5, 3.0, iso(70e9, 0.3, 2700.0, 0.004))
    Kb, Mb = shell_element_blocks(fe)
    st0 = assembly.assemble(fe, check=False)
    st1 = assembly.assemble(fe, check=False, shell_blocks=(Kb, Mb))
    assert abs(st1.K - st0.K).max() <= 1e-13 * abs(st0.K).max()
    assert abs(st1.M - st0.M).max() <= 1e-13 * abs(st0.M).max()
    bad = Kb.copy()
    bad[0, 0, 0] = np.nan
    for blocks, field in (((Kb[:-1], Mb), "shell_blocks.K"), ((Kb, Mb[:, :12]), "shell_blocks.M"),
                          ((bad, Mb), "shell_blocks.K"), ((Kb,), "shell_blocks")):
        with pytest.raises(InputError, match=field):
            assembly.assemble(fe, check=False, shell_blocks=blocks)
