"""NASTRAN bulk-data export and import of an :class:`~windflutter.structure.fem.FEModel`.

``write_bdf`` writes the deck as plain text in *large-field* fixed format (16-character fields,
about ten significant digits) and needs no third-party package.  ``read_bdf`` parses a deck
with pyNastran (optional extra ``pip install 'windflutter[nastran]'``) and builds an FEModel.

Card mapping (all in the basic coordinate system; grid id = node index + 1)
---------------------------------------------------------------------------
=====================  ======================================================================
FEModel                NASTRAN
=====================  ======================================================================
nodes                  GRID
shell elements         CQUAD4 with MCID (one CORD2R per distinct material axis; NASTRAN
                       projects the MCID x-axis onto the element plane, which is exactly
                       windflutter's ``shell_matdir`` convention) and ZOFFS = property offset
laminate               PCOMP (plies: MID, T, THETA in degrees from the material axis);
                       a single isotropic ply is written as PSHELL (MID1 = MID2 = MID3)
materials              MAT1 (isotropic), MAT8 (orthotropic: E1 E2 NU12 G12 G1Z=G13 G2Z=G23)
beam elements          CBEAM with orientation vector; PBEAM + a unit-modulus MAT1 (E = 1 Pa,
                       nu = 0.3) so that A = EA, I1 = EIz, I2 = EIy, I12 = -EIyz, J = GJ/G,
                       K1 = GAy/(G A), K2 = GAz/(G A); all mass as non-structural mass:
                       NSM = m, M1/M2 = mass-centre offset, NSI = torsional inertia about it
lumped masses          CONM2 (CID 0: offset and inertia in basic axes)
rigid links            RBE2
SPC                    SPC1 (set 1)
springs                CELAS2 per non-zero diagonal term (scalar spring between like DOFs)
=====================  ======================================================================

What standard cards cannot carry -- the off-diagonal terms of a general 6x6 beam section
(extension-twist, bend-twist, shear couplings, tension-centre offsets), the sectional rotary
inertia about y and z, and off-diagonal spring terms -- is reported with a
:class:`BdfApproximationWarning` and, together with names, regions and node groups, stored
exactly in ``$WF`` comment lines that NASTRAN ignores.  ``read_bdf`` restores the exact data
from those comments *only if* the standard cards still hold the values written (an edited
card wins, with a warning), so the round trip ``read_bdf(write_bdf(fe))`` is lossless.

Layout: the field table of every card (QRG names, types, the pyNastran attribute read) is in
:mod:`windflutter.structure.bdf.cards`; the writer (:mod:`~windflutter.structure.bdf.write`)
fills cards by field name, the reader (:mod:`~windflutter.structure.bdf.read`) takes named
fields back from pyNastran's parsed cards; :mod:`~windflutter.structure.bdf.beam` maps beam
sections to PBEAM / PBAR values and back.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.bdf import read as _read
from windflutter.structure.bdf.cards import BdfApproximationWarning, real16 as _real16  # noqa: F401
from windflutter.structure.bdf.read import NASTRAN_EXTRA_HINT
from windflutter.structure.bdf.write import bdf_text
from windflutter.structure.fem import FEModel

__all__ = ["write_bdf", "read_bdf", "BdfApproximationWarning", "NASTRAN_EXTRA_HINT"]


def write_bdf(fe: FEModel, path: str | Path, *, title: str = "windflutter model", full_deck: bool = True,
              n_modes: int = 20) -> Path:
    """Write an FEModel as a NASTRAN deck (large-field fixed format).

    Parameters
    ----------
    fe : the model (SI units; written as is, so the deck is in m, kg, s, N).
    path : output file (``.bdf``/``.dat``).
    title : TITLE line of the case control.
    full_deck : if True write a SOL 103 deck (executive + case control with ``SPC = 1``,
        ``METHOD = 1``, EIGRL for ``n_modes`` modes, consistent mass); else bulk data only.
    n_modes : number of modes requested on the EIGRL card.

    Returns
    -------
    Path of the written file.

    Warns
    -----
    BdfApproximationWarning
        when a beam section or spring has terms the standard cards cannot carry (see module
        docstring); windflutter's :func:`read_bdf` still restores them exactly.
    """
    path = Path(path)
    text = bdf_text(fe, title, full_deck, int(n_modes))
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    tmp.replace(path)
    return path


def read_bdf(path: str | Path) -> FEModel:
    """Read a NASTRAN deck into an FEModel (needs the ``nastran`` extra: pyNastran).

    Supported: GRID (any CP), CQUAD4 (THETA or MCID, ZOFFS) with PSHELL/PCOMP and MAT1/MAT8,
    CBEAM with PBEAM (constant section) and CBAR with PBAR, CONM2 (CID 0/-1), RBE2, SPC1/SPC
    (all sets), the MPC cards of windflutter's diaphragms (from the ``$WF`` data), CELAS1/CELAS2 between like components.  Node indices follow ascending GRID id;
    elements ascending element id.  Anything else raises :class:`InputError` naming the cards.
    Decks written by :func:`write_bdf` are restored exactly (names, regions, node groups and
    the full 6x6 beam sections from the ``$WF`` comments).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("path", str(path), "an existing NASTRAN bulk-data file")
    model = _read.load_deck(path)
    meta = _read.read_meta(path)
    source = str(path)
    _read.check_supported(model, source)
    grids = _read.Grids(model, source)
    shell_properties, shell_conn, shell_prop, shell_matdir = _read.shells(
        model, meta, grids, _read.materials(model, meta))
    beam_pids, beam_sections = _read.beam_sections(model, meta, source)
    beam_conn, beam_section, beam_orient = _read.beams(model, grids, beam_pids)
    regions, region_names, groups = _regions_and_groups(
        meta, source, len(grids.xyz), (shell_prop, shell_properties), (beam_section, beam_pids))
    fe = FEModel(
        nodes=grids.xyz, shell_conn=shell_conn, shell_prop=shell_prop, shell_matdir=shell_matdir,
        shell_properties=shell_properties, beam_conn=beam_conn, beam_section=beam_section,
        beam_orient=beam_orient, beam_sections=beam_sections, masses=_read.masses(model, meta, grids),
        rigid_links=_read.rigid_links(model, meta, grids), diaphragms=_read.diaphragms(model, meta, source),
        springs=_read.springs(model, meta, grids),
        spc=_read.spcs(model, grids), node_groups=groups, element_regions=regions,
        region_names=region_names,
    )
    fe.check()
    return fe


def _regions_and_groups(meta: dict, source: str, n_nodes: int, shell: tuple, beam: tuple):
    """Element regions, region names and node groups from the ``$WF`` data where they fit the
    deck; for a foreign deck one region per property (shells first, then beams)."""
    (shell_prop, shell_properties), (beam_section, beam_pids) = shell, beam
    n_sh, n_bm = len(shell_prop), len(beam_section)
    regions = {}
    for kind, ids in meta.get("element_regions", {}).items():
        expect = {"shell": n_sh, "beam": n_bm}.get(kind)
        if expect is None or len(ids) == expect:
            regions[kind] = np.asarray(ids, np.int64)
    region_names = list(meta.get("region_names", []))
    if not meta:
        regions = {"shell": shell_prop.copy(), "beam": beam_section + len(shell_properties)}
        region_names = [p.name for p in shell_properties] + [f"PID{pid}" for pid in beam_pids]
    groups = {k: np.asarray(v, np.int64) for k, v in meta.get("node_groups", {}).items()
              if not v or max(v) < n_nodes}
    if meta and (meta.get("n_shell") != n_sh or meta.get("n_beam") != n_bm):
        warnings.warn(f"{source}: element counts differ from the windflutter data; regions may not apply",
                      BdfApproximationWarning, stacklevel=3)
    return regions, region_names, groups
