"""Synthetic shell-like quadratic eigenproblems for tests and benchmarks.

:func:`tube_qep` builds, without any FE library, a problem with the *structure* of the
windflutter shell models: a clamped tube of 4-node quads, 6 DOF per node, so the sparsity
pattern (and hence the LU fill-in) is that of a CQUAD4 shell model of the same size; a
gyroscopic (skew) damping term on the translations; and a complex, element-local "aero" coupling
in ``M``, ``D`` and ``K`` (as the thesis's aero quads produce). It is *not* a physical shell: the
element stiffness is a 6x6 SPD block times the graph Laplacian of the quad, which gives a
cantilever-like spectrum (smooth low modes, clamped ring removes the rigid-body motion) and is
all the performance and model-reduction code needs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError

__all__ = ["TubeQEP", "tube_qep", "demo_point"]


@dataclass
class TubeQEP:
    """A synthetic quadratic eigenproblem ``(lam^2 M + lam D + K) x = 0``.

    Attributes
    ----------
    Ms, Ks
        Real symmetric structural mass and stiffness (CSC), the part a modal basis is built from.
    G
        Real skew-symmetric gyroscopic matrix (CSC).
    Ma, Da, Ka
        Complex element-local coupling matrices (CSC), the "aero" part.
    loads
        Real ``(n, 2)`` load shapes of the coupling (for static-correction modes).
    n_nodes
        Number of free nodes (``n = 6 * n_nodes``).
    """

    Ms: sp.csc_matrix
    Ks: sp.csc_matrix
    G: sp.csc_matrix
    Ma: sp.csc_matrix
    Da: sp.csc_matrix
    Ka: sp.csc_matrix
    loads: np.ndarray
    n_nodes: int

    @property
    def n(self) -> int:
        return self.Ms.shape[0]

    @property
    def M(self) -> sp.csc_matrix:
        """Total mass ``Ms - Ma`` (complex)."""
        return (self.Ms - self.Ma).tocsc()

    @property
    def D(self) -> sp.csc_matrix:
        """Total damping ``Ds + G - Da`` with ``Ds = beta Ks`` (complex)."""
        return (1e-3 * self.Ks + self.G - self.Da).tocsc()

    @property
    def K(self) -> sp.csc_matrix:
        """Total stiffness ``Ks - Ka`` (complex)."""
        return (self.Ks - self.Ka).tocsc()


def _spd6(rng: np.random.Generator, scale: np.ndarray) -> np.ndarray:
    a = rng.standard_normal((6, 6)) * 0.3
    return np.diag(scale) + a @ a.T * np.sqrt(np.outer(scale, scale)) * 0.2


def tube_qep(
    n_around: int = 8,
    n_along: int = 10,
    *,
    coupling: float = 0.05,
    gyro: float = 0.2,
    seed: int = 0,
) -> TubeQEP:
    """Build a clamped-tube shell-like QEP with ``6 * n_around * n_along`` DOF.

    Parameters
    ----------
    n_around
        Nodes around the circumference (>= 3).
    n_along
        Free rings of nodes along the axis (>= 1); ring 0 is clamped and removed.
    coupling
        Size of the complex "aero" coupling relative to the structural matrices (-).
    gyro
        Size of the gyroscopic matrix relative to ``sqrt(k m)`` (-).
    seed
        Random seed (the problem is a deterministic function of the arguments).

    Returns
    -------
    TubeQEP
    """
    if int(n_around) < 3:
        raise InputError("n_around", n_around, "an integer >= 3")
    if int(n_along) < 1:
        raise InputError("n_along", n_along, "an integer >= 1")
    n_around, n_along = int(n_around), int(n_along)
    rng = np.random.default_rng(seed)
    n_rings = n_along + 1
    node = np.arange(n_rings * n_around).reshape(n_rings, n_around)
    # quads (ring j, j+1) x (around i, i+1 mod n_around)
    q0 = node[:-1, :]
    q1 = np.roll(node[:-1, :], -1, axis=1)
    q2 = np.roll(node[1:, :], -1, axis=1)
    q3 = node[1:, :]
    quads = np.stack([q0, q1, q2, q3], axis=-1).reshape(-1, 4)
    ne = quads.shape[0]

    # element matrices: kron(4-node pattern, 6x6 block); one stiffness/mass block per ring so the
    # tube is "tapered" and modes are not degenerate pairs.
    L4 = 4.0 * np.eye(4) - np.ones((4, 4))  # Laplacian of the complete graph K4
    M4 = np.array([[4, 2, 1, 2], [2, 4, 2, 1], [1, 2, 4, 2], [2, 1, 2, 4]], float) / 36.0
    ring_of_el = np.repeat(np.arange(n_along), n_around)
    taper = 1.0 - 0.5 * ring_of_el / max(n_along, 1)
    Sk = _spd6(rng, np.array([1.0, 1.0, 1.0, 0.1, 0.1, 0.1]))
    Sm = np.diag([1.0, 1.0, 1.0, 0.01, 0.01, 0.01])
    Ke = np.kron(L4, Sk)[None] * taper[:, None, None] ** 3
    Me = np.kron(M4, Sm)[None] * taper[:, None, None]
    # complex coupling, element-local (like an aero quad): random complex 6x6 pattern
    A6 = (rng.standard_normal((6, 6)) + 1j * rng.standard_normal((6, 6))) * 0.1
    A6[:, 3:] *= 0.3
    Kae = coupling * np.kron(M4 * 4.0, A6)[None] * taper[:, None, None] ** 2
    Dae = 0.3 * coupling * np.kron(M4 * 4.0, 1j * A6.conj())[None] * taper[:, None, None]
    Mae = 0.05 * coupling * np.kron(M4 * 4.0, np.abs(A6))[None] * taper[:, None, None]

    dof = (6 * quads[:, :, None] + np.arange(6)[None, None, :]).reshape(ne, 24)
    rows = np.repeat(dof, 24, axis=1).ravel()
    cols = np.tile(dof, (1, 24)).ravel()
    n_all = 6 * n_rings * n_around
    free = np.arange(6 * n_around, n_all)  # clamp ring 0

    def assemble(Ae):
        A = sp.coo_matrix((Ae.ravel(), (rows, cols)), shape=(n_all, n_all)).tocsc()
        return A[free][:, free].tocsc()

    Ks = assemble(Ke)
    Ms = assemble(Me)
    Ka = assemble(Kae.astype(complex))
    Da = assemble(Dae.astype(complex))
    Ma = assemble(Mae.astype(complex))
    Ks = ((Ks + Ks.T) * 0.5).tocsc()
    Ms = ((Ms + Ms.T) * 0.5).tocsc()

    # gyroscopic: G = 2 m S(Omega) per node on translations, rotation about the tube axis (x)
    n_free_nodes = n_along * n_around
    mnode = np.asarray(Ms.diagonal()).reshape(n_free_nodes, 6)[:, 0]
    S = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    base = 6 * np.arange(n_free_nodes)
    ii, jj = np.nonzero(S)
    g_rows = (base[:, None] + ii[None, :]).ravel()
    g_cols = (base[:, None] + jj[None, :]).ravel()
    g_vals = (2.0 * gyro * mnode[:, None] * S[ii, jj][None, :]).ravel()
    n = 6 * n_free_nodes
    G = sp.coo_matrix((g_vals, (g_rows, g_cols)), shape=(n, n)).tocsc()

    # load shapes of the coupling: unit "plunge" (uz) and "pitch" (rx) distributions
    loads = np.zeros((n, 2))
    loads[2::6, 0] = 1.0
    loads[3::6, 1] = 1.0
    return TubeQEP(Ms=Ms, Ks=Ks, G=G, Ma=Ma, Da=Da, Ka=Ka, loads=loads, n_nodes=n_free_nodes)


def demo_point(task: dict) -> dict:
    """A stand-in "operating point" for tests and benchmarks of :mod:`windflutter.parallel`.

    Builds :func:`tube_qep` with the task's size and a speed-dependent stiffening
    ``K + speed^2 * 0.3 Ks``, reduces it on ``n_modes`` structural modes and returns the
    ``n_eig`` smallest eigenvalues. Deterministic in ``task``.

    Parameters
    ----------
    task
        ``{"speed": float, "n_around": int, "n_along": int, "n_modes": int, "n_eig": int,
        "repeat": int}``; ``repeat`` re-solves to make the task longer (benchmarks).
        A negative ``speed`` raises :class:`InputError` (to test failure reporting).
    """
    from windflutter.solve.reduction import reduced_eigs, structural_modes

    speed = float(task.get("speed", 0.0))
    if speed < 0:
        raise InputError("speed", speed, "a non-negative rotor speed (rad/s)")
    p = tube_qep(int(task.get("n_around", 4)), int(task.get("n_along", 4)), seed=int(task.get("seed", 0)))
    Kstr = (p.Ks * (1.0 + 0.3 * speed**2)).tocsc()
    K = (Kstr - p.Ka).tocsc()
    for _ in range(max(1, int(task.get("repeat", 1)))):
        b = structural_modes(p.Ms, Kstr, int(task.get("n_modes", 10)))
        lam, _ = reduced_eigs(p.M, p.D, K, b, int(task.get("n_eig", 6)))
    return {"speed": speed, "eigenvalues": lam, "pid": __import__("os").getpid()}
