"""Modes of the multi-blade system: their eigenvalues, shapes and amplitudes, and their names.

For an eigenpair ``(lambda, x)`` of the first-order system (``x = [q, q', z]``, ``q`` over the
ground-fixed coordinates and the multi-blade coordinates of the blades) :func:`classify` gives the
kinetic-energy shares of the groups (support, drivetrain, blades; diagonal blocks of the mass
matrix), the physical signature that tracking compares (:func:`mode_signature`) and the blade-tip
and tower-top amplitudes in HAWCStab2's terms.  The name -- family, order and whirl -- is the mode's
structural identity, its participation in the turbine's own structural modes
(:mod:`windflutter.system.identity`, :func:`identify_modes`): ``"1st flap BW"``, ``"2nd edge
collective"``, ``"1st tower fore-aft"``, ``"drivetrain"``, ``"2nd edge BW + 2nd tower side-side"``
for a mixed mode.  Whirl: with ``eta_b = eta_c cos psi_b + eta_s sin psi_b`` and ``e^{i omega t}``,
``eta_s = -i eta_c`` is a pattern turning with the rotor (FW, at the rotating-frame frequency +
Omega) and ``eta_s = +i eta_c`` against it (BW, - Omega).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.linalg_tools import mac_matrix
from windflutter.structure.labels import blade_motion_components, frame_components
from windflutter.system.identity import (CONTINUED_MAC, HEAVY_DAMPING, assign, name_record, participations,
                                         point_own_modes)



@dataclass
class ModeRecord:
    """One mode at one operating point (SI inside; Hz at the reporting edge).

    eigenvalue : lambda (1/s).  frequency_hz : undamped ``|lambda| / 2 pi``; damped_frequency_hz :
    ``Im lambda / 2 pi``; damping_ratio : ``-Re lambda / |lambda|``.  shape : the mode's ``q``
    (multi-blade coordinates), unit norm, for tracking.  energy : kinetic-energy shares by group.
    tip : (3, N) complex flap (m), edge (m) and torsion (rad) of the blades' outermost strip in each
    multi-blade coordinate (collective, cosine, sine, ...), for the mode's ``shape`` (None without
    blades), in the blade's pitching frame (flap along its x, downwind; edge along y; torsion about
    the pitch axis z: the undeformed blade axes turned with the pitch, the axes of the steady
    state's tip deflection, not the deflected and elastically twisted tip section's): what
    HAWCStab2's amplitude files give for the blade tip.  tower_top : (6,) complex
    translation (m: along the wind, across it, up) and rotation (rad, about the same axes: roll,
    tilt, yaw) of the tower-top node for the same shape (None without a support).
    """

    eigenvalue: complex
    family: str
    whirl: str
    order: int = 0
    name: str = ""
    shape: np.ndarray | None = field(default=None, repr=False)
    energy: dict = field(default_factory=dict)
    rigid: bool = False
    signature: np.ndarray | None = field(default=None, repr=False)
    tip: np.ndarray | None = field(default=None, repr=False)
    tower_top: np.ndarray | None = field(default=None, repr=False)
    #: the structural identity given (:class:`windflutter.system.identity.Identity`), its share of the
    #: mode's kinetic energy, the two largest participations ``[(name, share), ...]``, and whether
    #: the given identity carries less than ``identity.MIXED_SHARE`` (named by both)
    identity: object = field(default=None, repr=False)
    share: float = float("nan")
    participation: list = field(default_factory=list, repr=False)
    mixed: bool = False
    #: the blade's own modes at this mode's point, named (:class:`windflutter.system.identity.OwnModeNames`):
    #: the next point of a sweep continues their names
    own_modes: object = field(default=None, repr=False)

    @property
    def identity_name(self) -> str:
        """The name of the structural identity given (``"1st flap FW"``), without the second
        participation that :attr:`name` shows for a mixed mode; :attr:`name` without one."""
        return self.identity.name if self.identity is not None else self.name

    @property
    def heavily_damped(self) -> bool:
        """Damping ratio above ``identity.HEAVY_DAMPING`` (0.3): drawn and flagged as such."""
        return self.damping_ratio > 0.3

    @property
    def frequency_hz(self) -> float:
        return float(abs(self.eigenvalue) / (2 * np.pi))

    @property
    def damped_frequency_hz(self) -> float:
        return float(self.eigenvalue.imag / (2 * np.pi))

    @property
    def damping_ratio(self) -> float:
        a = abs(self.eigenvalue)
        return float(-self.eigenvalue.real / a) if a > 0 else 0.0

    def multiblade_components(self) -> dict[str, complex] | None:
        """The complex tip motion in HAWCStab2's multi-blade components: ``sym_edge``, ``bw_edge``,
        ``fw_edge``, ``sym_flap``, ... ``fw_tors`` (m; torsion rad) and, with a support, the tower top
        along and across the wind, ``tower_fa``, ``tower_ss`` (m; HAWCStab2's TWR y and TWR x), and its yaw
        about the vertical ``tower_yaw`` (rad; HAWCStab2's TWR yaw, with z up here): the
        collective ``a_0`` and the whirling parts ``a_c -+ i a_s`` of the first cyclic pair (FW:
        ``a_c + i a_s``, as :func:`classify` names the whirl), without the factor 1/2 that would make
        a blade's whirl amplitude: HAWCStab2's amplitude files count the whirling parts so (against its
        IEA 15 MW files, ours over HAWCStab2's cyclic amplitudes are 0.44-0.49 relative to the
        collective flap or the tower top with the half, 1.06-1.09 for the tower top over the collective:
        ``tests/system/test_hawcstab2_iea15mw.py::test_whirl_amplitudes_count_as_hawcstab2s``).  None
        without blades or with fewer than 3."""
        if self.tip is None or self.tip.shape[1] < 3:
            return None
        a0, ac, as_ = self.tip[:, 0], self.tip[:, 1], self.tip[:, 2]
        out: dict[str, complex] = {}
        if self.tower_top is not None:
            out["tower_fa"], out["tower_ss"] = (complex(x) for x in self.tower_top[:2])
            if self.tower_top.size >= 6:
                out["tower_yaw"] = complex(self.tower_top[5])
        for k, dof in enumerate(("flap", "edge", "tors")):
            out[f"sym_{dof}"] = complex(a0[k])
            out[f"bw_{dof}"] = complex(ac[k] - 1j * as_[k])
            out[f"fw_{dof}"] = complex(ac[k] + 1j * as_[k])
        return out

    def multiblade_amplitudes(self) -> dict[str, float] | None:
        """The magnitudes of :meth:`multiblade_components` (what HAWCStab2's amplitude files give)."""
        c = self.multiblade_components()
        return None if c is None else {k: float(abs(v)) for k, v in c.items()}

    def as_dict(self) -> dict:
        part = [(n, float(x)) for n, x in self.participation] + [("", None)] * (2 - len(self.participation))
        return {"name": self.name, "family": self.family, "order": int(self.order), "whirl": self.whirl,
                "frequency_hz": self.frequency_hz, "damped_frequency_hz": self.damped_frequency_hz,
                "damping_ratio": self.damping_ratio, "share": self.share if np.isfinite(self.share) else None,
                "mixed": bool(self.mixed),
                "heavily_damped": self.heavily_damped,
                "participation_1": part[0][0], "participation_1_share": part[0][1],
                "participation_2": part[1][0], "participation_2_share": part[1][1]}


def rotating_frequency(mode, omega: float) -> float:
    """The mode's damped frequency in the rotating frame (rad/s): ``|w -+ Omega|`` for FW / BW
    (``w = |Im lambda|``, the ground-fixed damped frequency; ``Omega`` = ``omega``, rad/s), ``w`` for
    collective and non-blade modes."""
    w = abs(mode.eigenvalue.imag)
    return abs({"FW": w - omega, "BW": w + omega}.get(mode.whirl, w))


def rotating_damping_ratio(mode, omega: float) -> float:
    """``-Re lambda / |Re lambda + i w_r|`` with ``w_r`` the :func:`rotating_frequency`: the damping
    ratio of the motion the blades see.  A root that is static in the rotating frame (a cyclic blade
    mode growing without oscillating) shows in the ground-fixed frame at the rotor speed, with a
    moderate ground-fixed damping ratio; here it is -1."""
    s = float(mode.eigenvalue.real)
    return -s / max(float(np.hypot(s, rotating_frequency(mode, omega))), 1e-300)


def _block_energy(q: np.ndarray, M: np.ndarray, sl: slice) -> float:
    v = q[sl]
    return float(np.real(np.vdot(v, M[sl, sl] @ v))) if v.size else 0.0


def basis_components(ps) -> np.ndarray:
    """(3, ns, m) flap, edge and torsion (x quarter chord) strip motion of each of the blade's ``m``
    elastic coordinates at the point: its fixed-interface basis vectors, or at full order its
    constrained coordinates themselves; computed once per point (the motion is linear in them)."""
    if ps.basis_components is None:
        T = ps.blade.struct.T
        B = T @ ps.Phi if ps.Phi is not None else T.toarray()
        ps.basis_components = blade_motion_components(ps.blade.sections, np.asarray(B))
    return ps.basis_components


def _blade_components(ps, q_eta: list[np.ndarray]) -> np.ndarray:
    """(3, ns, k) flap, edge and torsion (x quarter chord) motion of the strips for each of the
    ``k`` multi-blade coordinates (blade frame, the blade's fixed-interface deformation)."""
    if ps.Phi is None:  # full order: the nodal motions themselves (no dense copy of T for a shell)
        return blade_motion_components(ps.blade.sections, np.asarray(ps.blade.struct.T @ np.stack(q_eta, 1)))
    return basis_components(ps) @ np.stack(q_eta, 1)


def _tip_components(ps, q_eta: list[np.ndarray]) -> np.ndarray | None:
    """(3, k) tip flap, edge (m) and torsion (rad) of the outermost strip in the blade's pitching
    frame (``ps.tip_frame``) for each of the ``k`` multi-blade coordinates; None without a frame."""
    frame = ps.tip_frame
    if frame is None:
        return None
    rb = ps.blade
    if ps.Phi is None:
        return frame_components(rb.sections, np.asarray(rb.struct.T @ np.stack(q_eta, 1)), frame)
    if ps.tip_basis is None:
        ps.tip_basis = frame_components(rb.sections, np.asarray(rb.struct.T @ ps.Phi), frame)
    return ps.tip_basis @ np.stack(q_eta, 1)


def _unit_block(v: np.ndarray, weight: float) -> np.ndarray:
    v = np.asarray(v, complex).ravel()
    nv = np.linalg.norm(v)
    return v * (np.sqrt(max(weight, 0.0)) / nv) if nv > 0 else v


def mode_signature(ps, q: np.ndarray, energy: dict, comps: np.ndarray | None) -> np.ndarray:
    """A physical description of a mode that does not depend on the reduction bases: the support's
    node motions, the drivetrain coordinates, the strips' motion per multi-blade coordinate; each
    block of unit norm times the square root of its energy share (so MAC weighs them by energy)."""
    mb = ps.mbc
    ns = sum(1 for lb in ps.labels if lb.startswith("support"))
    parts = []
    if ps.support is not None:
        parts.append(_unit_block(ps.support.expand @ q[:ns], energy.get("support", 0.0)))
    parts.append(_unit_block(q[ns:mb.n_fixed], energy.get("drivetrain", 0.0)))
    if comps is not None:
        parts.append(_unit_block(comps * np.sqrt(ps.blade.sections.width)[None, :, None], energy.get("blade", 0.0)))
    return np.concatenate(parts)


def _amplitudes(ps, q: np.ndarray, tip: np.ndarray | None, ns: int) -> dict:
    """``tip`` (:func:`_tip_components` of the mode) and ``tower_top`` of :class:`ModeRecord` for the
    mode ``q`` scaled to unit norm."""
    scale = 1.0 / max(np.linalg.norm(q), 1e-300)
    out = {}
    if tip is not None:
        out["tip"] = tip * scale
    sm = ps.support
    if sm is not None and sm.fe is not None and "tower_top" in sm.fe.node_groups:
        i_top = int(sm.fe.node_groups["tower_top"][0])
        out["tower_top"] = np.asarray(sm.expand[6 * i_top: 6 * i_top + 6] @ q[:ns]).ravel() * scale
    return out


def classify(ps, lam: complex, x: np.ndarray) -> ModeRecord:
    """Energy shares, signature and amplitudes of one eigenpair of ``ps.mbc`` (a :class:`PointSystem`);
    family ``other`` until :func:`identify_modes` names it."""
    mb = ps.mbc
    n = mb.M.shape[0]
    q = x[:n]
    nF, m, N = mb.n_fixed, mb.n_eta, mb.n_blades
    labels = ps.labels
    ns = sum(1 for lb in labels if lb.startswith("support"))
    groups = {"support": _block_energy(q, mb.M, slice(0, ns)),
              "drivetrain": _block_energy(q, mb.M, slice(ns, nF))}
    coords = [slice(nF + j * m, nF + (j + 1) * m) for j in range(N)]
    e_coord = [_block_energy(q, mb.M, s) for s in coords]
    groups["blade"] = float(sum(e_coord))
    tot = max(sum(groups.values()), 1e-300)
    energy = {k: v / tot for k, v in groups.items()}
    shape = q / max(np.linalg.norm(q), 1e-300)
    comps = _blade_components(ps, [q[s] for s in coords]) if m else None
    sig = mode_signature(ps, q, energy, comps)
    tip = _tip_components(ps, [q[s] for s in coords]) if m else None
    rec = {"shape": shape, "energy": energy, "signature": sig, **_amplitudes(ps, q, tip, ns)}
    return ModeRecord(lam, "other", "none", **rec)  # named by identify_modes


def state_eig(mbc) -> tuple:
    """``(eigenvalues, left, right)`` of ``mbc``'s state matrix: the one dense eigen-solve that
    :func:`point_modes` (its ``eig``), the Campbell's refined steps and the design sensitivities'
    :func:`~windflutter.sensitivity.eigen.mode_vectors` can share."""
    import scipy.linalg as sla

    return sla.eig(mbc.state_matrix(), left=True, right=True)


def point_modes(ps, max_hz: float = 2.5, max_damping: float = 0.99, min_structural: float = 0.8,
                previous: list[ModeRecord] | None = None, eig: tuple | None = None) -> list[ModeRecord]:
    """Every oscillatory structural mode of the point up to ``max_hz`` (undamped frequency), named by
    its participation in the turbine's own structural modes (:mod:`windflutter.system.identity`).

    Left out: roots with ``Im lambda <= 0`` (the conjugates), over-damped roots (``zeta >=
    max_damping``) and the aerodynamic lag roots -- real in the rotating frame, ``-beta U/b +- i
    Omega`` for the cyclic states -- recognised by their participation factors ``|u_i v_i|`` (left
    and right eigenvectors, scale-invariant): a mode is structural when the structural states
    ``[q, q']`` carry at least ``min_structural`` of it, or at least half of it and its damped
    frequency is not within 10 % of the rotor speed's multiples (heavily damped flap modes in
    operation share much of themselves with the lag states).  ``previous``: the named modes of the
    previous point of a sweep (wind or rotor speed), whose identities this point continues by the
    similarity of the mode signatures (:func:`windflutter.system.identity.assign`).  ``eig``: the
    ``(eigenvalues, left, right)`` of ``ps.mbc.state_matrix()`` already solved
    (``scipy.linalg.eig(S, left=True, right=True)``, e.g. by the design sensitivities, which need the
    left vectors too); default solved here.
    """
    if eig is None:
        eig = state_eig(ps.mbc)
    lam, UL, X = eig
    n2 = 2 * ps.mbc.M.shape[0]
    part = np.abs(UL.conj() * X)
    share = part[:n2].sum(axis=0) / np.maximum(part.sum(axis=0), 1e-300)
    keep = (lam.imag > 1e-3 * 2 * np.pi) & (np.abs(lam) <= 2 * np.pi * max_hz)
    keep &= (-lam.real < max_damping * np.abs(lam)) & (share >= 0.5)
    # between half and min_structural: heavily damped structural modes (flap in operation), or
    # cyclic aerodynamic lag roots, whose damped frequency is a multiple of the rotor speed
    om = max(ps.omega, 1e-12)
    k = np.arange(1, max(1, (ps.n_blades - 1) // 2) + 1)
    near_kp = np.min(np.abs(lam.imag[:, None] - k[None, :] * om), axis=1) < 0.1 * om
    keep &= (share >= min_structural) | ~near_kp
    idx = np.where(keep)[0]
    idx = idx[np.argsort(np.abs(lam[idx]))]
    modes = [classify(ps, complex(lam[i]), X[:, i]) for i in idx]
    return identify_modes(ps, modes, X[: ps.mbc.M.shape[0], idx], previous)


def identify_modes(ps, modes: list[ModeRecord], Q: np.ndarray, previous: list[ModeRecord] | None = None):
    """Name ``modes`` (their structural coordinates the columns of ``Q``) by their participation in
    the structural identities of ``ps.reference``, in place; returns ``modes``."""

    if not modes:
        return modes
    ref = ps.reference
    own = None
    if ps.mbc.n_eta:
        before = next((m.own_modes for m in previous or () if m.own_modes is not None), None)
        own = point_own_modes(ps, basis_components(ps), ref, previous=before)
    freqs = np.array([m.frequency_hz for m in modes])
    zetas = np.array([m.damping_ratio for m in modes])
    ids, S = participations(ps, Q, own, ref, freqs, zetas)
    cont = None
    if previous:

        by_id = {m.identity: m for m in previous if m.identity is not None and m.signature is not None}
        cols = [k for k, i in enumerate(ids) if i in by_id]
        if cols:
            A = np.stack([m.signature for m in modes], 1)
            B = np.stack([by_id[ids[k]].signature for k in cols], 1)
            cont = np.zeros_like(S)
            cont[:, cols] = mac_matrix(A, B)
    got = assign(S, cont)
    for i, rec in enumerate(modes):
        k = int(got[i])
        continued = cont is not None and k >= 0 and cont[i, k] >= CONTINUED_MAC
        name_record(rec, ids, S[i], k, heavy=bool(zetas[i] > HEAVY_DAMPING), continued=continued)
        rec.own_modes = own.names if own is not None else None
    return modes
