"""Structural damping matrices from the turbine files' data.

* Blades: the stiffness-proportional damping of BeamDyn / windIO (``mu`` per direction,
  :class:`~windflutter.model.blade.BladeDamping`): each beam element's stiffness assembled with the
  section matrix ``sqrt(diag(mu)) S sqrt(diag(mu))`` in place of ``S`` (a congruence: positive
  definite with ``S``, whatever the spread of ``mu``; the coupling terms get the geometric mean of
  their two coefficients; a mode of frequency ``f`` dominated by one direction gets
  ``zeta ~ pi f mu``).  Directions with ``mu = 0`` get :data:`MU_FLOOR` times the largest, so
  that the section matrix stays invertible for the element (their damping is negligible).  Shell blades: ``beta K``
  with ``beta`` the larger of the two bending coefficients (the layup has no per-direction split).
* Tower: modal ratios (ElastoDyn ``TwrFADmp``/``TwrSSDmp``) as stiffness-proportional damping
  ``beta = zeta_1 / (pi f_1)`` at the support's first mode.
* A file without damping data gives none (the conservative choice); ``damping="none"`` ignores
  what the files give.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from windflutter.structure.assembly import assemble_matrices
from windflutter.structure.modal import symmetric_eigs


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


def tower_ratios(turbine) -> tuple[np.ndarray, np.ndarray]:
    """``(fore_aft, side_side)`` modal damping ratios (-) of the files, NaN-free (empty if none)."""
    d = getattr(turbine.tower, "damping", None)
    if d is None:
        return np.zeros(0), np.zeros(0)
    fa, ss = (np.atleast_1d(np.asarray(x, float)) for x in (d.fore_aft_ratio, d.side_side_ratio))
    return fa[np.isfinite(fa)], ss[np.isfinite(ss)]


def support_modal_damping(K: np.ndarray, M: np.ndarray, M_rotor: np.ndarray, fa: np.ndarray, ss: np.ndarray,
                          direction_energy) -> np.ndarray | None:
    """Modal damping (N s/m) of the support in its coordinates from the files' tower modal ratios.

    The modes are those of the support with the rotor lumped at the hub (``M + M_rotor``), i.e. the
    turbine's tower modes; a mode is fore-aft or side-side by ``direction_energy(v) -> (e_x, e_y)``
    and gets the files' ratio of its order (the last one given for higher orders, the mean of
    fore-aft and side-side for modes that are neither): ``D = M' V diag(2 zeta omega) V^T M'``.
    """
    if fa.size == 0 and ss.size == 0:
        return None
    fa = fa if fa.size else ss
    ss = ss if ss.size else fa
    Mt = M + M_rotor
    w2, V = symmetric_eigs(K, Mt)
    zeta = np.zeros(w2.size)
    count = {"fa": 0, "ss": 0}
    for i in range(w2.size):
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
    blades' ``mu`` on the blade elements, the tower's modal ratio as ``beta K`` on the tower
    elements with ``beta = 2 zeta / omega_1`` at the model's first mode; None if the files give none."""
    fe = struct.fe
    D = blade_damping_matrix(element_subset(fe, "blade"), blade_mu(turbine))
    zeta = tower_ratio(turbine)
    if zeta > 0 and "tower" in fe.region_names:
        w2 = symmetric_eigs(struct.Kr.tocsc(), struct.Mr.tocsc(), 1, shift=-1.0, vectors=False)[0][0]
        _, Kt = assemble_matrices(element_subset(fe, "tower"))
        Dt = sp.csr_matrix((2.0 * zeta / np.sqrt(max(w2, 1e-12))) * Kt)
        D = Dt if D is None else (D + Dt).tocsr()
    return D
