"""Structural damping matrices from the turbine files' data.

* Blades: the stiffness-proportional damping of BeamDyn / windIO (``mu`` per direction,
  :class:`~windflutter.model.blade.BladeDamping`): each beam element's stiffness assembled with the
  section matrix ``sqrt(diag(mu)) S sqrt(diag(mu))`` in place of ``S`` (a congruence: positive
  definite with ``S``, whatever the spread of ``mu``; the coupling terms get the geometric mean of
  their two coefficients; a mode of frequency ``f`` dominated by one direction gets
  ``zeta ~ pi f mu``).  Directions with ``mu = 0`` get :data:`MU_FLOOR` times the largest, so
  that the section matrix stays invertible for the element (their damping is negligible).
* Shell blades (:func:`shell_modal_damping`): modal damping on the blade's lowest
  :data:`SHELL_DAMPED_MODES` fixed-interface modes, ``C = M Phi diag(2 zeta_i omega_i) Phi^T M``,
  each mode getting what the beam's per-direction ``mu`` gives a mode of its character:
  ``zeta_i = omega_i / 2 * sum_d e_id mu_d``, ``e_id`` the share of the mode's kinetic energy in
  direction ``d`` (axial, torsion, edge, flap) of the strips' rigid-section motion
  (:func:`mode_direction_shares`).  (A shell has no per-direction stiffness to scale; one
  ``beta K`` would give every mode the largest bending coefficient: the NREL 5 MW edge +57 %.)
  The matrix is low-rank (:class:`ModalDamping`); it is built once on the pitch-0 blade and turned
  with the nodes (pitch, deflected shape).  Modes above the set get no structural damping.
* Tower: modal ratios (ElastoDyn ``TwrFADmp``/``TwrSSDmp``) as stiffness-proportional damping
  ``beta = zeta_1 / (pi f_1)`` at the support's first mode.
* A file without damping data gives none (the conservative choice); ``damping="none"`` ignores
  what the files give.
* The seed's frozen-azimuth model gives its shell blades the same modal damping: the clamped
  blade's (:func:`shell_modal_damping`) placed on each of its blades (:meth:`ModalDamping.placed`);
  :func:`turbine_damping_matrix` is then the tower's alone.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from windflutter.system.blade_basis import clamped_modes
from windflutter.structure.assembly import assemble_matrices
from windflutter.structure.modal import split_directions, symmetric_eigs


def blade_mu(turbine) -> np.ndarray | None:
    """(6,) stiffness-proportional coefficients (s), BeamSection order, or None."""
    d = getattr(turbine.blade, "damping", None)
    mu = None if d is None else getattr(d, "mu", None)
    if mu is None:
        return None
    mu = np.asarray(mu, float)
    return mu if np.any(mu > 0) else None


#: the smallest coefficient of a direction, relative to the largest (module docstring)
MU_FLOOR = 1e-6


def blade_damping_matrix(fe, mu: np.ndarray | None, K=None) -> sp.csr_matrix | None:
    """Full-numbering damping matrix (N s/m) of the blade elements of ``fe`` for coefficients
    ``mu``; None without coefficients.  ``K``: the shell model's assembled stiffness, reused when
    it has no springs (it is then the elements' stiffness)."""
    if mu is None:
        return None
    mu = np.asarray(mu, float)
    if len(fe.beam_conn):
        r = np.sqrt(np.maximum(mu, MU_FLOOR * mu.max()))
        _, K = assemble_matrices(fe.with_beam_stiffness_scaled(r))
        return sp.csr_matrix(K)
    beta = float(max(mu[4], mu[5]))
    if K is None or len(fe.springs):
        _, K = assemble_matrices(replace(fe, masses=[], springs=[]))
    return sp.csr_matrix(beta * K)


#: fixed-interface modes of a shell blade that get the files' damping (twice the default blade basis)
SHELL_DAMPED_MODES = 40

#: :func:`mode_direction_shares` columns, and the BeamSection index of their coefficient ``mu``
DIRECTIONS = ("axial", "torsion", "edge", "flap")
DIRECTION_MU = (0, 3, 4, 5)


class ModalDamping:
    """A low-rank damping matrix ``C = U diag(c) U^T`` (full numbering, N s/m).

    ``U`` (n_dof, k): ``M Phi`` of mass-normalised modes ``Phi``; ``c`` (k,): ``2 zeta omega``.
    ``zeta``, ``freq_hz`` (k,) and ``shares`` (k, 4, :data:`DIRECTIONS`) record how it was built.
    Supports ``C @ X`` (X dense or sparse, vector or matrix), ``shape`` and ``toarray()``.
    """

    def __init__(self, U, c, zeta=None, freq_hz=None, shares=None):
        self.U = np.asarray(U, float)
        self.c = np.asarray(c, float)
        self.zeta, self.freq_hz, self.shares = zeta, freq_hz, shares

    @property
    def shape(self) -> tuple[int, int]:
        return (self.U.shape[0], self.U.shape[0])

    def __matmul__(self, X):
        Y = self.U.T @ X
        Y = Y.toarray() if sp.issparse(Y) else np.asarray(Y)
        return self.U @ (self.c[:, None] * Y if Y.ndim == 2 else self.c * Y)

    def toarray(self) -> np.ndarray:
        return (self.U * self.c[None, :]) @ self.U.T

    def rotated(self, R: np.ndarray) -> "ModalDamping":
        """The matrix carried by nodal rotations ``R`` ((n, 3, 3), or one (3, 3) for all nodes):
        ``Q C Q^T`` with ``Q`` the block-diagonal of the nodes' rotations on both their
        translations and rotations."""
        U = self.U.reshape(-1, 2, 3, self.U.shape[1])
        R = np.broadcast_to(np.asarray(R, float), (U.shape[0], 3, 3))
        U2 = np.einsum("nab,nkbm->nkam", R, U).reshape(self.U.shape)
        return ModalDamping(U2, self.c, self.zeta, self.freq_hz, self.shares)

    def placed(self, source, x_source, targets, n_nodes: int) -> "ModalDamping":
        """One blade's matrix placed on every blade of another model (``n_nodes`` nodes): ``source``
        the blade's node ids here, ``x_source`` (n, 3) their positions; ``targets`` one ``(ids, x)``
        per blade there, the same nodes in the same order.  Each copy is carried by the rigid motion
        that maps ``x_source`` on ``x`` (:func:`rigid_fit`), so ``C = sum_k Q_k C_b Q_k^T``; the
        copies' columns side by side.  The other nodes here (a clamped hub) must carry no row."""
        U = self.U.reshape(-1, 6, self.U.shape[1])
        source = np.asarray(source, dtype=np.int64)
        rest = np.setdiff1d(np.arange(U.shape[0]), source)
        if rest.size and np.abs(U[rest]).max() > 1e-12 * max(np.abs(U).max(), 1e-300):
            raise ValueError("the blade's damping acts on nodes outside the blade (not a clamped blade)")
        blocks = []
        for ids, x in targets:
            R = rigid_fit(x_source, x)
            Ub = ModalDamping(U[source].reshape(-1, U.shape[2]), self.c).rotated(R).U
            Uk = np.zeros((int(n_nodes), 6, U.shape[2]))
            Uk[np.asarray(ids, dtype=np.int64)] = Ub.reshape(-1, 6, U.shape[2])
            blocks.append(Uk.reshape(-1, U.shape[2]))
        k = len(blocks)
        zeta, freq = (None if a is None else np.tile(a, k) for a in (self.zeta, self.freq_hz))
        return ModalDamping(np.hstack(blocks), np.tile(self.c, k), zeta, freq,
                            None if self.shares is None else np.concatenate([self.shares] * k))


def rigid_fit(a, b, tol: float = 1e-6) -> np.ndarray:
    """The rotation ``R`` (3, 3) of the rigid motion ``b ~ R a + t`` of the point sets ``a``, ``b``
    (n, 3) (least squares: SciPy's ``Rotation.align_vectors`` of the centred sets); ValueError if it
    misses a point by more than ``tol`` of the set's size (the sets are not one body moved)."""
    from scipy.spatial.transform import Rotation

    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape:
        raise ValueError(f"point sets of shapes {a.shape} and {b.shape}")
    pa, pb = a - a.mean(axis=0), b - b.mean(axis=0)
    R = Rotation.align_vectors(pb, pa)[0].as_matrix()
    size = max(np.linalg.norm(pa, axis=1).max(), 1e-300)
    if np.linalg.norm(pa @ R.T - pb, axis=1).max() > tol * size:
        raise ValueError("the point sets are not one body moved rigidly")
    return R


#: cross terms only between modes whose kinetic energy the strips' rigid-section motion carries
#: to within this fraction (the section's own deformation modes have no beam directions)
RIGID_CAPTURE = 0.1


def mode_direction_energies(fe, M, Phi: np.ndarray, sections) -> np.ndarray:
    """(4, k, k) direction terms of the kinetic-energy products of the full-numbering modes ``Phi``
    (n_dof, k), mass ``M``: ``E[d, i, j] = sym(part_d(phi_i)^T M phi_j)``.  ``part_d`` splits each
    strip's rigid-section motion (``sections.motion_map``) in its frame (span ``s``, chord ``c``,
    flapwise ``n = c x s``) into the :data:`DIRECTIONS`: axial ``(u.s) s``, torsion ``(theta.s) s x
    d``, edge ``(u.c) c + (theta.n) n x d`` and flap ``(u.n) n + (theta.c) c x d`` displacements of
    the nodes (``d`` from the strip's point; each node on the strip nearest along the span).  Their
    sum over ``d`` is ``sym(rigid(phi_i)^T M phi_j)``, the identity for modes the strips follow
    rigidly."""
    x = np.asarray(fe.nodes, float)
    p = np.asarray(sections.origin, float)
    s = np.asarray(sections.e_span, float)
    s = s / np.linalg.norm(s, axis=1, keepdims=True)
    c = np.asarray(sections.e_chord, float)
    c = c - np.sum(c * s, axis=1, keepdims=True) * s
    c = c / np.linalg.norm(c, axis=1, keepdims=True)
    n = np.cross(c, s)
    j = np.argmin(np.abs(np.einsum("kjd,jd->kj", x[:, None, :] - p[None], s)), axis=1)
    d = x - p[j]
    Phi = np.asarray(Phi, float)
    q = np.asarray(sections.motion_map @ Phi).reshape(-1, 6, Phi.shape[1])[j]  # (nodes, 6, k)
    g = np.asarray(M @ Phi).reshape(-1, 6, Phi.shape[1])[:, :3]  # nodal inertia forces (nodes, 3, k)
    u, th = q[:, :3], q[:, 3:]

    def along(e, a):  # (e . a) e per node and mode
        return np.einsum("nd,ndk->nk", e, a)[:, None, :] * e[:, :, None]

    def moved(e, a):  # (e . a) e x d
        return np.einsum("nd,ndk->nk", e, a)[:, None, :] * np.cross(e, d)[:, :, None]

    S, C, N = s[j], c[j], n[j]
    parts = (along(S, u), moved(S, th), along(C, u) + moved(N, th), along(N, u) + moved(C, th))
    E = np.stack([np.einsum("ndk,ndl->kl", a, g) for a in parts])
    return 0.5 * (E + np.swapaxes(E, 1, 2))


def mode_direction_shares(energies: np.ndarray) -> np.ndarray:
    """(k, 4) shares of the :data:`DIRECTIONS` in each mode's kinetic energy (the diagonal of
    :func:`mode_direction_energies`), negative parts set to zero and the rest normalised."""
    E = np.maximum(np.einsum("dkk->kd", energies), 0.0)
    return E / np.maximum(E.sum(axis=1, keepdims=True), 1e-300)


def shell_modal_damping(fe, struct, sections, mu: np.ndarray | None,
                        n_modes: int = SHELL_DAMPED_MODES) -> ModalDamping | None:
    """The files' per-direction damping ``mu`` on a shell blade (``fe``, its clamped assembly
    ``struct``, its strips) on its lowest ``n_modes`` fixed-interface modes; None without
    coefficients.  In the modes' coordinates ``D = W S W``, ``W = diag(omega)``: on the diagonal
    ``S_ii = sum_d e_id mu_d`` (the shares, :func:`mode_direction_shares`), so that mode ``i`` gets
    ``zeta_i = omega_i S_ii / 2``; off it the direction terms ``S_ij = sum_d mu_d E_dij /
    sqrt(n_i n_j)`` (:func:`mode_direction_energies`, ``n_i`` the sum of mode ``i``'s kept parts),
    less ``(S_ii + S_jj)/2`` times their sum (which vanishes for modes the strips follow rigidly):
    they vanish when every ``mu_d`` is equal (then ``D = mu W^2``, stiffness-proportional damping
    on the modes) and couple two modes that share directions of different ``mu``, as the beam's
    ``mu`` per direction does; kept only between modes the strips carry (:data:`RIGID_CAPTURE`).
    ``D``'s negative eigenvalues are set to zero."""
    if mu is None:
        return None
    mu = np.asarray(mu, float)
    Mr = sp.csc_matrix(struct.Mr)
    k = int(min(n_modes, Mr.shape[0] - 2))
    w2, X = clamped_modes(struct, k)
    X = X / np.sqrt(np.einsum("im,im->m", X, Mr @ X))
    Phi = np.asarray(struct.T @ X)
    w = np.sqrt(np.maximum(w2, 0.0))
    E = mode_direction_energies(fe, struct.M, Phi, sections)
    shares = mode_direction_shares(E)
    m = mu[list(DIRECTION_MU)]
    norm = np.sqrt(np.maximum(np.einsum("dkk->kd", E), 0.0).sum(axis=1))
    Eh = E / np.maximum(np.outer(norm, norm), 1e-300)[None]
    diag = shares @ m
    ref = 0.5 * (diag[:, None] + diag[None, :])
    S = np.einsum("d,dkl->kl", m, Eh) - ref * Eh.sum(axis=0)
    rigid = np.abs(norm**2 - 1.0) <= RIGID_CAPTURE  # the strips carry the mode: its direction terms hold
    S *= np.outer(rigid, rigid)
    S[np.diag_indices_from(S)] = diag
    lam, V = symmetric_eigs(w[:, None] * S * w[None, :], np.eye(len(w)))  # D = V diag(lam) V^T
    zeta = 0.5 * w * np.diag(S)
    return ModalDamping(np.asarray(struct.M @ Phi) @ V, np.maximum(lam, 0.0), zeta=zeta, freq_hz=w / (2 * np.pi),
                        shares=shares)


def tower_ratios(turbine) -> tuple[np.ndarray, np.ndarray]:
    """``(fore_aft, side_side)`` modal damping ratios (-) of the files, NaN-free (empty if none)."""
    d = getattr(turbine.tower, "damping", None)
    if d is None:
        return np.zeros(0), np.zeros(0)
    fa, ss = (np.atleast_1d(np.asarray(x, float)) for x in (d.fore_aft_ratio, d.side_side_ratio))
    return fa[np.isfinite(fa)], ss[np.isfinite(ss)]


def support_modal_damping(K: np.ndarray, M: np.ndarray, M_rotor: np.ndarray, fa: np.ndarray, ss: np.ndarray,
                          direction_energy, wall=None) -> np.ndarray | None:
    """Modal damping (N s/m) of the support in its coordinates from the files' tower modal ratios.

    The modes are those of the support with the rotor lumped at the hub (``M + M_rotor``), i.e. the
    turbine's tower modes; a mode is fore-aft or side-side by ``direction_energy(v) -> (e_x, e_y)``
    and gets the files' ratio of its order (the last one given for higher orders):
    ``D = M' V diag(2 zeta omega) V^T M'``.  ``wall(V) -> (n,) bool``, optional: the shell tower's
    wall modes (:func:`windflutter.system.reference.tower_wall_waves`), neither fore-aft nor
    side-side: they get the mean of the files' first fore-aft and side-side ratios and take no
    bending mode's order.
    """
    if fa.size == 0 and ss.size == 0:
        return None
    fa = fa if fa.size else ss
    ss = ss if ss.size else fa
    Mt = M + M_rotor
    w2, V = symmetric_eigs(K, Mt)
    V = split_directions(w2, V, direction_energy)
    zeta = np.zeros(w2.size)
    count = {"fa": 0, "ss": 0}
    is_wall = np.zeros(w2.size, bool) if wall is None else np.asarray(wall(V), bool)
    for i in range(w2.size):
        if is_wall[i]:
            zeta[i] = 0.5 * (fa[0] + ss[0])
            continue
        ex, ey = direction_energy(V[:, i])
        key = "fa" if ex >= ey else "ss"
        ratios = fa if key == "fa" else ss
        zeta[i] = ratios[min(count[key], ratios.size - 1)]
        count[key] += 1
    MV = Mt @ V
    return (MV * (2.0 * zeta * np.sqrt(np.maximum(w2, 0.0)))[None, :]) @ MV.T


def tower_ratio(turbine) -> float:
    """First fore-aft / side-side modal damping ratio of the files (-), 0 if none."""
    d = getattr(turbine.tower, "damping", None)
    if d is None:
        return 0.0
    vals = np.concatenate([np.atleast_1d(d.fore_aft_ratio)[:1], np.atleast_1d(d.side_side_ratio)[:1]])
    vals = vals[np.isfinite(vals)]
    return float(vals.mean()) if vals.size else 0.0


def element_subset(fe, prefix: str):
    """``fe`` with only the elements whose region name starts with ``prefix`` (no masses or springs):
    for assembling a damping matrix of one part of a model."""
    names = list(fe.region_names)
    keep = {i for i, nm in enumerate(names) if nm.startswith(prefix)}
    sh = np.isin(np.asarray(fe.element_regions.get("shell", np.zeros(0, int))), list(keep))
    bm = np.isin(np.asarray(fe.element_regions.get("beam", np.zeros(0, int))), list(keep))
    return replace(fe, shell_conn=fe.shell_conn[sh], shell_prop=fe.shell_prop[sh], shell_matdir=fe.shell_matdir[sh],
                   beam_conn=fe.beam_conn[bm], beam_section=fe.beam_section[bm], beam_orient=fe.beam_orient[bm],
                   masses=[], springs=[], element_regions={"shell": fe.element_regions["shell"][sh],
                                                           "beam": fe.element_regions["beam"][bm]})


def turbine_damping_matrix(turbine, struct) -> sp.csr_matrix | None:
    """Full-numbering structural damping of a whole (frozen-azimuth) model from the files: the
    beam blades' ``mu`` on the blade elements (shell blades: none here, their modal damping is
    :meth:`ModalDamping.placed`), the tower's modal ratio as ``beta K`` on the tower
    elements with ``beta = 2 zeta / omega_1`` at the model's first mode; None if the files give none."""
    fe = struct.fe
    blades = element_subset(fe, "blade")
    D = None if len(blades.shell_conn) else blade_damping_matrix(blades, blade_mu(turbine))
    zeta = tower_ratio(turbine)
    if zeta > 0 and "tower" in fe.region_names:
        w2 = symmetric_eigs(struct.Kr.tocsc(), struct.Mr.tocsc(), 1, shift=-1.0, vectors=False)[0][0]
        _, Kt = assemble_matrices(element_subset(fe, "tower"))
        Dt = sp.csr_matrix((2.0 * zeta / np.sqrt(max(w2, 1e-12))) * Kt)
        D = Dt if D is None else (D + Dt).tocsr()
    return D
