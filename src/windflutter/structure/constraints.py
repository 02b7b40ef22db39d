"""Constraint transformation ``u = T q`` from single-point constraints and rigid links.

Rigid links (RBE2-like) are imposed by *elimination*: each tied component of a dependent node is
an exact linear combination of the independent node's six DOFs,

    u_d = u_i + theta_i x (x_d - x_i),   theta_d = theta_i,

and single-point constraints (value 0) drop the DOF.  No penalty numbers are involved, so the
reduced matrices ``T^T K T`` keep the conditioning of the unconstrained element matrices.
Chains of links (a dependent node that is the independent node of another link) are resolved by
repeated substitution; cycles raise :class:`ModelError`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError, ModelError
from windflutter.linalg_tools import skew
from windflutter.structure.fem import FEModel


def spc_dofs(fe: FEModel) -> np.ndarray:
    """Sorted global DOF numbers fixed by ``fe.spc``."""
    out = []
    for node, comps in fe.spc.items():
        comps = tuple(int(c) for c in comps)
        if any(c < 0 or c > 5 for c in comps):
            raise InputError(f"spc[{node}]", comps, "components in 0..5 (ux, uy, uz, rx, ry, rz)")
        out.extend(6 * int(node) + c for c in comps)
    return np.unique(np.array(out, dtype=np.int64))


def rigid_link_rows(fe: FEModel) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Linear relations of dependent DOFs: ``u[dep] = sum coef * u[col]`` as COO triplets.

    Returns
    -------
    dep_dofs : (nd,) unique dependent DOF numbers.
    rows, cols, vals : COO entries of the relation (rows are dependent DOF numbers).
    """
    x = np.asarray(fe.nodes, dtype=float)
    rows, cols, vals, deps = [], [], [], []
    for k, link in enumerate(fe.rigid_links):
        dep = np.atleast_1d(np.asarray(link.dependent, dtype=np.int64))
        comps = np.array(sorted(set(int(c) for c in link.dofs)), dtype=np.int64)
        if comps.size == 0 or comps.min() < 0 or comps.max() > 5:
            raise InputError(f"rigid_links[{k}].dofs", link.dofs, "components in 0..5")
        if np.any(dep == link.independent):
            raise InputError(f"rigid_links[{k}].dependent", int(link.independent), "nodes other than the independent node")
        i = int(link.independent)
        r = x[dep] - x[i]  # (nd, 3)
        # full 6x6 relation per dependent node: [u; th]_d = G [u; th]_i, G = [[I, -S(r)], [0, I]]
        G = np.zeros((dep.size, 6, 6))
        G[:, :3, :3] = np.eye(3)
        G[:, 3:, 3:] = np.eye(3)
        G[:, :3, 3:] = -skew(r)
        for c in comps:
            g = G[:, c, :]  # (nd, 6)
            nz = np.nonzero(np.abs(g) > 0)
            rows.append(6 * dep[nz[0]] + c)
            cols.append(6 * i + nz[1])
            vals.append(g[nz])
            deps.append(6 * dep + c)
    for k, dia in enumerate(fe.diaphragms):
        for part in diaphragm_rows(x, dia, k):
            for lst, v in zip((rows, cols, vals, deps), part):
                lst.append(v)
    if not deps:
        e = np.zeros(0, dtype=np.int64)
        return e, e, e, np.zeros(0)
    dep_all = np.concatenate(deps)
    uniq, counts = np.unique(dep_all, return_counts=True)
    if np.any(counts > 1):
        d = int(uniq[counts > 1][0])
        raise ModelError(f"DOF {d % 6} of node {d // 6} is dependent in more than one rigid link")
    return uniq, np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)


def diaphragm_rows(x: np.ndarray, dia, k: int):
    """Relation rows of one :class:`~windflutter.structure.fem.Diaphragm` (see
    :func:`rigid_link_rows`).

    With an in-plane basis ``E`` (2 x 3) of the plane normal to ``n``, every dependent node obeys
    ``E u_d = E (u_i + theta_i x r)``, ``r = x_d - x_i``.  The two global components eliminated
    are those other than ``c = argmax |n_c|`` (the determinant of ``E`` on them is ``+-n_c``, the
    largest possible), so ``u_d[ab] = E_ab^-1 E (u_i - S(r) theta_i) - E_ab^-1 E_c u_d[c]``.
    Yields ``(rows, cols, vals, deps)`` arrays.
    """
    dep = np.atleast_1d(np.asarray(dia.dependent, dtype=np.int64))
    i = int(dia.independent)
    if np.any(dep == i):
        raise InputError(f"diaphragms[{k}].dependent", i, "nodes other than the independent node")
    n = np.asarray(dia.normal, float)
    n = n / np.linalg.norm(n)
    e1 = np.cross(n, np.eye(3)[int(np.argmin(np.abs(n)))])
    e1 /= np.linalg.norm(e1)
    E = np.vstack([e1, np.cross(n, e1)])  # (2, 3)
    c = int(np.argmax(np.abs(n)))
    ab = [j for j in range(3) if j != c]
    Einv = np.linalg.inv(E[:, ab])  # (2, 2)
    r = x[dep] - x[i]
    # coefficients on the independent node's 6 DOFs and on the dependent node's own component c
    on_i = np.concatenate([np.broadcast_to(Einv @ E, (dep.size, 2, 3)), -np.einsum("ab,bk,nkl->nal", Einv, E, skew(r))],
                          axis=2)  # (nd, 2, 6)
    on_c = -(Einv @ E[:, c])  # (2,)
    for q, comp in enumerate(ab):
        g = on_i[:, q, :]
        nz = np.nonzero(np.abs(g) > 1e-14)
        rows = np.concatenate([6 * dep[nz[0]] + comp, 6 * dep + comp])
        cols = np.concatenate([6 * i + nz[1], 6 * dep + c])
        vals = np.concatenate([g[nz], np.full(dep.size, on_c[q])])
        keep = np.abs(vals) > 1e-14
        yield rows[keep], cols[keep], vals[keep], 6 * dep + comp


def constraint_map(fe: FEModel, extra_fixed: np.ndarray | None = None) -> tuple[sp.csr_matrix, np.ndarray]:
    """Build the sparse constraint map ``T`` (n_dof x nq) and the retained DOF numbers.

    Parameters
    ----------
    fe : the model.
    extra_fixed : optional further DOF numbers to fix (e.g. automatically detected empty DOFs).

    Returns
    -------
    T : CSR (n_dof, nq); column j is the unit motion of retained DOF ``free_dofs[j]`` together
        with the motion it imposes on dependent DOFs.
    free_dofs : (nq,) retained (independent, unconstrained) global DOF numbers, ascending.
    """
    n = fe.n_dof
    fixed = spc_dofs(fe)
    if extra_fixed is not None and len(extra_fixed):
        fixed = np.union1d(fixed, np.asarray(extra_fixed, dtype=np.int64))
    dep, r, c, v = rigid_link_rows(fe)
    both = np.intersect1d(dep, spc_dofs(fe))
    if both.size:
        d = int(both[0])
        raise ModelError(
            f"node {d // 6} component {d % 6} is both a rigid-link dependent DOF and single-point constrained; "
            "constrain the independent node instead")
    is_dep = np.zeros(n, dtype=bool)
    is_dep[dep] = True
    indep = np.nonzero(~is_dep)[0]
    # G: identity on independent DOFs, relation rows on dependent ones
    G = sp.csr_matrix(
        (np.concatenate([np.ones(indep.size), v]), (np.concatenate([indep, r]), np.concatenate([indep, c]))),
        shape=(n, n))
    Tf = G
    for _ in range(64):
        # columns that still refer to dependent DOFs?
        Tc = Tf.tocsc()
        bad = np.diff(Tc.indptr)[dep] if dep.size else np.zeros(0)
        if not np.any(bad):
            break
        Tf = (Tf @ G).tocsr()
        Tf.eliminate_zeros()
    else:
        raise ModelError("rigid links form a cycle (a node depends on itself through a chain of links)")
    keep = np.ones(n, dtype=bool)
    keep[dep] = False
    keep[fixed] = False
    free = np.nonzero(keep)[0]
    T = Tf.tocsc()[:, free].tocsr()
    T.eliminate_zeros()
    return T, free
