"""The reference of mode identity: the parts' own structural modes, named once per model
(step 1 of :mod:`windflutter.system.identity`).

The blade's structural modes at standstill, without aerodynamics, in its own (pitching) frame, each
named by its largest strip motion -- flap, edge or torsion
(:func:`windflutter.structure.labels.blade_motion_components`) -- and ordered in frequency within its
family; the support's modes (the support alone), named fore-aft / side-side / torsion by their motion,
and a shell tower's wall modes by their circumferential wave number.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.structure.labels import blade_motion_components, wall_waves
from windflutter.structure.modal import mass_normalize, split_directions, symmetric_eigs
from windflutter.system.blade_basis import clamped_modes

#: the blade's reference modes: its lowest this many standstill modes
REFERENCE_MODES = 24
#: the default frequency limit of the Campbell and the overspeed sweep: this factor x the blade's 1st
#: torsion frequency at standstill
MAX_HZ_FACTOR = 1.25
BLADE_FAMILIES = ("flap", "edge", "torsion")


@dataclass
class StructuralReference:
    """The blade's standstill modes (``blade``: (family, order, frequency Hz) in frequency order,
    ``signatures``: their unit strip-motion signatures, columns) and the support's modes (``Phi_s``
    mass-normalized in support coordinates, ``support``: (family, order, frequency Hz),
    ``support_wave``: the circumferential wave number of the shell tower's wall modes, -1 for the
    others)."""

    blade: list
    signatures: np.ndarray
    support: list = field(default_factory=list)
    Phi_s: np.ndarray | None = None
    support_wave: np.ndarray | None = None

    def default_max_hz(self) -> float:
        """The Campbell's and the overspeed sweep's frequency limit (Hz) when none is given:
        :data:`MAX_HZ_FACTOR` x the blade's 1st torsion frequency (its classical-flutter partner), or
        x its highest reference mode without a torsion mode."""
        f = self.first_hz("torsion")
        return MAX_HZ_FACTOR * (f if np.isfinite(f) else max(fk for _, _, fk in self.blade))

    def first_hz(self, family: str) -> float:
        """The frequency (Hz) of the blade's 1st mode of ``family`` (NaN if it has none)."""
        return next((f for fam, o, f in self.blade if fam == family and o == 1), float("nan"))


def strip_signatures(sections, comps: np.ndarray) -> np.ndarray:
    """(3 ns, n) unit-norm signatures of strip motions ``comps`` (3, ns, n) (flap, edge, torsion x a
    quarter chord), weighted by the square root of the strip widths."""
    s = comps * np.sqrt(np.asarray(sections.width, float))[None, :, None]
    s = s.reshape(-1, comps.shape[-1])
    return s / np.maximum(np.linalg.norm(s, axis=0), 1e-300)[None, :]


def strip_family(sections, comps: np.ndarray) -> list[str]:
    """flap / edge / torsion of each mode: the largest width-weighted strip-motion energy."""
    en = np.sum(np.abs(comps) ** 2 * np.asarray(sections.width, float)[None, :, None], axis=1)
    return [BLADE_FAMILIES[k] for k in np.argmax(en, axis=0)]


def _ordered(families: list[str]) -> list[int]:
    count: dict = {}
    out = []
    for fam in families:
        count[fam] = count.get(fam, 0) + 1
        out.append(count[fam])
    return out


def blade_reference(struct, sections) -> StructuralReference:
    """The blade part of the reference: its lowest :data:`REFERENCE_MODES` structural modes at
    standstill (``struct``: its assembled, root-clamped :class:`~windflutter.structure.assembly.
    Structural`), named and with their strip signatures."""

    w2, X = clamped_modes(struct, min(REFERENCE_MODES, struct.Kr.shape[0] - 2))  # shared with the damping
    f = np.sqrt(np.maximum(w2, 0.0)) / (2 * np.pi)
    comps = blade_motion_components(sections, np.asarray(struct.T @ mass_normalize(X, struct.Mr)))
    fams = strip_family(sections, comps)
    named = [(fam, o, float(fk)) for fam, o, fk in zip(fams, _ordered(fams), f)]
    return StructuralReference(blade=named, signatures=strip_signatures(sections, comps))


def tower_wall_waves(support, Phi: np.ndarray) -> np.ndarray:
    """(n,) the circumferential wave number of each support mode (columns of ``Phi``, support
    coordinates) that is a mode of the shell tower's wall, -1 for the others (all of them for a beam
    tower): :func:`windflutter.structure.labels.wall_waves` on the support's tower.  Such a mode has
    equal fore-aft and side-side motion and no preferred direction (it comes in degenerate pairs):
    a fore-aft / side-side name, decided by the solver's rotation of the pair, would change from run
    to run."""
    fe = getattr(support, "fe", None)
    groups = getattr(fe, "node_groups", None) or {}
    if "tower" not in groups:
        return np.full(Phi.shape[1], -1)
    masses = np.asarray(support.struct.M.diagonal()).reshape(-1, 6)[:, 0]
    return wall_waves(fe.nodes, masses, np.asarray(support.expand @ Phi), groups["tower"])


def support_reference(support) -> tuple[list, np.ndarray | None, np.ndarray]:
    """(named modes, mass-normalized shapes, wave numbers) of the support alone (tower, nacelle, hub;
    no rotor): each mode named tower fore-aft, side-side or torsion by its motion, or ``tower_wall``
    with its circumferential wave number (:func:`tower_wall_waves`; -1 for the others), ordered within
    its family (the wall's within its wave number)."""
    if support is None:
        return [], None, np.zeros(0, dtype=np.int64)
    w2, Phi = symmetric_eigs(support.K, support.M)
    md = np.asarray(support.struct.M.diagonal())

    def energies(V):  # (6, n): the support nodes' kinetic energy per motion component of each mode
        U = np.asarray(support.expand @ V).reshape(md.size, -1)
        return (md[:, None] * np.abs(U) ** 2).reshape(-1, 6, U.shape[1]).sum(axis=0)

    # a degenerate fore-aft / side-side pair of an axisymmetric tower comes out of the solver in any
    # rotation: turned onto its directions, its names no longer change from one run to the next
    Phi = split_directions(w2, Phi, lambda v: tuple(energies(v[:, None])[:2, 0]))
    e = energies(Phi)
    waves = tower_wall_waves(support, Phi)
    fams = ["tower_wall" if waves[k] >= 0 else "tower_torsion" if e[5, k] > max(e[0, k], e[1, k])
            else ("tower_fa" if e[0, k] >= e[1, k] else "tower_ss") for k in range(Phi.shape[1])]
    orders = _ordered([f"{fam}{waves[k]}" if fam == "tower_wall" else fam for k, fam in enumerate(fams)])
    f = np.sqrt(np.maximum(w2, 0.0)) / (2 * np.pi)
    return [(fam, o, float(fk)) for fam, o, fk in zip(fams, orders, f)], Phi, waves


def structural_reference(blade, support) -> StructuralReference:
    """The reference of a turbine model: ``blade`` a :class:`~windflutter.system.blade.RotorBlade`
    (its standstill structure; the pitch does not change its modes in its own frame), ``support`` the
    support model or None."""
    ref = blade_reference(blade.struct, blade.sections)
    ref.support, ref.Phi_s, ref.support_wave = support_reference(support)
    return ref
