"""Mode identity from the turbine's own structural modes: what every aeroelastic mode *is*.

The names a Campbell diagram is read by are the structural modes an engineer knows: the blade's
1st flap, 1st edge, 2nd flap, ..., 1st torsion (each as collective, backward- or forward-whirling
rotor mode), the tower's fore-aft and side-side modes, the drivetrain's shaft torsion.  They are
defined here once per turbine, from the parts' own modes, and each aeroelastic mode is named by its
participation in them -- not by the geometry of its eigenvector and its frequency order at the
point, which fail at high pitch, high damping and strong coupling.

1. **Reference** (:class:`~windflutter.system.reference.StructuralReference`, once per model, in
   :mod:`windflutter.system.reference`): the blade's structural modes at
   standstill, without aerodynamics, in its own (pitching) frame; each named by its largest strip
   motion -- flap, edge or torsion (:func:`windflutter.structure.labels.blade_motion_components`) --
   and ordered in frequency within its family.  The support's modes (the support alone), named fore-
   aft / side-side / torsion by their motion.
2. **The point's own modes**: the blade's structural modes at the operating point -- rotating, with
   the steady state's stress and deflection, still without aerodynamics (``ps.blade_structure``) --
   each given the name of the reference mode it continues, by an assignment of the MAC of their
   strip motions (a comparison that does not depend on the reduction basis or the pitch).
3. **Participation**: an aeroelastic mode's blade coordinates, in each multi-blade coordinate, are
   expanded in the point's own modes (mass-orthogonal: the energies add up exactly); with ``a_0,
   a_c, a_s`` the collective and first cyclic amplitudes of own mode ``j`` the parts are ``N
   |a_0|^2`` (collective), ``N/4 |a_c + i a_s|^2`` (forward whirl, FW) and ``N/4 |a_c - i a_s|^2``
   (backward whirl, BW), weighted by ``omega_j^2``: shares of the modal strain energy (of the
   kinetic energy for modes damped above :data:`KINETIC_DAMPING`, :func:`participations`).  The
   support's coordinates are expanded in its modes, the drivetrain's in its rigid rotation and its
   shaft torsion.
4. **Assignment**: the identities are given to the point's aeroelastic modes by the assignment of
   largest total share (Hungarian algorithm), so a name is used once per operating point, and a
   crossing or veering keeps the names by participation; along a sweep continuation keeps a name on
   its branch, but where modes exchange character it moves with the content (:func:`exchanges`).  A
   mode whose assigned identity carries less than :data:`MIXED_SHARE` of it is *mixed* and named by
   its two largest participations (``"2nd edge BW + 2nd tower side-side"``), not guessed.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from windflutter.linalg_tools import mac_matrix
from windflutter.structure.labels import ordinal
from windflutter.structure.modal import degenerate_groups, symmetric_eigs
from windflutter.system.reference import StructuralReference, strip_family, strip_signatures

#: a mode whose assigned identity carries less than this share of its kinetic energy is reported as
#: mixed, with its two largest participations
MIXED_SHARE = 0.6
#: a point mode continues a reference mode only with at least this MAC of their strip motions
REFERENCE_MAC = 0.3
#: an assigned identity carrying less than this share of a mode (for a heavily damped mode, or less
#: than half of its largest participation) is not given to it (the identities that fit it are taken
#: by modes that fit them better): the mode is named by its two largest participations, as mixed
MIN_ASSIGNED_SHARE = 0.1
#: a share at or below this is round-off, reported as no second participation (the uncoupled wall
#: modes of a shell tower had a "second participant" of share 1e-25, a different one in every run)
NO_SHARE = 1e-12
#: along a sweep, a mode that continues the previous point's carrier of an identity (MAC of their
#: signatures at least this) keeps that identity whatever its share (reported mixed, with its largest
#: participation): a mode whose own part fades as it couples keeps its name, as HAWCStab2's
#: continuation keeps it (the IEA 15 MW's tower torsion, 16-27 % damped at 16-25 m/s, its kinetic
#: energy more and more the blades' flap) -- unless it moves in an exchange (:func:`exchanges`)
CONTINUED_MAC = 0.8
#: along a sweep, a continued own-mode name is given back to the reference (:func:`reanchor`) when
#: another own mode resembles the name's reference mode (standstill shape) with a MAC of at least this
#: (:data:`REFERENCE_MAC`: the least resemblance that names a mode afresh) and ...
REANCHOR_MAC = REFERENCE_MAC
#: ... the carrier's MAC with it is at most this fraction of that one (hysteresis: through a veering's
#: mixed middle, where both resemble it about alike, the name stays where continuation put it; in a
#: two-mode veering it moves once the carrier has less than 20 % of the content)
REANCHOR_RATIO = 0.25
#: the drivetrain's rigid-body rotation is an identity only for roots below this frequency (Hz)
RIGID_HZ = 0.15
#: a heavily damped mode (drawn and flagged as such)
HEAVY_DAMPING = 0.3
#: modes damped above this are named by their kinetic, not strain, energy (aerodynamically damped flap)
KINETIC_DAMPING = 0.15
TOWER_NAMES = {"tower_fa": "tower fore-aft", "tower_ss": "tower side-side", "tower_torsion": "tower torsion"}


@dataclass(frozen=True)
class Identity:
    """One structural identity: ``family`` (flap, edge, torsion, tower_fa, tower_ss, tower_torsion,
    drivetrain, rigid; buckling: an own mode of the prestressed blade that is statically unstable
    without aerodynamics -- a local buckling of a shell mesh --, never an aeroelastic instability),
    ``order`` (1st, 2nd ...; 0 for the drivetrain's), ``whirl`` (collective, BW,
    FW, asymmetric for blade modes; none otherwise); ``wave``: the circumferential wave number of a
    shell tower's wall mode (family ``tower_wall``, ordered within its wave number), -1 otherwise."""

    family: str
    order: int
    whirl: str = "none"
    wave: int = -1

    @property
    def name(self) -> str:
        return identity_name(self.family, self.whirl, self.order, self.wave)


@functools.lru_cache(maxsize=1024)
def identity_name(family: str, whirl: str, order: int, wave: int = -1) -> str:
    """``"1st flap BW"``, ``"2nd tower side-side"``, ``"1st tower wall n=2"``, ``"drivetrain"``,
    ``"drivetrain rigid-body"`` (a few dozen distinct names, asked for thousands of times along a
    sweep: made once each)."""
    if family == "tower_wall":
        return f"{ordinal(order)} tower wall n={wave}"
    if family in TOWER_NAMES:
        return f"{ordinal(order)} {TOWER_NAMES[family]}"
    if family == "drivetrain":
        return "drivetrain"
    if family == "rigid":
        return "drivetrain rigid-body"
    if family == "other":
        return f"other {order}" if order else "other"
    if family == "buckling":
        return "blade structure unstable" + (f" {order}" if order > 1 else "")
    return f"{ordinal(order)} {family} {whirl}".rstrip()


# ------------------------------------------------------------------------------------------------
# 2. the point's own blade modes, named by the reference
# ------------------------------------------------------------------------------------------------
@dataclass
class OwnModeNames:
    """The names of the blade's own modes at a point: ``sig`` (k, r) their strip signatures and
    ``ident`` (r,) the (family, order) each continues -- what the next point of a sweep continues."""

    sig: np.ndarray
    ident: list


@dataclass
class PointOwnModes:
    """The blade's own modes at an operating point: ``V`` (m, r) M-orthonormal on the blade's elastic
    coordinates, ``Me`` their mass, ``ident`` (r,) the (family, order) each continues, ``names`` the
    signatures and names a next point continues."""

    V: np.ndarray
    Me: np.ndarray
    ident: list
    w2: np.ndarray | None = None
    names: OwnModeNames | None = None


def _continued(previous: OwnModeNames | None, sig: np.ndarray) -> list:
    """(r,) the names of the previous point's own modes that these (signatures ``sig``) continue by
    an assignment of the MAC of their strip motions, where it is at least :data:`CONTINUED_MAC`
    (None elsewhere and for a previous local buckling)."""
    ident: list = [None] * sig.shape[1]
    if previous is None:
        return ident
    mac = mac_matrix(previous.sig, sig)
    for r, c in zip(*linear_sum_assignment(-mac)):
        if mac[r, c] >= CONTINUED_MAC and previous.ident[r] is not None and previous.ident[r][0] != "buckling":
            ident[c] = previous.ident[r]
    return ident


def reanchor(ident: list, mac: np.ndarray, reference: StructuralReference) -> list:
    """The continued names ``ident`` (r,) (None where not continued) given back to the reference:
    a name ``(family, order)`` moves from its carrier ``c`` to the own mode ``j`` that resembles its
    reference mode best (``mac`` (n_ref, r): MAC of the reference's strip signatures with the own
    modes') when ``mac[ref, j] >= REANCHOR_MAC``, ``mac[ref, c] <= REANCHOR_RATIO * mac[ref, j]``
    and ``j`` resembles it more than the reference mode of the name it carries; ``c`` and ``j``'s
    former name are left to the reference assignment.  Strongest moves first, one per own mode.

    Continuation (previous point's MAC) follows a branch through a veering: after a local mode (a
    shell's tip panel) has crossed and mixed with the 1st torsion, the branch named 1st torsion is the
    local mode and the torsion is on the other branch.  The reference's shape is what the name means;
    the hysteresis keeps the continued name through the mixed middle and where the deflection makes
    two modes resemble the reference mode alike."""
    out = list(ident)
    row = {(fam, order): k for k, (fam, order, _) in enumerate(reference.blade)}
    moves = []
    for c, x in enumerate(ident):
        k = row.get(x)
        if k is None:
            continue
        others = [j for j in range(len(ident)) if j != c]
        if not others:
            continue
        j = max(others, key=lambda j: mac[k, j])
        own_k = row.get(ident[j])
        if (mac[k, j] >= REANCHOR_MAC and mac[k, c] <= REANCHOR_RATIO * mac[k, j]
                and (own_k is None or mac[k, j] > mac[own_k, j])):
            moves.append((mac[k, j], c, j, x))
    moved: set = set()
    for _, c, j, x in sorted(moves, key=lambda m: -m[0]):
        if c in moved or j in moved or out[c] != x:
            continue
        out[c], out[j] = None, x
        moved.update((c, j))
    return out


def point_own_modes(ps, basis_components: np.ndarray, reference: StructuralReference,
                    previous: OwnModeNames | None = None) -> PointOwnModes:
    """The blade's structural modes at the point (rotating, steady stress, no aerodynamics) named by
    the previous point's own modes they continue (``previous``, along a sweep: the deflection changes
    them little from one point to the next) and otherwise by the reference modes they continue
    (assignment of the MAC of their strip motions)."""
    M, K = ps.blade_structure
    e = slice(6, None)
    Me = 0.5 * (M[e, e] + M[e, e].T)
    w2, V = symmetric_eigs(K[e, e], Me)
    comps = basis_components @ V
    sig = strip_signatures(ps.blade.sections, comps)
    mac = mac_matrix(reference.signatures, sig)
    ident = reanchor(_continued(previous, sig), mac, reference)
    taken = {i for i in ident if i is not None}
    rows_free = [r for r, (fam, order, _) in enumerate(reference.blade) if (fam, order) not in taken]
    cols_free = [c for c in range(len(ident)) if ident[c] is None]
    if rows_free and cols_free:
        sub = mac[np.ix_(rows_free, cols_free)]
        for i, j in zip(*linear_sum_assignment(-sub)):
            if sub[i, j] >= REFERENCE_MAC:
                fam, order, _ = reference.blade[rows_free[i]]
                ident[cols_free[j]] = (fam, order)
    # an own mode left without a reference (MAC below REFERENCE_MAC after the assignment): the unused
    # reference mode it resembles most in shape and frequency (MAC / (1 + |ln(f / f_ref)|)), else an
    # ordinal after the reference's in its own strip family (an own mode above the reference's range)
    fams = strip_family(ps.blade.sections, comps)
    used = {ident[c] for c in range(len(ident)) if ident[c] is not None}
    top: dict = {}
    for fam, order, _ in reference.blade:
        top[fam] = max(top.get(fam, 0), order)
    n_unstable = 0
    for c in np.argsort(w2):
        if w2[c] < 0:  # the prestressed blade statically unstable without aerodynamics (a local buckling)
            n_unstable += 1
            ident[c] = ("buckling", n_unstable)
            continue
        if ident[c] is not None:
            continue
        free = [r for r, (fam, order, _) in enumerate(reference.blade) if (fam, order) not in used]
        if free:  # the closest in shape and frequency (the deflection couples e.g. the 1st torsion with the 3rd edge)
            f_c = np.sqrt(max(w2[c], 0.0)) / (2 * np.pi)
            r = max(free, key=lambda r: mac[r, c] / (1.0 + abs(np.log(max(f_c, 1e-9) / reference.blade[r][2]))))
            ident[c] = reference.blade[r][:2]
        else:
            top[fams[c]] = top.get(fams[c], 0) + 1
            ident[c] = (fams[c], top[fams[c]])
        used.add(ident[c])
    return PointOwnModes(V=V, Me=Me, ident=ident, w2=w2, names=OwnModeNames(sig=sig, ident=list(ident)))


# ------------------------------------------------------------------------------------------------
# 3. participation of each aeroelastic mode in the identities
# ------------------------------------------------------------------------------------------------
def participations(ps, Q: np.ndarray, own: PointOwnModes | None, reference: StructuralReference,
                   frequencies_hz: np.ndarray, damping_ratios: np.ndarray | None = None
                   ) -> tuple[list[Identity], np.ndarray]:
    """``(identities, S)``: ``S[i, k]`` the share of the strain energy of mode ``i`` (column ``i``
    of ``Q``, the structural coordinates of ``ps.mbc``) in identity ``k`` (modal strain energy).

    Strain, not kinetic, energy: the blade coordinates are deformations relative to the hub, so that
    in a mode that moves the hub above the blade's 1st flap frequency (a 2nd or 3rd tower mode, a
    whirling 3rd edge mode) the blades, left behind by the moving hub, carry a large relative kinetic
    energy in their 1st flap shape (the shape with the largest base-motion participation) but little
    strain.  Each part's strain energy is ``sum_j omega_j^2 |a_j|^2`` over its own modes
    (frequencies ``omega_j``, mass-normalized amplitudes ``a_j``); the drivetrain's that of its shaft
    spring; its rigid rotation (an identity only below :data:`RIGID_HZ`, where every share is a
    kinetic one, below) counts with its kinetic energy.  A heavily damped mode (70 % flap in operation) spreads its strain over
    neighbouring modes of its family (its quasi-static response to the aerodynamic load, weighted up by
    their stiffness): for modes damped above :data:`KINETIC_DAMPING` (``damping_ratios``) the shares are
    those of the modal kinetic energies ``|a_j|^2`` instead -- heavy aerodynamic damping is the blades'
    flap, with little hub motion.  So are a root's below :data:`RIGID_HZ` (whatever its damping; the
    rotor-speed root, unstable where the aerodynamic torque rises with the rotor speed, included): the
    blades' deformation is quasi-static there too."""
    mb = ps.mbc
    nF, m, N = mb.n_fixed, mb.n_eta, mb.n_blades
    labels = ps.labels
    ns = sum(1 for lb in labels if lb.startswith("support"))
    w = 2 * np.pi * np.asarray(frequencies_hz, float)
    heavy = np.zeros(Q.shape[1], bool) if damping_ratios is None else np.asarray(damping_ratios) > KINETIC_DAMPING
    # a root below RIGID_HZ is quasi-static for every elastic mode: its blades' deformation is their
    # static response to its loads, as a heavily damped mode's, and its strain says nothing of what
    # moves (the rotor-speed root, all of its kinetic energy in the rotor's rotation, had 80 % of its
    # strain in the 1st flap collective on the IEA 22 MW shell at 6 m/s, 8 RPM, and passed for it)
    heavy |= w < 2 * np.pi * RIGID_HZ
    ids: list[Identity] = []
    cols: list[np.ndarray] = []
    twins: list = []
    if ns and reference.Phi_s is not None:  # support: its own modes
        a = reference.Phi_s.T @ (0.5 * (ps.support.M + ps.support.M.T)) @ Q[:ns]
        ws = 2 * np.pi * np.array([f for _, _, f in reference.support])
        waves = reference.support_wave if reference.support_wave is not None else np.full(len(ws), -1)
        for k, (fam, order, _) in enumerate(reference.support):
            ids.append(Identity(fam, order, wave=int(waves[k])))
            cols.append(np.where(heavy, 1.0, ws[k] ** 2) * np.abs(a[k]) ** 2)
        twins = _wall_pairs(ids, ws)
    dt = [i for i, lb in enumerate(labels) if lb in ("azimuth", "generator")]
    if dt:  # drivetrain: rigid rotation and shaft torsion
        qd = Q[dt]
        Md = mb.M[np.ix_(dt, dt)]
        Md = 0.5 * (Md + Md.T)
        r = np.ones(len(dt))
        mr = r @ Md @ r
        e_rig = np.abs((r @ Md @ qd) / mr) ** 2 * mr  # kinetic: it counts only where ``heavy`` holds
        ids.append(Identity("rigid", 0))
        cols.append(np.where(w < 2 * np.pi * RIGID_HZ, e_rig, 0.0))
        if len(dt) > 1 and ps.fixed is not None:
            Kd = ps.fixed.K[np.ix_(dt, dt)]
            ids.append(Identity("drivetrain", 0))
            e_k = np.abs(np.real(np.einsum("ij,ik,kj->j", qd.conj(), 0.5 * (Kd + Kd.T), qd)))
            e_m = np.maximum(np.real(np.einsum("ij,ik,kj->j", qd.conj(), Md, qd)) - e_rig, 0.0)
            cols.append(np.where(heavy, e_m, e_k))
    if m and own is not None:  # blades: the point's own modes, per multi-blade coordinate
        wj2 = np.where(heavy[None, :], 1.0, np.abs(own.w2)[:, None])
        A = [own.V.T @ (own.Me @ Q[nF + j * m: nF + (j + 1) * m]) for j in range(N)]
        e = {"collective": N * np.abs(A[0]) ** 2}
        if N >= 3:
            e["FW"] = N / 4 * np.abs(A[1] + 1j * A[2]) ** 2
            e["BW"] = N / 4 * np.abs(A[1] - 1j * A[2]) ** 2
        rest = sum((np.abs(x) ** 2 for x in A[3 if N >= 3 else 1:]), np.zeros_like(A[0], float))
        if np.any(rest):
            e["asymmetric"] = N / 2 * rest
        e = {k: wj2 * v for k, v in e.items()}
        known = {(fam, order) for fam, order, _ in reference.blade} | {x for x in own.ident if x[0] == "buckling"}
        residual = np.zeros(Q.shape[1])
        for j, (fam, order) in enumerate(own.ident):
            for wh, ew in e.items():
                if (fam, order) not in known:  # above the reference's range (and the basis's static
                    residual += ew[j]         # corrections): counted, never a name
                    continue
                ids.append(Identity(fam, order, wh))
                cols.append(ew[j])
        cols.append(residual)
    S = np.stack(cols, axis=1) if cols else np.zeros((Q.shape[1], 1))
    tot = S.sum(axis=1, keepdims=True)
    S = (S / np.maximum(tot, 1e-300))[:, :len(ids)]
    for group in twins:
        S[:, group] = S[:, group].sum(axis=1, keepdims=True)
    return ids, S


def _wall_pairs(ids: list, ws: np.ndarray) -> list:
    """The degenerate groups (index lists, :func:`~windflutter.structure.modal.degenerate_groups`) of
    the shell tower wall's reference modes (``ids``' first ``len(ws)`` entries, frequencies ``ws``),
    one per wave number.  The solver returns a pair (the wave's cos and sin, no preferred direction)
    in any rotation, and at an operating point the pair is still degenerate, its two modes any
    rotation of it: each member's share is the pair's (both members' identities fit both modes alike,
    the assignment gives one to each), so which rotation either run's solver returned decides no name
    and no share."""
    out = []
    for group in degenerate_groups(np.asarray(ws) ** 2):
        walls: dict = {}
        for k in group:
            if ids[k].family == "tower_wall":
                walls.setdefault(ids[k].wave, []).append(k)
        out += [g for g in walls.values() if len(g) > 1]
    return out


# ------------------------------------------------------------------------------------------------
# 4. assignment
# ------------------------------------------------------------------------------------------------
def continues(S: np.ndarray, continuity: np.ndarray) -> np.ndarray:
    """(n_modes, n_ids) where a mode continues the previous point's carrier of an identity (similarity
    at least :data:`CONTINUED_MAC`) and the identity's content has not moved to another mode of the
    point: no other mode carries at least :data:`MIN_ASSIGNED_SHARE` of it while this one carries at
    most :data:`REANCHOR_RATIO` of that (the hysteresis of :func:`reanchor`)."""
    if S.shape[0] < 2:
        return continuity >= CONTINUED_MAC
    top = np.sort(S, axis=0)
    other = np.where(S >= top[-1], top[-2], top[-1])  # each mode's largest share of the identity elsewhere
    moved = (other >= MIN_ASSIGNED_SHARE) & (S <= REANCHOR_RATIO * other)
    return (continuity >= CONTINUED_MAC) & ~moved


def _largest_total(C: np.ndarray) -> np.ndarray:
    out = np.full(C.shape[0], -1)
    if C.size:
        rows, cols = linear_sum_assignment(-C)
        out[rows] = cols
    return out


def exchanges(kept: np.ndarray, fresh: np.ndarray, S: np.ndarray) -> np.ndarray:
    """``kept`` (identity index per mode, -1 none) with the exchanges of ``fresh`` taken: closed cycles
    in which modes pass their ``kept`` identities round among themselves, each taking one it is made
    of (at least :data:`MIN_ASSIGNED_SHARE` of it in ``S``) -- a veering's exchange of character.
    Elsewhere ``kept``: a change that would leave an identity to no mode, take one no mode had, or put
    one on a mode with next to none of it is not an exchange."""
    owner = {int(k): i for i, k in enumerate(kept) if k >= 0}
    out = kept.copy()
    for i in np.flatnonzero(kept != fresh):
        cycle, j = [int(i)], owner.get(int(fresh[i]))
        while j is not None and j not in cycle:
            cycle.append(j)
            j = owner.get(int(fresh[j]))
        if j == i and all(S[c, fresh[c]] >= MIN_ASSIGNED_SHARE for c in cycle):
            out[cycle] = fresh[cycle]
    return out


def assign(S: np.ndarray, continuity: np.ndarray | None = None, weight: float = 0.2) -> np.ndarray:
    """(n_modes,) the identity index given to each mode (largest total share, one identity per mode;
    -1 for none); ``continuity`` (n_modes, n_ids), optional, adds ``weight`` times each mode's
    similarity to the mode that carried the identity at the previous point of a sweep -- where the
    identity has at least :data:`MIN_ASSIGNED_SHARE` of the mode, or the mode continues that carrier
    (similarity at least :data:`CONTINUED_MAC`): continuity chooses among the identities a mode can
    carry and keeps a continued one; it does not pull a name onto a mode that is neither made of it
    nor its continuation.  The weight is small (0.2), a tie-breaker: through a veering, where two
    modes exchange character, the names follow the participation, not the branch (with 0.5 the IEA
    15 MW's 1st torsion FW and 3rd tower fore-aft had kept the branch's names at 13-21 m/s, the
    tower's name on a mode with 18 % tower and 24 % torsion).

    A veering spread over many wind speeds keeps every step's similarity high while the two modes
    exchange character, so continuation alone would keep the branch's names to the end (the IEA 22
    MW shell's "1st torsion FW" at 10 m/s on a 4.08 Hz mode of 52 % 4th flap FW, while the 3.76 Hz
    mode carried 28 % of the torsion).  So the assignment is made twice, the second time without the
    continuation of identities whose content has moved (:func:`continues`), and the second one's
    closed exchanges are taken (:func:`exchanges`): the modes swap names, each taking one it is made of.
    A continued name whose content has only spread (the IEA 15 MW's tower torsion at 19-25 m/s, a
    12-16 % damped mode that HAWCStab2 continues as one; at 22 m/s the second assignment would have
    put it on a 2.5 Hz flap mode with less than 10 % of it) stays."""
    if continuity is None:
        return _largest_total(S)
    made_of = S >= MIN_ASSIGNED_SHARE
    kept = _largest_total(S + weight * np.where(made_of | (continuity >= CONTINUED_MAC), continuity, 0.0))
    fresh = _largest_total(S + weight * np.where(made_of | continues(S, continuity), continuity, 0.0))
    return exchanges(kept, fresh, S)


def name_record(rec, ids: list[Identity], shares: np.ndarray, k: int, heavy: bool = False,
                continued: bool = False) -> None:
    """Give mode record ``rec`` the identity ``ids[k]`` (its shares ``shares`` over ``ids``), in place:
    family, order, whirl, name, the dominant and second participations, mixed and rigid flags;
    ``continued``: the mode continues the previous point's carrier of ``ids[k]`` (kept whatever its
    share, :data:`CONTINUED_MAC`).  The drivetrain's rigid rotation (its share non-zero only below
    :data:`RIGID_HZ`, :func:`participations`) is kept whatever its share too: a heavily damped
    rotor-speed root (-79 % on the IEA 22 MW shell at 8 m/s) moves the blades' flap more than the
    rotor turns, and its name must still say rigid body so that it is never an instability."""
    order = [int(i) for i in np.argsort(shares)[::-1]]
    if k >= 0 and order[0] != k and shares[k] == shares[order[0]]:  # a tie (a wall pair): the assigned one first
        order.remove(k)
        order.insert(0, k)
    first = order[0]
    # a wall pair's twin shares the pair's participation (:func:`_wall_pairs`): not a second one
    second = next((i for i in order[1:] if not (ids[i].family == "tower_wall" == ids[first].family
                                                 and ids[i].wave == ids[first].wave and shares[i] == shares[first])), -1)
    if second >= 0 and shares[second] <= NO_SHARE:  # round-off (an uncoupled tower wall mode: 1e-25), not a participant
        second = -1
    rec.participation = [(ids[i].name, float(shares[i])) for i in (first, second) if i >= 0]
    kept = continued or (k >= 0 and ids[k].family == "rigid" and shares[k] > 0)
    floor = 0.0 if kept else max(MIN_ASSIGNED_SHARE, 0.5 * shares[first] if heavy else 0.0)
    if k < 0 or shares[k] < floor:  # no identity of its own: named by its participations
        rec.identity, rec.family, rec.order, rec.whirl = None, "mixed", 0, "none"
        rec.rigid, rec.share, rec.mixed = False, 0.0, True
        rec.name = " + ".join(n for n, _ in rec.participation)
        _mark_buckling(rec, ids[first], shares[first])
        return
    mine = ids[k]
    rec.identity, rec.family, rec.order, rec.whirl = mine, mine.family, mine.order, mine.whirl
    rec.rigid = mine.family == "rigid"
    rec.share = float(shares[k])
    other = next(((n, s) for n, s in rec.participation if n != mine.name), None)
    rec.mixed = rec.share < MIXED_SHARE
    rec.name = mine.name if not rec.mixed or other is None else f"{mine.name} + {other[0]}"
    _mark_buckling(rec, ids[first], shares[first])


def _mark_buckling(rec, largest: Identity, share: float) -> None:
    """A mode made mostly (half or more) of a statically unstable own mode of the prestressed blade
    is that, whatever name the assignment gave it: family ``buckling``, never an aeroelastic
    instability."""
    if largest.family == "buckling" and share >= 0.5:
        rec.family, rec.mixed = "buckling", False
        rec.name = largest.name
