"""A blade structure that loses static stability on its own is not reported as divergence.

Found on the NREL 5 MW shell blade at 8 m/s: its steady stress makes the FE structure statically
unstable at 22.0 RPM without any aerodynamics (a local mode of the tip's slender shell elements,
w^2 from +38 to -7800 1/s^2 between 22 and 23 RPM), and the static-margin search called that
"divergence".  Aeroelastic divergence is the aerodynamic stiffness overcoming a stable structure;
a structural instability of the FE model stops the sweep with a note instead.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import windflutter
import windflutter.overspeed as op
from windflutter.units import RPM


def test_a_structural_instability_stops_the_sweep_with_a_note(monkeypatch):
    """Control logic, on the beam model: the structure alone declared unstable from 14 RPM on (the
    real margin of a beam blade stays positive); the sweep stops between its grid points, the note
    says where (interpolated between them) and why, and no divergence or flutter is reported
    beyond it."""
    real = op.blade_structural_margin

    def fake(ps):
        w = real(ps)
        return w if ps.omega / RPM < 14.0 else -1.0

    monkeypatch.setattr(op, "blade_structural_margin", fake)
    (p,) = windflutter.stability("nrel5mw", [11.4], model={"part": "rotor"})
    note = p.as_dict()["note"]
    assert note and "loses static stability on its own at" in note and "not aeroelastic divergence" in note
    stop = float(re.search(r"at about ([0-9.]+) RPM", note).group(1))
    assert 12.1 < stop <= 14.0 + 0.02
    assert p.divergence_rpm is None and p.flutter_rpm is None
    assert np.max(p.sweep_rpm) < 14.0
    # the note says from which rotor speed it holds, so that the verdict does not put its caution
    # on onsets found below it (a note without one concerns the whole sweep)
    from windflutter.post.verdict import _note_from_rpm

    assert _note_from_rpm(note) == pytest.approx(stop, abs=0.006)


@pytest.mark.slow
def test_iea22mw_shell_structural_instability_is_not_divergence():
    """The real case (about 20 s): the IEA 22 MW shell (default mesh) at 10 m/s, whose blade structure
    alone under its steady stress loses static stability between the operating 6.16 and 8 RPM, its
    mode largest at r/R = 0.70 (docs/verification.md, "Not verified", item 18): the sweep stops there
    with the note, and reports no divergence.  Until Dec 2026 the case here was the NREL 5 MW's open
    tip on the seed's mesh (20.07 RPM, r/R 0.97), which was pyfe3d's one-point-shear hourglass mode:
    with MITC4's shear that tip does not buckle, and its sweep reaches an aeroelastic divergence at
    29.2 RPM."""
    (p,) = windflutter.stability("iea22mw", [10.0], model="shell")
    note = p.as_dict()["note"]
    assert p.divergence_rpm is None and p.flutter_rpm is None, p.as_dict()
    assert note and "loses static stability on its own" in note and "not aeroelastic divergence" in note
    assert 0.6 <= float(re.search(r"r/R = ([0-9.]+)", note).group(1)) <= 0.8
    stop = float(re.search(r"at about ([0-9.]+) RPM", note).group(1))
    assert 6.1 < stop <= 8.0


@pytest.mark.slow
def test_nrel5mw_shell_with_the_tip_rib_stays_structurally_stable():
    """The default closure (a rib: the tip section keeps its shape in its plane): the structure alone
    with its steady stress is stable at 26 RPM, where the open tip had failed with the one-point
    shear (the previous test), and the sweep runs on to the aeroelastic onsets (no note).  Measured 2 Dec 2026 with
    one stiffness-proportional damping on the shell: 4th flap BW flutter 29.02 RPM; since the shell's
    per-direction structural damping (issue 33, 4 Dec) the first onset is the 1st edge BW + 1st flap
    BW at 20.56 RPM (0.68 Hz), the beam of the same blade's 20.37 RPM
    (test_shell_same_blade.py's slow onset check), ~110 s."""
    (p,) = windflutter.stability("nrel5mw", [8.0], model="shell")
    d = p.as_dict()
    assert d["note"] is None, d  # no structural instability anywhere in the sweep (which runs past 26 RPM)
    assert p.flutter_rpm is not None and 1.5 * 12.1 < p.flutter_rpm < 26.0
    assert "edge" in p.flutter_mode
    assert p.divergence_rpm is None or p.divergence_rpm > 26.0


def _fake_point(K_elastic, motion_of_coordinate, nodes, conn=None, props=()):
    """A point whose blade has ``len(K_elastic)`` elastic coordinates (unit mass); coordinate ``j``
    moves the nodes by ``motion_of_coordinate[j]`` (n_nodes,) along x; shell elements ``conn`` of
    properties ``props``."""
    from types import SimpleNamespace

    from windflutter.structure.fem import IsotropicMaterial, Ply, ShellProperty

    m = len(K_elastic)
    M, K = np.eye(6 + m), np.diag(np.r_[np.ones(6), K_elastic])
    n = len(nodes)

    def basis_full(_phi):
        B = np.zeros((6 * n, 6 + m))
        for j, a in enumerate(motion_of_coordinate):
            B[0::6, 6 + j] = a
        return B

    shell = [ShellProperty(tuple(Ply(IsotropicMaterial(E=1e10, nu=0.3, rho=1000.0, name=nm), t) for nm, t in p))
             for p in props]
    fe = SimpleNamespace(nodes=np.asarray(nodes, float), shell_conn=np.zeros((0, 4), int) if conn is None else
                         np.asarray(conn), shell_prop=np.arange(len(shell)), shell_properties=shell)
    blade = SimpleNamespace(fe=fe, apex=np.zeros(3), basis_full=basis_full)
    return SimpleNamespace(blade_structure=(M, K), blade=blade, Phi=None)


def test_the_unstable_mode_is_located_with_its_laminate():
    """The message's site: r/R of the node that moves most in the lowest (negative) mode and, on a
    shell blade, the laminate of the element that moves most -- two elements along a 4 m blade, the
    outer one a 2.2 mm single skin; the mode (eigenvalue -5) moves the outer element's nodes, the
    stable one (+3) the inner's.  Swapping the two modes' shapes names the other element."""
    nodes = [[0, 0, z] for z in (1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0)]
    conn = [[0, 1, 3, 2], [4, 5, 7, 6]]
    props = [(("glass_triax", 0.0012), ("foam", 0.02), ("glass_triax", 0.0012)), (("glass_triax", 0.0012), ("Gelcoat", 0.001))]
    inner, outer = np.r_[1, 1, 1, 1, 0, 0, 0, 0.0], np.r_[0, 0, 0, 0, 0.5, 0.5, 1, 1.0]
    site = op.structural_mode_site(_fake_point([-5.0, 3.0], [outer, inner], nodes, conn, props))
    assert site == "largest at r/R = 1.00, where the shell is a 2.2 mm laminate: glass_triax 1.2 mm, Gelcoat 1.0 mm"
    site = op.structural_mode_site(_fake_point([3.0, -5.0], [outer, inner], nodes, conn, props))
    assert site.startswith("largest at r/R = 0.25, where the shell is a 22.4 mm laminate: glass_triax 1.2 mm, foam")
    assert op.structural_mode_site(_fake_point([-5.0, 3.0], [outer, inner], nodes)) == "largest at r/R = 1.00"
    # the basis stable, the full-order stiffness not (negative pivots outside the basis): the basis's
    # lowest mode is not the unstable one, so no site is given
    stable = _fake_point([3.0, 5.0], [outer, inner], nodes, conn, props)
    assert op.structural_mode_site(stable).startswith("largest at r/R = 1.00")
    stable.blade_negative = 2
    assert op.structural_mode_site(stable) == "(its shape not computed: outside the blade basis's modes)"


def test_a_structure_unstable_at_the_operating_point_is_refused_with_its_site(monkeypatch):
    """The structure alone unstable at the operating point (faked on the beam rotor: every margin
    negative): the wind speed is refused with one ModelError saying where the mode lives."""
    from windflutter.errors import ModelError

    monkeypatch.setattr(op, "blade_structural_margin", lambda ps: -1.0)
    with pytest.raises(ModelError, match=r"statically unstable at the operating point \(11\.92 RPM\) without "
                                         r"aerodynamics: a mode largest at r/R = [01]\.\d\d -- a local buckling is likely$"):
        windflutter.stability("nrel5mw", [11.4], model={"part": "rotor"})


@pytest.mark.slow
def test_nrel5mw_shell_blade_has_no_hourglass_instability():
    """The NREL 5 MW shell blade (the default mesh) deflected at 16 m/s and 30 RPM: with pyfe3d's
    one-point transverse shear its full-order stiffness has one negative eigenvalue (-1.6e5 1/s^2,
    91 % of its normal motion the elements' w-hourglass pattern, alternating node to node on a
    chordwise line at r/R 0.65-0.8; docs/mesh.md "Transverse shear"), which stopped the sweeps at
    14-18 m/s between 26 and 28 RPM; with MITC4's shear (the default) the stiffness is positive
    definite and its lowest eigenvalue (35.6 1/s^2, the 1st flap) moves by 0.05 %.  About 80 s."""
    from windflutter.methods import operational_options
    from windflutter.system.operational import OperationalModel

    negative = {}
    for shear in ("one-point", "mitc4"):
        cfg = windflutter.analysis_config(model={"type": "shell", "shell_shear": shear})
        om = OperationalModel(windflutter.load_turbine("nrel5mw"), operational_options(cfg, "viscous"))
        negative[shear] = om.at(16.0, rpm=30.0).blade_negative
    assert negative == {"one-point": 1, "mitc4": 0}
