"""Assembly of the global sparse mass and stiffness matrices and the constraint map.

``assemble(fe)`` returns a :class:`Structural` with the *unconstrained* CSR matrices ``M`` and
``K`` in the full numbering (6 DOF per node, ``6*node + c``), the constraint map ``T`` (u = T q)
and the reduced matrices ``Mr = T^T M T``, ``Kr = T^T K T`` used by the solvers.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError, ModelError
from windflutter.linalg_tools import skew as _skew
from windflutter.structure.beam import beam_global_matrices, element_dofs
from windflutter.structure.constraints import constraint_map
from windflutter.structure.fem import DOF_NAMES, FEModel
from windflutter.structure.linalg import NotPositiveDefinite, SPDFactor
from windflutter.structure.shell import shell_coo


@dataclass
class Structural:
    """Assembled structural model.

    Attributes
    ----------
    fe : the :class:`FEModel` it was assembled from.
    M, K : CSR (n_dof, n_dof) unconstrained mass (kg, kg m, kg m^2) and stiffness matrices.
    T : CSR (n_dof, nq) constraint map, ``u = T q``.
    free_dofs : (nq,) global DOF number of each reduced coordinate q.
    auto_spc : DOF numbers fixed automatically because nothing (no element, mass or spring)
        touches them, e.g. unconnected nodes.
    """

    fe: FEModel
    M: sp.csr_matrix
    K: sp.csr_matrix
    T: sp.csr_matrix
    free_dofs: np.ndarray
    auto_spc: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))

    @property
    def n_dof(self) -> int:
        """Number of DOFs in the full (unconstrained) numbering, 6 per node."""
        return int(self.K.shape[0])

    @property
    def nq(self) -> int:
        """Number of reduced coordinates q."""
        return int(self.T.shape[1])

    def reduce(self, A: sp.spmatrix | np.ndarray) -> sp.csr_matrix | np.ndarray:
        """Reduced matrix ``T^H A T`` (sparse in, CSR out; dense in, dense out)."""
        if A.shape != (self.n_dof, self.n_dof):
            raise InputError("A", A.shape, f"a ({self.n_dof}, {self.n_dof}) matrix in full numbering")
        TH = self.T.T.conj()
        if sp.issparse(A):
            return (TH @ A @ self.T).tocsr()
        return np.asarray(TH @ (self.T.T @ np.asarray(A).T).T)

    def reduce_vector(self, f: np.ndarray) -> np.ndarray:
        """Reduced load ``T^T f`` of a full-numbering load vector (or (n_dof, k) array)."""
        f = np.asarray(f)
        if f.shape[0] != self.n_dof:
            raise InputError("f", f.shape, f"first dimension {self.n_dof}")
        return self.T.T @ f

    def expand(self, q: np.ndarray) -> np.ndarray:
        """Full displacement ``u = T q`` for q of shape (nq,) or (nq, k)."""
        q = np.asarray(q)
        if q.shape[0] != self.nq:
            raise InputError("q", q.shape, f"first dimension {self.nq} (reduced coordinates)")
        return self.T @ q

    @cached_property
    def Kr(self) -> sp.csr_matrix:
        """Reduced stiffness ``T^T K T``."""
        return self.reduce(self.K)

    @cached_property
    def Mr(self) -> sp.csr_matrix:
        """Reduced mass ``T^T M T``."""
        return self.reduce(self.M)

    @property
    def dof_node(self) -> np.ndarray:
        """Node index of each reduced coordinate."""
        return self.free_dofs // 6

    @property
    def dof_component(self) -> np.ndarray:
        """Component (0..5 = ux, uy, uz, rx, ry, rz) of each reduced coordinate."""
        return self.free_dofs % 6

    def dof_labels(self, full: bool = False) -> list[str]:
        """Labels ``"<node>:<ux|uy|uz|rx|ry|rz>"`` of the reduced (or all, if full) DOFs."""
        d = np.arange(self.n_dof) if full else self.free_dofs
        return [f"{i // 6}:{DOF_NAMES[i % 6]}" for i in d]

    def dof_index(self, node: int, component: int | str) -> int:
        """Position in q of a node's component; raises InputError if it is not a free DOF."""
        c = DOF_NAMES.index(component) if isinstance(component, str) else int(component)
        g = 6 * int(node) + c
        j = np.searchsorted(self.free_dofs, g)
        if j >= self.nq or self.free_dofs[j] != g:
            raise InputError("dof", f"{node}:{DOF_NAMES[c]}", "a DOF that is neither constrained nor dependent")
        return int(j)

    def rigid_body_vectors(self, center: np.ndarray | None = None) -> np.ndarray:
        """(n_dof, 6) full-numbering unit rigid motions (3 translations, 3 rotations about center)."""
        return rigid_body_vectors(self.fe.nodes, center)

    def total_mass(self) -> float:
        """Total translational mass (kg) of the unconstrained model."""
        R = self.rigid_body_vectors()
        return float(R[:, 0] @ (self.M @ R[:, 0]))


def rigid_body_vectors(nodes: np.ndarray, center: np.ndarray | None = None) -> np.ndarray:
    """(6n, 6) rigid-body modes of a node set: unit translations then rotations about ``center``."""
    x = np.asarray(nodes, dtype=float)
    c = np.zeros(3) if center is None else np.asarray(center, dtype=float)
    n = x.shape[0]
    R = np.zeros((n, 6, 6))
    R[:, :3, :3] = np.eye(3)
    R[:, 3:, 3:] = np.eye(3)
    # u = theta x (x - c) = -S(x - c) theta
    R[:, :3, 3:] = -_skew(x - c)
    return R.reshape(6 * n, 6)


def coo_matrix_of(mats: np.ndarray, dofs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """COO triplets of element matrices (ne, k, k) with DOF numbers (ne, k)."""
    k = dofs.shape[1]
    r = np.repeat(dofs, k, axis=1).ravel()
    c = np.tile(dofs, (1, k)).ravel()
    return r, c, mats.reshape(-1)


def lumped_mass_matrices(fe: FEModel) -> tuple[np.ndarray, np.ndarray]:
    """6x6 nodal mass matrices (nm, 6, 6) of the lumped masses and their DOFs (nm, 6).

    For mass m with centre offset c from the node and inertia J about its centre:
    ``[[m I, -m S(c)], [m S(c), J - m S(c) S(c)]]`` (velocity of the centre ``v - S(c) w``).
    """
    nm = len(fe.masses)
    out = np.zeros((nm, 6, 6))
    nodes = np.zeros(nm, dtype=np.int64)
    for i, lm in enumerate(fe.masses):
        J = np.asarray(lm.inertia, dtype=float)
        c = np.asarray(lm.offset, dtype=float).reshape(-1)
        if J.shape != (3, 3) or not np.all(np.isfinite(J)) or not np.allclose(J, J.T, atol=1e-12 * max(1.0, np.abs(J).max())):
            raise InputError(f"masses[{i}].inertia", J.tolist() if J.size == 9 else J.shape,
                             "a finite symmetric (3, 3) inertia tensor (kg m^2)")
        if np.linalg.eigvalsh(J).min() < -1e-9 * max(np.abs(J).max(), 1e-300):
            raise InputError(f"masses[{i}].inertia", J.tolist(), "a positive semi-definite inertia tensor")
        if c.shape != (3,) or not np.all(np.isfinite(c)):
            raise InputError(f"masses[{i}].offset", c.tolist(), "a finite 3-vector (m)")
        S = _skew(c)
        m = float(lm.mass)
        out[i, :3, :3] = m * np.eye(3)
        out[i, :3, 3:] = -m * S
        out[i, 3:, :3] = m * S
        out[i, 3:, 3:] = J - m * S @ S
        nodes[i] = lm.node
    return out, element_dofs(nodes[:, None])


def spring_matrices(fe: FEModel) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Grounded (ng, 6, 6) + DOFs and two-node (n2, 12, 12) + DOFs spring matrices."""
    g_k, g_n, t_k, t_n = [], [], [], []
    for i, s in enumerate(fe.springs):
        Ks = np.asarray(s.stiffness, dtype=float)
        if Ks.shape != (6, 6) or not np.all(np.isfinite(Ks)):
            raise InputError(f"springs[{i}].stiffness", Ks.shape, "a finite (6, 6) array (N/m, N, N m/rad)")
        if not 0 <= s.node_a < fe.n_nodes or (s.node_b is not None and not 0 <= s.node_b < fe.n_nodes):
            raise InputError(f"springs[{i}]", (s.node_a, s.node_b), f"node indices in 0..{fe.n_nodes - 1}")
        Ks = 0.5 * (Ks + Ks.T)
        if s.node_b is None:
            g_k.append(Ks)
            g_n.append(s.node_a)
        else:
            t_k.append(np.block([[Ks, -Ks], [-Ks, Ks]]))
            t_n.append((s.node_a, s.node_b))
    gk = np.array(g_k).reshape(-1, 6, 6)
    gd = element_dofs(np.array(g_n, dtype=np.int64).reshape(-1, 1))
    tk = np.array(t_k).reshape(-1, 12, 12)
    td = element_dofs(np.array(t_n, dtype=np.int64).reshape(-1, 2))
    return gk, gd, tk, td


def _given_shell_blocks(fe: FEModel, shell_blocks) -> tuple[np.ndarray, np.ndarray]:
    """The ``shell_blocks`` ``(K, M)`` of :func:`assemble_matrices`, checked against ``fe``."""
    ne = len(fe.shell_conn)
    try:
        K, M = (np.asarray(b, dtype=float) for b in shell_blocks)
    except (TypeError, ValueError):
        raise InputError("shell_blocks", type(shell_blocks).__name__, "a pair (K, M) of element blocks") from None
    for name, B in (("K", K), ("M", M)):
        if B.shape != (ne, 24, 24) or not np.all(np.isfinite(B)):
            raise InputError(f"shell_blocks.{name}", B.shape, f"finite ({ne}, 24, 24) element blocks, one per shell")
    return K, M


def assemble_matrices(fe: FEModel, shell_mass: str = "consistent",
                      shell_blocks=None) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Unconstrained global (M, K) as CSR, summing all element contributions (COO).  ``shell_blocks``:
    the shells' ``(K, M)`` element blocks (ne, 24, 24) given (global axes, DOFs node by node in
    ``fe.shell_conn`` order, e.g. :func:`~windflutter.structure.shell.turned_blocks`) instead of
    pyfe3d's elements on ``fe``'s nodes."""
    fe.check()
    n = fe.n_dof
    kr, kc, kv, mr, mc, mv = [], [], [], [], [], []

    def add(target, mats, dofs):
        if len(mats):
            r, c, v = coo_matrix_of(mats, dofs)
            target[0].append(r)
            target[1].append(c)
            target[2].append(v)

    Kt, Mt = (kr, kc, kv), (mr, mc, mv)
    if len(fe.beam_conn):
        Ke, Me, d = beam_global_matrices(fe)
        add(Kt, Ke, d)
        add(Mt, Me, d)
    if len(fe.shell_conn) and shell_blocks is not None:
        Kb, Mb = _given_shell_blocks(fe, shell_blocks)
        d = element_dofs(np.asarray(fe.shell_conn, dtype=np.int64))
        add(Kt, Kb, d)
        add(Mt, Mb, d)
    elif len(fe.shell_conn):
        (r, c, v), (r2, c2, v2) = shell_coo(fe, mass=shell_mass)
        kr.append(r), kc.append(c), kv.append(v)
        mr.append(r2), mc.append(c2), mv.append(v2)
    if fe.masses:
        Me, d = lumped_mass_matrices(fe)
        add(Mt, Me, d)
    if fe.springs:
        gk, gd, tk, td = spring_matrices(fe)
        add(Kt, gk, gd)
        add(Kt, tk, td)

    def build(r, c, v):
        if not r:
            return sp.csr_matrix((n, n))
        return symmetric_csr(np.concatenate(r), np.concatenate(c), np.concatenate(v), n)

    return build(*Mt), build(*Kt)


#: the last few COO patterns :func:`symmetric_csr` turned into CSR: (rows, cols, n, slot maps, pattern)
_PATTERNS: list = []
_PATTERN_CACHE = 4


def symmetric_csr(r: np.ndarray, c: np.ndarray, v: np.ndarray, n: int) -> sp.csr_matrix:
    """The (n, n) CSR matrix ``(A + A^T) / 2`` of the COO triplets ``(r, c, v)`` (duplicates summed):
    element matrices are symmetric up to round-off, and this makes the assembly exactly symmetric.

    The operating points of a deflected shell re-assemble the same mesh on moved nodes: the same
    triplet pattern with new values.  The map from each triplet to its CSR entry (and to its
    transposed entry) is kept for the last :data:`_PATTERN_CACHE` patterns, compared in full
    (``np.array_equal``) before reuse, so a repeated pattern costs two ``bincount`` calls instead of
    the COO -> CSR conversion, the duplicate sum and the sparse transpose and sum (0.3 s a matrix
    on the IEA 22 MW shell blade).  Entries that sum to exactly zero are dropped, as before."""
    for entry in _PATTERNS:
        r0, c0, n0, slot, tslot, indptr, indices = entry
        if n0 == n and r0.shape == r.shape and np.array_equal(r0, r) and np.array_equal(c0, c):
            nnz = indices.size
            data = 0.5 * (np.bincount(slot, weights=v, minlength=nnz) + np.bincount(tslot, weights=v, minlength=nnz))
            out = sp.csr_matrix((data, indices.copy(), indptr.copy()), shape=(n, n))
            out.eliminate_zeros()
            return out
    # the pattern of A + A^T (SciPy's conversion: sorted indices, duplicates summed), and each
    # triplet's place in it (the keys row * n + col are sorted in CSR order)
    P = sp.coo_matrix((np.ones(2 * r.size), (np.concatenate([r, c]), np.concatenate([c, r]))), shape=(n, n)).tocsr()
    P.sum_duplicates()
    indptr, indices = P.indptr, P.indices
    keys = np.repeat(np.arange(n, dtype=np.int64), np.diff(indptr)) * n + indices
    slot = np.searchsorted(keys, r.astype(np.int64) * n + c).astype(indices.dtype)
    tslot = np.searchsorted(keys, c.astype(np.int64) * n + r).astype(indices.dtype)
    _PATTERNS.insert(0, (r.copy(), c.copy(), n, slot, tslot, indptr, indices))
    del _PATTERNS[_PATTERN_CACHE:]
    return symmetric_csr(r, c, v, n)


def assemble(fe: FEModel, check: bool = True, shell_mass: str = "consistent", allow_rigid: bool = False,
             shell_blocks=None) -> Structural:
    """Assemble a :class:`FEModel` into a :class:`Structural`.

    Parameters
    ----------
    fe : the model (validated with ``fe.check()``).
    check : if True (default) raise :class:`ModelError` when the constrained model still has
        rigid-body motion (a mechanism or a missing support), see :func:`check_constrained`.
    shell_mass : "consistent" (default) or "lumped" shell mass matrix.
    allow_rigid : accept a model with no free DOF left (a rigid substructure, e.g. a rigid blade
        tied to a clamped hub); the default refuses it.
    shell_blocks : the shells' ``(K, M)`` element blocks given (:func:`assemble_matrices`).

    Returns
    -------
    Structural
    """
    if shell_mass not in ("consistent", "lumped"):
        raise InputError("shell_mass", shell_mass, "'consistent' or 'lumped'")
    M, K = assemble_matrices(fe, shell_mass=shell_mass, shell_blocks=shell_blocks)
    T, free = constraint_map(fe)
    # DOFs that nothing touches (unconnected nodes, unused rotations of point masses...)
    Kr = (T.T @ K @ T).tocsr()
    Mr = (T.T @ M @ T).tocsr()
    empty = np.nonzero((np.abs(Kr.diagonal()) == 0) & (np.abs(Mr.diagonal()) == 0))[0]
    auto = free[empty]
    if auto.size:
        T, free = constraint_map(fe, extra_fixed=auto)
    st = Structural(fe=fe, M=M, K=K, T=T, free_dofs=free, auto_spc=auto)
    if not auto.size:  # reuse the reduced matrices (cached_property storage)
        st.__dict__["Kr"], st.__dict__["Mr"] = Kr, Mr
    if st.nq == 0 and not allow_rigid:
        raise ModelError("the model has no free degrees of freedom after constraints")
    if check and st.nq:
        check_constrained(st)
    return st


def check_constrained(st: Structural, max_ratio: float = 1e10) -> None:
    """Raise :class:`ModelError` if the reduced stiffness is singular (rigid-body motion).

    Uses the pivots of a Cholesky factorisation (CHOLMOD, or SuperLU with diagonal pivoting as
    fallback) of ``Kr``: a rigid-body mode shows as a pivot that is zero, negative or
    ``max_ratio`` times smaller than the matrix diagonal entry of its DOF (NASTRAN's MAXRATIO
    check; a genuine elastic structure gives ratios far below 1e10 in double precision).
    """
    Kr = st.Kr.tocsc()
    diag = Kr.diagonal()
    zero_k = np.nonzero(diag <= 0)[0]
    if zero_k.size:
        _raise_rbm(st, zero_k[:5], "have no stiffness")
    try:
        fac = SPDFactor(Kr)
    except NotPositiveDefinite:
        _raise_rbm(st, np.zeros(0, dtype=np.int64), "make the stiffness matrix singular or indefinite")
    ratio = diag[fac.pivot_dofs] / fac.pivots
    bad = np.nonzero(ratio > max_ratio)[0]
    if bad.size:
        _raise_rbm(st, fac.pivot_dofs[bad[:5]], f"give pivot ratios up to {ratio[bad].max():.3g} (> {max_ratio:g})")


def _raise_rbm(st: Structural, q_idx: np.ndarray, what: str) -> None:
    labels = ", ".join(f"node {st.free_dofs[j] // 6} {DOF_NAMES[st.free_dofs[j] % 6]}" for j in q_idx)
    raise ModelError(
        "the structure is not sufficiently constrained (rigid-body motion or a mechanism): "
        f"degrees of freedom {labels or '(unknown)'} {what}; add supports (spc), springs or connections")
