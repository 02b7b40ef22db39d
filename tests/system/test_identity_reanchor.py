"""A continued own-mode name returns to its mode after a veering with a local mode (issue 33).

A small matrix blade driven through :func:`windflutter.system.identity.point_own_modes` along a
sweep: four generalized coordinates whose strip motions are a 1st torsion (twist linear along the
span), a 1st flap, a 1st edge and a local tip mode (edge motion of the outermost strip only, as the
shell's tip-panel modes at 97-100 % span); the local mode's stiffness is swept from above the
torsion's to below it and coupled to it, so that the two veer: through the veering their modes mix,
and after it the upper branch is the torsion again, the lower one the local mode.  Continuation by
the previous point's MAC alone follows the branches, the name "1st torsion" staying on the lower
branch (the local mode) after the separation; re-anchoring to the reference gives it back to the
torsion.  Expected names are known by construction (the coordinates' shapes), not from the solver.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from windflutter.system.identity import point_own_modes
from windflutter.system.reference import StructuralReference, strip_signatures

NS = 10  # strips
TWO_PI = 2 * np.pi
K_FIXED = {"torsion": (TWO_PI * 1.0) ** 2, "flap": (TWO_PI * 0.3) ** 2, "edge": (TWO_PI * 0.5) ** 2}
COUPLING = 0.06 * K_FIXED["torsion"]  # veering half-width about 6 % in stiffness


def _components() -> np.ndarray:
    """(3, NS, 4) flap/edge/torsion strip motion of the coordinates torsion, flap, edge, local tip."""
    s = np.linspace(0.1, 1.0, NS)
    c = np.zeros((3, NS, 4))
    c[2, :, 0] = s
    c[0, :, 1] = s**2
    c[1, :, 2] = s**2
    c[1, -1, 3] = 1.0
    return c


def _ps(k_local: float):
    K = np.diag([K_FIXED["torsion"], K_FIXED["flap"], K_FIXED["edge"], k_local])
    K[0, 3] = K[3, 0] = COUPLING
    Kf, Mf = np.zeros((10, 10)), np.eye(10)  # 6 rigid-body coordinates first, as the blade's structure
    Kf[6:, 6:] = K
    sections = SimpleNamespace(width=np.ones(NS))
    return SimpleNamespace(blade_structure=(Mf, Kf), blade=SimpleNamespace(sections=sections))


def _reference() -> StructuralReference:
    """Standstill: the local mode far above the torsion (its coordinates' own shapes, frequency order)."""
    sig = strip_signatures(SimpleNamespace(width=np.ones(NS)), _components())
    blade = [("torsion", 1, 1.0), ("flap", 1, 0.3), ("edge", 1, 0.5), ("edge", 2, 2.0)]
    order = np.argsort([f for *_, f in blade])
    return StructuralReference(blade=[blade[i] for i in order], signatures=sig[:, order])


def _sweep():
    """(k_local / k_torsion, {name: own-mode index}, own modes) along the sweep, each point continuing
    the previous one's names."""
    ref, comps, previous, out = _reference(), _components(), None, []
    for ratio in np.linspace(1.5, 0.6, 31):  # 3 % steps: the branches' MAC between points stays above 0.8
        own = point_own_modes(_ps(ratio * K_FIXED["torsion"]), comps, ref, previous=previous)
        out.append((ratio, {x: j for j, x in enumerate(own.ident)}, own))
        previous = own.names
    return out


def _torsion_content(own, j: int) -> float:
    """The share of own mode ``j`` in the torsion coordinate (its shape is known by construction)."""
    return float(own.V[0, j] ** 2 / np.sum(own.V[:, j] ** 2))


def test_the_torsion_name_returns_to_the_torsion_after_a_veering_with_a_local_mode():
    sweep = _sweep()
    # away from the veering (local stiffness 25 % or more off the torsion's: the modes are 98 % pure)
    # the name "1st torsion" is on the mode made of the torsion coordinate, before and after
    checked = 0
    for ratio, where, own in sweep:
        if abs(ratio - 1.0) >= 0.25:
            assert _torsion_content(own, where[("torsion", 1)]) > 0.95, (ratio, where)
            assert _torsion_content(own, where[("edge", 2)]) < 0.05, (ratio, where)
            checked += 1
    assert checked >= 10
    # the case is the one meant: at the veering's middle the two modes mix (each 25-75 % torsion)
    _, _, own = min(sweep, key=lambda x: abs(x[0] - 1.0))
    content = sorted(_torsion_content(own, j) for j in range(4))
    assert 0.25 < content[-2] <= content[-1] < 0.75, content

def test_names_of_uncoupled_modes_stay_and_every_name_is_used_once():
    for _, where, own in _sweep():
        assert len(where) == len(own.ident)
        assert np.argmax(np.abs(own.V[1, :])) == where[("flap", 1)]
        assert np.argmax(np.abs(own.V[2, :])) == where[("edge", 1)]


def test_the_name_moves_once_not_back_and_forth_through_the_veering():
    """Hysteresis: the name leaves the lower branch once, after the mixed middle (it is kept there while
    both branches resemble the torsion alike), and never comes back."""
    side = []
    for _, where, own in _sweep():
        veer = sorted((j for j in range(4) if abs(own.V[1, j]) < 0.5 and abs(own.V[2, j]) < 0.5),
                      key=lambda j: own.w2[j])
        side.append(veer.index(where[("torsion", 1)]))
    switches = sum(a != b for a, b in zip(side, side[1:]))
    assert side[0] == 0 and side[-1] == 1 and switches == 1, side
