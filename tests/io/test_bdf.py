"""NASTRAN BDF export/import.

Tests marked ``nastran`` need pyNastran (extra ``nastran``); CI runs them in ``.venv-nastran``
via ``make test-nastran`` (see .ci/run), so they are not skipped there.
"""

from __future__ import annotations

import importlib.util
import sys
import dataclasses
import os
import warnings
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from _models import consistent_section, mixed_model  # noqa: E402

from windflutter.errors import InputError  # noqa: E402
from windflutter.structure.fem import BeamSection, FEModel, LumpedMass  # noqa: E402
from windflutter.structure.bdf.cards import CARDS  # noqa: E402
from windflutter.structure.io_bdf import BdfApproximationWarning, _real16, read_bdf, write_bdf  # noqa: E402

# CI runs the nastran-marked tests in .venv-nastran (numpy < 2) via `make test-nastran`
HAVE_PYNASTRAN = importlib.util.find_spec("pyNastran") is not None
if os.environ.get("WINDFLUTTER_REQUIRE_NASTRAN") and not HAVE_PYNASTRAN:
    raise RuntimeError("WINDFLUTTER_REQUIRE_NASTRAN is set but pyNastran is not importable "
                       "(pip install 'windflutter[nastran]')")


def _write(fe, path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BdfApproximationWarning)
        return write_bdf(fe, path, **kw)


def _cards(text: str) -> dict[str, int]:
    counts: dict[str, int] = {}
    for line in text.splitlines():
        if line and line[0] not in "$* " and "*" in line[:8]:
            name = line[:8].rstrip().rstrip("*")
            counts[name] = counts.get(name, 0) + 1
    return counts


# ---------------------------------------------------------------------------------------------
# writer (no pyNastran needed)
# ---------------------------------------------------------------------------------------------
def test_real_fields_keep_ten_digits():
    rng = np.random.default_rng(1)
    x = rng.standard_normal(2000) * 10.0 ** rng.integers(-30, 30, 2000)
    for v in x:
        s = _real16(v)
        assert len(s) <= 16 and ("." in s)
        # 16-character fields hold >= 9 significant digits even for negative numbers with
        # two-digit exponents ("-1.23456789e-05"): relative error <= 5e-9
        assert abs(float(s) - v) <= 5e-9 * abs(v)
    assert _real16(0.0) == "0.0" and _real16(30.000000000000004) == "30."


def test_write_card_counts_and_format(tmp_path):
    fe = mixed_model()
    path = _write(fe, tmp_path / "m.bdf")
    text = path.read_text()
    assert all(len(line) <= 80 for line in text.splitlines() if not line.startswith("$WF"))
    c = _cards(text)
    n_dirs = 4  # material axes at 0, 10, 20, 30 degrees (0 and 10 used twice)
    assert c["GRID"] == fe.n_nodes and c["CQUAD4"] == 6 and c["CBEAM"] == 3 and c["CONM2"] == 2
    assert c["RBE2"] == 2 and c["CELAS2"] == 4 and c["CORD2R"] == n_dirs
    assert c["PCOMP"] == 2 and c["PSHELL"] == 1 and c["PBEAM"] == 2
    assert c["MAT8"] == 1 and c["MAT1"] == 3  # aluminium, foam and the unit-modulus beam material
    assert c["SPC1"] == 2  # "123456" root edge and "3" on one node
    assert text.startswith("SOL 103") and text.rstrip().endswith("ENDDATA")
    bulk = _write(fe, tmp_path / "b.bdf", full_deck=False).read_text()
    assert "SOL 103" not in bulk and "BEGIN BULK" not in bulk


def test_coupled_section_warns(tmp_path):
    with pytest.warns(BdfApproximationWarning, match=r"stiffness entries \[\(3, 4\)\]"):
        write_bdf(mixed_model(coupled_section=True), tmp_path / "c.bdf")


def test_consistent_section_does_not_warn(tmp_path):
    fe = FEModel(nodes=np.array([[0.0, 0, 0], [1.0, 0, 0]]), beam_conn=np.array([[0, 1]]),
                 beam_section=np.array([0]), beam_orient=np.array([[0.0, 1, 0]]),
                 beam_sections=[consistent_section()])
    with warnings.catch_warnings():
        warnings.simplefilter("error", BdfApproximationWarning)
        write_bdf(fe, tmp_path / "ok.bdf")


def test_bad_input_is_named(tmp_path):
    fe = mixed_model()
    fe.shell_matdir[2] = 0.0
    with pytest.raises(InputError, match=r"shell_matdir\[2\]"):
        write_bdf(fe, tmp_path / "x.bdf")
    fe = mixed_model()
    fe.beam_orient[1] = fe.nodes[fe.beam_conn[1, 1]] - fe.nodes[fe.beam_conn[1, 0]]
    with pytest.raises(InputError, match=r"beam_orient\[1\]"):
        write_bdf(fe, tmp_path / "x.bdf")
    fe = mixed_model()
    fe.shell_conn[0, 0] = 999
    with pytest.raises(InputError, match="shell_conn"):
        write_bdf(fe, tmp_path / "x.bdf")


@pytest.mark.skipif(HAVE_PYNASTRAN, reason="checks the message shown when pyNastran is absent")
def test_read_without_pynastran_names_the_extra(tmp_path):
    path = _write(mixed_model(), tmp_path / "m.bdf")
    with pytest.raises(ImportError, match=r"windflutter\[nastran\]"):
        read_bdf(path)


# ---------------------------------------------------------------------------------------------
# reader (pyNastran)
# ---------------------------------------------------------------------------------------------
def _assert_same_model(a: FEModel, b: FEModel, rtol=1e-12, exact_sections=True):
    # 15-character reals keep >= 13 significant digits for coordinates: 1e-12 of the model size
    np.testing.assert_allclose(b.nodes, a.nodes, rtol=0, atol=1e-12 * max(1.0, np.abs(a.nodes).max()))
    np.testing.assert_array_equal(b.shell_conn, a.shell_conn)
    np.testing.assert_array_equal(b.shell_prop, a.shell_prop)
    unit = a.shell_matdir / np.linalg.norm(a.shell_matdir, axis=1)[:, None]
    np.testing.assert_allclose(b.shell_matdir, unit, atol=1e-12)
    assert len(b.shell_properties) == len(a.shell_properties)
    for pa, pb in zip(a.shell_properties, b.shell_properties):
        assert pb.offset == pytest.approx(pa.offset, rel=rtol, abs=1e-15)
        assert len(pa.plies) == len(pb.plies)
        for qa, qb in zip(pa.plies, pb.plies):
            # values are exact decimal round trips here; names only via the $WF block
            assert dataclasses.replace(qb.material, name="") == dataclasses.replace(qa.material, name="")
            assert qb.thickness == pytest.approx(qa.thickness, rel=rtol)
            assert qb.angle == pytest.approx(qa.angle, rel=1e-12, abs=1e-14)
    np.testing.assert_array_equal(b.beam_conn, a.beam_conn)
    np.testing.assert_array_equal(b.beam_section, a.beam_section)
    np.testing.assert_allclose(b.beam_orient, a.beam_orient, rtol=rtol)
    for sa, sb in zip(a.beam_sections, b.beam_sections):
        tol = 0 if exact_sections else 1e-9  # 16-character fields: ~10 significant digits
        np.testing.assert_allclose(sb.stiffness, sa.stiffness, rtol=tol, atol=tol * np.abs(sa.stiffness).max())
        np.testing.assert_allclose(sb.mass, sa.mass, rtol=tol, atol=tol * np.abs(sa.mass).max())
    assert len(b.masses) == len(a.masses)
    for ma, mb in zip(a.masses, b.masses):
        assert (mb.node, mb.mass) == (ma.node, ma.mass)
        np.testing.assert_allclose(mb.inertia, ma.inertia, rtol=rtol)
        np.testing.assert_allclose(mb.offset, ma.offset, rtol=rtol)
    assert len(b.rigid_links) == len(a.rigid_links)
    for ra, rb in zip(a.rigid_links, b.rigid_links):
        assert rb.independent == ra.independent and tuple(rb.dofs) == tuple(ra.dofs)
        np.testing.assert_array_equal(np.sort(rb.dependent), np.sort(ra.dependent))
    assert b.spc == {k: tuple(sorted(v)) for k, v in a.spc.items()}
    assert len(b.springs) == len(a.springs)
    for sa, sb in zip(a.springs, b.springs):
        assert (sb.node_a, sb.node_b) == (sa.node_a, sa.node_b)
        np.testing.assert_allclose(sb.stiffness, sa.stiffness, rtol=rtol)


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
@pytest.mark.parametrize("coupled", [False, True])
def test_round_trip_exact(tmp_path, coupled):
    fe = mixed_model(coupled_section=coupled)
    fe2 = read_bdf(_write(fe, tmp_path / "m.bdf"))
    _assert_same_model(fe, fe2)
    # names, regions and groups come back from the $WF block
    assert [p.name for p in fe2.shell_properties] == [p.name for p in fe.shell_properties]
    assert [s.name for s in fe2.beam_sections] == [s.name for s in fe.beam_sections]
    assert [m.name for m in fe2.masses] == [m.name for m in fe.masses]
    assert [m.material.name for m in fe2.shell_properties[0].plies] == ["glass UD", "foam", "glass UD"]
    assert fe2.region_names == fe.region_names
    for k in fe.element_regions:
        np.testing.assert_array_equal(fe2.element_regions[k], fe.element_regions[k])
    for k in fe.node_groups:
        np.testing.assert_array_equal(fe2.node_groups[k], fe.node_groups[k])


def _strip_meta(path: Path) -> Path:
    out = path.with_name("plain_" + path.name)
    out.write_text("".join(l for l in path.read_text().splitlines(keepends=True) if not l.startswith("$WF")))
    return out


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_standard_cards_alone_carry_representable_model(tmp_path):
    """Without the $WF comments the cards alone must rebuild the model (what NASTRAN sees)."""
    fe = mixed_model()
    fe.beam_sections = [consistent_section("a"), consistent_section("b")]
    fe2 = read_bdf(_strip_meta(_write(fe, tmp_path / "m.bdf")))
    _assert_same_model(fe, fe2, exact_sections=False)
    # without windflutter's data the regions are the NASTRAN properties
    assert fe2.region_names == ["PID1", "PID2", "PID3", "PID4", "PID5"]
    np.testing.assert_array_equal(fe2.element_regions["shell"], fe.shell_prop)
    np.testing.assert_array_equal(fe2.element_regions["beam"], fe.beam_section + 3)


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_standard_cards_drop_only_the_unrepresentable_terms(tmp_path):
    fe = mixed_model(coupled_section=True)
    fe2 = read_bdf(_strip_meta(_write(fe, tmp_path / "m.bdf")))
    K0, K1 = fe.beam_sections[0].stiffness, fe2.beam_sections[0].stiffness
    assert K1[3, 4] == 0.0 and K0[3, 4] != 0.0  # bend-twist coupling is lost for NASTRAN
    mask = np.ones((6, 6), bool)
    mask[3, 4] = mask[4, 3] = False
    np.testing.assert_allclose(K1[mask], K0[mask], rtol=1e-9)


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_edited_card_wins_over_metadata(tmp_path):
    fe = mixed_model(coupled_section=True)
    path = _write(fe, tmp_path / "m.bdf")
    text = path.read_text().replace("      200000000.         500000.", "      100000000.         500000.", 2)
    path.write_text(text)
    with pytest.warns(BdfApproximationWarning, match="PBEAM 4 differs"):
        fe2 = read_bdf(path)
    assert fe2.beam_sections[0].stiffness[0, 0] == pytest.approx(1e8)
    assert fe2.beam_sections[0].stiffness[3, 4] == 0.0


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_nastran_mass_properties_match_hand_calculation(tmp_path):
    """pyNastran's mass summary of the written deck vs mass computed by hand from the model
    (independent of our card mapping): checks PCOMP/PSHELL densities, PBEAM NSM and CONM2."""
    from pyNastran.bdf.bdf import BDF
    from pyNastran.bdf.mesh_utils.mass_properties import mass_properties

    fe = mixed_model(flat=True)
    path = _write(fe, tmp_path / "m.bdf")
    model = BDF(debug=None)
    model.read_bdf(str(path))
    mass, cg, _ = mass_properties(model, reference_point=np.zeros(3))
    # hand calculation: flat 0.5 m x 0.3 m quads, 0.4 m beams along global x
    area = 0.5 * 0.3
    m_el = np.array([area * fe.shell_properties[p].mass_per_area for p in fe.shell_prop])
    x_el = fe.nodes[fe.shell_conn].mean(axis=1)[:, 0]
    m_bm = np.array([0.4 * fe.beam_sections[s].mass[0, 0] for s in fe.beam_section])
    x_bm = fe.nodes[fe.beam_conn].mean(axis=1)[:, 0]
    m_pt = np.array([m.mass for m in fe.masses])
    x_pt = np.array([fe.nodes[m.node, 0] + m.offset[0] for m in fe.masses])
    total = m_el.sum() + m_bm.sum() + m_pt.sum()
    xcg = (m_el @ x_el + m_bm @ x_bm + m_pt @ x_pt) / total
    # pyNastran sums element masses in closed form: agreement to round-off (1e-10);
    # the x-coordinate of the CG is unaffected by the beams' cross-sectional CG offsets
    assert mass == pytest.approx(total, rel=1e-10)
    assert cg[0] == pytest.approx(xcg, rel=1e-10)


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_conm2_inertia_convention(tmp_path):
    """A single CONM2 with offset and products of inertia: NASTRAN's CG (pyNastran) must be
    node + offset and its inertia about the CG the tensor J we wrote."""
    from pyNastran.bdf.bdf import BDF
    from pyNastran.bdf.mesh_utils.mass_properties import mass_properties

    J = np.array([[2.0, 0.1, -0.2], [0.1, 3.0, 0.3], [-0.2, 0.3, 4.0]])
    node = np.array([1.0, 2.0, -0.5])
    off = np.array([0.1, -0.05, 0.2])
    fe = FEModel(nodes=node[None, :], masses=[LumpedMass(0, 25.0, J, off)])
    path = write_bdf(fe, tmp_path / "p.bdf", full_deck=False)
    model = BDF(debug=None)
    model.read_bdf(str(path), punch=True)
    mass, cg, I6 = mass_properties(model, reference_point=np.zeros(3), inertia_reference="cg")
    r = node + off
    Iref = J
    assert mass == 25.0
    np.testing.assert_allclose(cg, r, rtol=1e-14)
    np.testing.assert_allclose(I6[:3], np.diag(Iref), rtol=1e-12)
    # the card stores I21 = -J_xy etc. (MSC QRG, CONM2 remark: matrix [[I11, -I21, -I31], ...]);
    # pyNastran's CONM2.Inertia() implements that matrix, so it must give back J exactly
    (conm2,) = model.masses.values()
    np.testing.assert_allclose(np.array(conm2.Inertia()), J, rtol=1e-12)


HAND_DECK = """\
$ hand-written small-field deck (foreign file: THETA, CBAR/PBAR, CONM2 CID=-1, SPC, CELAS1)
BEGIN BULK
GRID    1               0.      0.      0.
GRID    2               1.      0.      0.
GRID    3               1.      1.      0.
GRID    4               0.      1.      0.
GRID    5               2.      0.      0.
CQUAD4  11      1       1       2       3       4       30.
PSHELL  1       7       .004    7
MAT1    7       70.+9           .3      2700.
CBAR    21      2       2       5       0.      0.      1.
PBAR    2       7       1.-3    2.-7    3.-7    4.-7    0.5
CONM2   31      5       -1      3.      2.1     0.      0.
SPC     1       1       123456  0.      4       123456  0.
CELAS1  41      5       5       3
PELAS   5       1.+4
ENDDATA
"""


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_foreign_deck(tmp_path):
    path = tmp_path / "hand.bdf"
    path.write_text(HAND_DECK)
    fe = read_bdf(path)
    assert fe.n_nodes == 5 and fe.shell_conn.tolist() == [[0, 1, 2, 3]]
    # THETA = 30 deg from edge G1-G2 (the global x axis here), about the normal +z
    np.testing.assert_allclose(fe.shell_matdir[0], [np.cos(np.pi / 6), np.sin(np.pi / 6), 0.0], atol=1e-14)
    (ply,) = fe.shell_properties[0].plies
    assert ply.thickness == 0.004 and ply.material.E == 70e9 and ply.material.rho == 2700.0
    # PBAR: EA = E A, EIz = E I1, EIy = E I2, GJ = G J; K1, K2 blank = shear-rigid; mass = rho A
    sec = fe.beam_sections[0]
    G = 70e9 / 2.6
    np.testing.assert_allclose(np.diag(sec.stiffness)[[0, 3, 4, 5]], [70e6, G * 4e-7, 70e9 * 3e-7, 70e9 * 2e-7],
                               rtol=1e-12)
    assert sec.mass[0, 0] == pytest.approx(2700.0 * 1e-3 + 0.5)  # rho A + NSM
    np.testing.assert_allclose(fe.beam_orient[0], [0, 0, 1])
    # CONM2 with CID=-1: absolute CG position -> offset from the node
    np.testing.assert_allclose(fe.masses[0].offset, [0.1, 0.0, 0.0], atol=1e-15)
    assert fe.spc == {0: (0, 1, 2, 3, 4, 5), 3: (0, 1, 2, 3, 4, 5)}
    assert fe.springs[0].node_a == 4 and fe.springs[0].node_b is None
    assert fe.springs[0].stiffness[2, 2] == 1e4 and np.count_nonzero(fe.springs[0].stiffness) == 1


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_unsupported_element_is_named(tmp_path):
    path = tmp_path / "tria.bdf"
    path.write_text(HAND_DECK.replace("CELAS1  41      5       5       3\n",
                                      "CTRIA3  51      1       1       2       3\n"))
    with pytest.raises(InputError, match="CTRIA3"):
        read_bdf(path)


# ---------------------------------------------------------------------------------------------
# assembled matrices
# ---------------------------------------------------------------------------------------------
def _assemble(fe):
    from windflutter.structure.assembly import assemble

    return assemble(fe, check=False)


def _matrices_equal(fe, fe2):
    st, st2 = _assemble(fe), _assemble(fe2)
    for A, B in ((st.M, st2.M), (st.K, st2.K), (st.T, st2.T)):
        D = (A - B).tocoo()
        scale = np.abs(A.data).max()
        # round-off only: the node coordinates, offsets and thicknesses are exact decimal
        # round trips; the material axes are normalised (1e-16); allow 1e-10 of the largest entry
        assert (np.abs(D.data).max() if D.nnz else 0.0) <= 1e-10 * scale


def _beams_masses_links_model():
    full = mixed_model()
    keep = np.unique(np.concatenate([full.beam_conn.ravel(), [full.rigid_links[0].independent]]))
    return FEModel(nodes=full.nodes, beam_conn=full.beam_conn, beam_section=full.beam_section,
                   beam_orient=full.beam_orient, beam_sections=[consistent_section("a"), full.beam_sections[1]],
                   masses=full.masses[:1], rigid_links=full.rigid_links[1:], springs=[],
                   spc={int(keep[0]): (0, 1, 2, 3, 4, 5)})


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
@pytest.mark.parametrize("build", [_beams_masses_links_model, mixed_model], ids=["beams_masses_links", "full_model"])
def test_round_trip_same_matrices(tmp_path, build):
    """Same M, K and T after the round trip, both through the exact $WF data and through the
    standard cards alone: a beam + CONM2 + RBE2 model (no shells), and the full model (shells:
    laminates at angles, offsets, twisted material axes; beams, masses, RBE2, SPC, springs)."""
    fe = build()
    path = _write(fe, tmp_path / "m.bdf")
    _matrices_equal(fe, read_bdf(path))
    _matrices_equal(fe, read_bdf(_strip_meta(path)))


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_matrix_comparison_detects_a_one_degree_ply_error(tmp_path):
    """The matrix check above must be able to fail: a 1-degree ply-angle error is detected."""
    fe = mixed_model()
    fe2 = read_bdf(_write(fe, tmp_path / "m.bdf"))
    p = fe2.shell_properties[0]
    plies = (dataclasses.replace(p.plies[0], angle=p.plies[0].angle + np.radians(1.0)),) + p.plies[1:]
    fe2.shell_properties[0] = dataclasses.replace(p, plies=plies)
    with pytest.raises(AssertionError):
        _matrices_equal(fe, fe2)


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
@pytest.mark.parametrize("old,new,field", [
    ("PSHELL  1       7       .004    7\n", "PSHELL  1       7       .004    7               7               2.\n",
     "NSM"),
    ("CBAR    21      2       2       5       0.      0.      1.\n",
     "CBAR    21      2       2       5       0.      0.      1.\n        1\n", "PA/PB"),
    ("PSHELL  1       7       .004    7\n", "PSHELL  1       7       .004    7       0.5\n", "PSHELL 1"),
    # 12I/T^3 = 0 (no bending stiffness) is not the homogeneous plate either (was read as 1)
    ("PSHELL  1       7       .004    7\n", "PSHELL  1       7       .004    7       0.\n", "PSHELL 1"),
])
def test_unrepresentable_foreign_cards_are_refused(tmp_path, old, new, field):
    """Non-structural shell mass, pin flags and non-homogeneous PSHELLs have no FEModel
    equivalent: refuse with the card named rather than silently change the model."""
    path = tmp_path / "bad.bdf"
    assert old in HAND_DECK
    path.write_text(HAND_DECK.replace(old, new))
    with pytest.raises(InputError, match=field):
        read_bdf(path)


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_round_trip_bundled_nrel5mw_blade(tmp_path):
    """Integration: a coarse shell model of the bundled NREL 5 MW blade (real layup: tens of
    laminates, per-element material axes) gives the same M and K after write -> read."""
    from windflutter.mesh.settings import MeshSettings
    from windflutter.mesh.turbine import build_model
    from windflutter.model.windio import load_turbine

    fe, _ = build_model(load_turbine("nrel5mw"), MeshSettings(model="shell", part="blade", n_chord=16, n_span=10,
                                                              n_web=2))
    assert len(fe.shell_properties) > 10
    fe2 = read_bdf(_write(fe, tmp_path / "blade.bdf"))
    _assert_same_model(fe, fe2)
    _matrices_equal(fe, fe2)


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
def test_diaphragm_mpcs_as_pynastran_reads_them(tmp_path):
    """The shell blade's tip rib goes to NASTRAN as MPC equations: read by pyNastran (not by our
    reader), every constrained motion of windflutter's map satisfies them, and they remove exactly
    the DOFs the map removes."""
    from windflutter.mesh.settings import MeshSettings
    from windflutter.mesh.turbine import build_model
    from windflutter.model.windio import load_turbine
    from windflutter.structure.assembly import assemble
    from windflutter.structure.bdf.read import load_deck

    fe, _ = build_model(load_turbine("nrel5mw"), MeshSettings(model="shell", part="blade", n_chord=12, n_span=4))
    assert len(fe.diaphragms) == 1
    path = _write(fe, tmp_path / "blade.bdf", full_deck=True)
    assert "MPC = 2" in Path(path).read_text()
    deck = load_deck(Path(path))
    eqs = [c for cards in deck.mpcs.values() for c in cards]
    C = np.zeros((len(eqs), fe.n_dof))
    for r, c in enumerate(eqs):
        for nid, comp, a in zip(c.nodes, c.components, c.coefficients):
            C[r, 6 * (nid - 1) + int(comp) - 1] += a
    st = assemble(fe)
    T = st.T.toarray()
    assert np.abs(C @ T).max() < 1e-12 * np.abs(C).max()
    n_spc = sum(len(v) for v in fe.spc.values()) + len(st.auto_spc)
    assert T.shape[1] == fe.n_dof - len(eqs) - n_spc == fe.n_dof - np.linalg.matrix_rank(C) - n_spc


# ---------------------------------------------------------------------------------------------
# the card tables
# ---------------------------------------------------------------------------------------------
def _distinct_values(card):
    """A value per field, each different, valid where pyNastran checks them (PBEAM: I1 I2 >
    I12^2 and X/XB = 1 at end B; keywords from the QRG)."""
    special = {"LAM": "SYM", "SOUT": "YES", "FT": "HILL", "SO": "YESA", "CM": "123", "C": "123", "OFFT": "GGG",
               "I12": 0.5, "I12(B)": 0.5, "X/XB": 1.0}
    vals = {f.name: special.get(f.name, 10 + i if f.kind == "I" else 3.5 if f.kind == "IR" else i + 0.25)
            for i, f in enumerate(card.fields)}
    rows = [tuple(special.get(f.name, 50 + i if f.kind == "I" else i + 0.75) for i, f in enumerate(card.repeat))]
    return vals, (rows if card.repeat else [])


@pytest.mark.nastran
@pytest.mark.skipif(not HAVE_PYNASTRAN, reason="pyNastran not installed: run `make test-nastran`")
@pytest.mark.parametrize("name", sorted(n for n, c in CARDS.items() if any(f.attr for f in c.fields)))
def test_card_table_positions_match_pynastran(name):
    """Each card of the table, written by the table with a distinct value in every field, is
    parsed by pyNastran (an independent reading of the QRG layout): every field the reader
    takes must come back by its name with the value put at that name's position."""
    from pyNastran.bdf.bdf import BDF

    card = CARDS[name]
    vals, rows = _distinct_values(card)
    model = BDF(debug=None)
    model.log.level = "error"
    model.add_card(card.text(rows, **vals).splitlines(), name, is_list=False)
    parsed = [*model.elements.values(), *model.properties.values(), *model.materials.values(),
              *model.masses.values(), *model.rigid_elements.values(), *(c for cs in model.spcs.values() for c in cs)]
    (obj,) = parsed
    got = card.read(obj)
    # pyNastran (as the QRG) ignores the PBAR shear factors K1, K2 when I12 != 0
    unchecked = {"K1", "K2"} if name == "PBAR" else set()
    for f in card.fields:
        if f.attr is not None and f.name not in unchecked:
            assert np.atleast_1d(got[f.name])[0] == vals[f.name], f.name
    for j, f in enumerate(card.repeat):
        if f.attr is not None:
            assert list(np.atleast_1d(got[f.name])) == [rows[0][j]], f.name
    if name in ("CBAR", "CBEAM"):  # X1..X3 and the offsets as pyNastran's parsed vectors
        np.testing.assert_array_equal(got["X"], [vals["X1"], vals["X2"], vals["X3"]])
        np.testing.assert_array_equal(got["WA"], [vals["W1A"], vals["W2A"], vals["W3A"]])
        np.testing.assert_array_equal(got["WB"], [vals["W1B"], vals["W2B"], vals["W3B"]])


def test_card_table_fills_fields_by_name():
    """The writer's card text: a field lands in its table position (16-character fields after the
    8-character name, four a line); the card ends after the last field given; unknown names and
    ill-sized repeated groups are refused."""
    text = CARDS["CELAS2"].text(EID=7, K=2.5, G1=3, C1=4)
    assert text == "CELAS2*" + " " + "7".rjust(16) + "2.5".rjust(16) + "3".rjust(16) + "4".rjust(16) + "\n"
    lines = CARDS["CONM2"].text(EID=1, G=2, CID=0, M=5.0, I33=9.0).splitlines()
    assert len(lines) == 4 and lines[3] == "*".ljust(8) + " " * 16 + "9.".rjust(16)
    assert CARDS["SPC1"].text([(5,), (6,)], SID=1, C="123").split() == ["SPC1*", "1", "123", "5", "6"]
    with pytest.raises(KeyError, match="XX"):
        CARDS["GRID"].text(XX=1)
    with pytest.raises(ValueError, match="repeated group"):
        CARDS["PCOMP"].text([(1, 0.1)], PID=1)
