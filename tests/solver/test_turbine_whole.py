"""Whole turbine (tower + nacelle + hub + rotor) against the rotor alone, and the p-k search
details that decide whether the whole turbine's blade flutter is found (issue 5).

Independent references used here:
* an analytic 2-DOF system (exact damping crossing) for the p-k onset logic;
* the rotor alone (hub clamped) for the whole turbine whose tower top is held or whose tower
  is made stiff -- the whole-turbine model must converge to it;
* the full-order solve (``reduction="none"``) for the reduced ones (slow).
"""

import math

import numpy as np
import pytest

import windflutter.mesh.turbine as mesh_turbine
from windflutter.frozen.search import pk_search
from windflutter.frozen.turbine import TurbineOptions, TurbineStability
from windflutter.structure.fem import BeamSection


# ------------------------------------------------------------------ analytic p-k onset logic
class _Toy:
    """``M x'' + D(p) x' + K x = 0`` without frequency dependence (an OperatingSystem stand-in)."""

    def __init__(self, p):
        Q = np.linalg.qr(np.array([[1.0, 0.3], [-0.2, 1.0]]))[0]  # rotated DOFs: rounding in the solves
        self.Ks = Q @ np.diag([4.0, 9.0]) @ Q.T
        # mode 1 (2 rad/s): damping ratio 2.5e-10 (5 - p) -- neutral to rounding level, crosses 0 at p = 5
        # mode 2 (3 rad/s): damping 0.3 (8 - p) -> Re(lambda) = -0.15 (8 - p), flutter exactly at p = 8
        self.D = Q @ np.diag([1e-9 * (5.0 - p), 0.3 * (8.0 - p)]) @ Q.T
        self.eig_cache, self.size = {}, 2

    def matrices(self, omega):
        return np.eye(2), self.D, self.Ks

    def newton_pencil(self, lam, omega):
        from windflutter.solve.qep import qep_pencil

        return qep_pencil(*self.matrices(omega), lam)

    def structural_pencil(self):
        return self.Ks, np.eye(2)


def test_pk_onset_analytic_and_neutral_mode_ignored():
    # A mode whose damping ratio only wanders at the 1e-10 level (an undamped tower mode with
    # no aero coupling, e.g. when the tower top is held) is not flutter: before the neutral
    # threshold the search reported "flutter" at the first grid point after p = 5.  The real
    # crossing is at p = 8 exactly, at sqrt(9 - 0) = 3 rad/s; root-finding tolerance 1e-6.
    on = pk_search(_Toy, np.arange(0.5, 12.0, 1.0), n_track=2, n_eig=4, xtol=1e-8, divergence=False,
                   stop_at_onset=False)
    assert on.flutter == pytest.approx(8.0, abs=1e-6)
    assert on.flutter_frequency == pytest.approx(3.0, rel=1e-6)
    assert on.flutter_mode == 1


# ------------------------------------------------------------------ NREL 5 MW whole turbine
N_SPAN = 8  # blade beam elements / strips per blade (reduced; the slow test uses 10)
GRID = dict(min_rpm=16.0, max_rpm=32.0, rpm_step=2.0)


def _analyse(turbine, part, monkeypatch=None, edit=None, n_span=N_SPAN, **opts):
    """Onsets at 10 m/s; ``edit(fe) -> fe`` changes the FE model before assembly."""
    if edit is not None:
        orig = mesh_turbine.build_model

        def build(t, settings):
            fe, sections = orig(t, settings)
            return edit(fe), sections

        monkeypatch.setattr(mesh_turbine, "build_model", build)
    o = TurbineOptions(model="beam", mesh={"n_span": n_span, "part": part}, **{**GRID, **opts})
    return TurbineStability(turbine, o).analyse_operating_point(10.0)


def _clamp_tower_top(fe):
    fe.spc[int(fe.node_groups["tower_top"][0])] = (0, 1, 2, 3, 4, 5)
    return fe


def _stiffen_tower(factor):
    def edit(fe):
        tower = fe.region_names.index("tower")
        ids = set(fe.beam_section[fe.element_regions["beam"] == tower].tolist())
        secs = [BeamSection(stiffness=s.stiffness * factor, mass=s.mass, name=s.name) if i in ids else s
                for i, s in enumerate(fe.beam_sections)]
        from dataclasses import replace

        return replace(fe, beam_sections=secs)

    return edit


@pytest.fixture(scope="module")
def whole(nrel5mw):
    return _analyse(nrel5mw, "turbine")


def test_rotor_alone_reference(rotor_alone):
    # the reference itself (tests/solver/conftest.py, the same mesh and grid as _analyse here):
    # 1st-torsion -> flap-torsion flutter at ~3.5 Hz below divergence
    p = rotor_alone
    grid = np.arange(GRID["min_rpm"], GRID["max_rpm"] + 1e-9, GRID["rpm_step"])
    np.testing.assert_array_equal(p.sweep_rpm, grid[: p.sweep_rpm.size])  # the sweep stops at the onset
    assert p.flutter_rpm is not None and p.divergence_rpm is not None
    assert p.flutter_rpm < p.divergence_rpm and p.first_instability == "flutter"
    assert 3.0 < p.flutter_frequency_hz < 4.0


def test_tower_top_held_equals_rotor_alone(nrel5mw, rotor_alone, monkeypatch):
    # Whole-turbine mesh with the tower-top node held: the rotor sees exactly the hub-clamped
    # boundary of the rotor alone (same blades, strips, motion map, rotating terms; the tower
    # and nacelle are decoupled and undamped).  Equal onsets to 3x the 0.01 RPM root-finding
    # tolerance and 0.1 % frequency; and the undamped tower modes must not be taken for flutter.
    p = _analyse(nrel5mw, "turbine", monkeypatch, _clamp_tower_top)
    r = rotor_alone
    assert p.flutter_rpm == pytest.approx(r.flutter_rpm, abs=0.03)
    assert p.flutter_frequency_hz == pytest.approx(r.flutter_frequency_hz, rel=1e-3)
    assert p.divergence_rpm == pytest.approx(r.divergence_rpm, abs=0.03)
    assert "tower" not in p.flutter_mode


def test_stiff_tower_converges_to_rotor_alone(nrel5mw, rotor_alone, whole, monkeypatch):
    # Tower stiffness x1e4 (masses kept; tower modes x100 in frequency, above 30 Hz): the
    # tower-top motion vanishes and the whole turbine must approach the rotor alone -- within
    # 0.03 RPM (3x the root-finding tolerance) on flutter and divergence, and far closer than
    # with the real tower, whose flexibility moves the onsets by O(1 RPM).  (x100 is not a
    # clean limit: it puts the 1st tower modes at ~3 Hz, next to the 3.5 Hz flutter mode.)
    p = _analyse(nrel5mw, "turbine", monkeypatch, _stiffen_tower(1e4))
    r = rotor_alone
    for key in ("flutter_rpm", "divergence_rpm"):
        d_stiff = abs(getattr(p, key) - getattr(r, key))
        d_real = abs(getattr(whole, key) - getattr(r, key))
        assert d_stiff < 0.03, (key, getattr(p, key), getattr(r, key))
        assert d_stiff < 0.2 * d_real
    assert p.flutter_frequency_hz == pytest.approx(r.flutter_frequency_hz, rel=1e-3)


def test_whole_turbine_finds_blade_flutter(whole, rotor_alone):
    # The issue: the whole turbine reported no flap-torsion flutter below divergence.  It must
    # find the 1st-torsion -> flap-torsion flutter near the rotor-alone one: same mode family
    # (3-4 Hz), below divergence, within 3 RPM of the rotor alone.  (At full order the two agree
    # to 0.05 RPM; the default 30-mode basis puts the whole turbine ~1.5 RPM high, which is
    # why the bound is not tighter -- docs/stability.md.)
    p = whole
    assert p.flutter_rpm is not None and p.divergence_rpm is not None
    assert p.first_instability == "flutter" and p.flutter_rpm < p.divergence_rpm
    assert 3.0 < p.flutter_frequency_hz < 4.0
    assert "torsion" in p.flutter_mode or "flap" in p.flutter_mode
    assert abs(p.flutter_rpm - rotor_alone.flutter_rpm) < 3.0


def test_all_three_torsion_modes_tracked(whole):
    # Three blades give three near-repeated 1st-torsion modes (collective and two cyclic),
    # split by the tower coupling; all three must be among the tracked modes, and below the
    # onset each must be found (no NaN) on its own root (no two on one root).  (The heavily
    # damped 1st-flap modes may turn overdamped -- no oscillatory root -- and are not checked.)
    p = whole
    tors = [j for j, lab in enumerate(p.mode_labels) if " torsion" in lab and "tower" not in lab]
    assert len(tors) >= 3, p.mode_labels
    below = p.sweep_rpm < p.flutter_rpm
    lam = p.onset.eigenvalues[below][:, tors]
    assert np.all(np.isfinite(lam))
    for row in lam:
        d = np.abs(row[:, None] - row[None, :]) + np.eye(row.size)
        assert d.min() > 1e-9 * np.abs(row).max()


def test_flutter_above_divergence_is_labelled(nrel5mw):
    # Tracking only the 8 lowest modes (no torsion, no 2nd flap: what a fixed count did before
    # the automatic one) the whole turbine's only flutter crossing is the edgewise one near
    # 31 RPM, 1.0 Hz, above the divergence (~25 RPM).  It is still reported (as a V-g plot
    # shows it), but the label and first_instability must say that divergence comes first.
    p = _analyse(nrel5mw, "turbine", n_tracked=8, max_rpm=40.0)
    assert p.divergence_rpm is not None and p.flutter_rpm is not None
    assert p.flutter_rpm > p.divergence_rpm
    assert p.first_instability == "divergence"
    assert p.flutter_mode.endswith("(above divergence)")
    d = p.as_dict()
    assert d["first_instability"] == "divergence" and d["flutter_rpm"] == pytest.approx(p.flutter_rpm)


@pytest.mark.slow
def test_full_order_whole_turbine(nrel5mw):
    # Full order (reduction "none", dense QEP) vs the projected model, whole turbine (6 elements
    # per blade, 8 tower elements, to keep the dense full-order solves affordable), and vs the
    # full-order rotor alone.  Tolerances: reduced with 60 modes per reference speed within 1 %
    # of full order (measured 0.1-0.3 % on the 10- and 30-element models); the whole turbine's
    # blade flutter within 2 % of the rotor alone's (the tower coupling is a small physical
    # effect here: +0.04 RPM at full order on the 30-element model, docs/stability.md);
    # divergence 2 %.
    mesh = {"n_tower_axial": 8}
    o = dict(model="beam", min_rpm=18.0, max_rpm=28.0, rpm_step=2.0)
    full = TurbineStability(nrel5mw, TurbineOptions(reduction="none", mesh={"n_span": 6, "part": "turbine", **mesh},
                                                    **o)).analyse_operating_point(10.0)
    red = TurbineStability(nrel5mw, TurbineOptions(basis_modes=60, mesh={"n_span": 6, "part": "turbine", **mesh},
                                                   **o)).analyse_operating_point(10.0)
    rot = _analyse(nrel5mw, "rotor", reduction="none", n_span=6, **{k: o[k] for k in ("min_rpm", "max_rpm", "rpm_step")})
    for p in (full, red, rot):  # the same flap-torsion family, ~3.0-3.1 Hz on this coarse mesh
        assert p.flutter_rpm is not None and p.divergence_rpm is not None
        assert p.first_instability == "flutter" and 2.5 < p.flutter_frequency_hz < 4.0
    assert red.flutter_rpm == pytest.approx(full.flutter_rpm, rel=0.01)
    assert red.divergence_rpm == pytest.approx(full.divergence_rpm, rel=0.01)
    assert red.flutter_frequency_hz == pytest.approx(full.flutter_frequency_hz, rel=0.01)
    assert full.flutter_rpm == pytest.approx(rot.flutter_rpm, rel=0.02)
    assert full.divergence_rpm == pytest.approx(rot.divergence_rpm, rel=0.02)
    assert not math.isnan(full.flutter_frequency_hz)


def test_tracked_modes_are_named_in_the_field_vocabulary(whole):
    """The frozen-azimuth sweep names its modes by the blade's identities (system/identity.py, the
    vocabulary of method p): ordinal and family of the blade's own mode, collective/asymmetric, one
    collective per blade triplet; the flutter mode is named by the tracked mode it grew from (and
    ``-> `` its identity at the onset where that differs)."""
    import re

    p = whole
    pat = re.compile(r"^\d+(st|nd|rd|th) (flap|edge|torsion|tower fore-aft|tower side-side|tower torsion)"
                     r"( collective| asymmetric| blade \d)?$")
    named = [lab for lab in p.mode_labels if lab != "lost"]
    assert named and all(pat.match(lab) for lab in named), p.mode_labels
    tors = [lab for lab in named if lab.startswith("1st torsion")]
    assert sorted(tors) == ["1st torsion asymmetric", "1st torsion asymmetric", "1st torsion collective"], named
    assert p.flutter_mode.split(" (")[0].split(" -> ")[0] in p.mode_labels
