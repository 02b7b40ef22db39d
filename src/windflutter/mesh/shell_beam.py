"""Beam properties of a shell blade, station by station, from the shell model itself (issue 33 item 3).

At each output station a segment of the shell blade is cut out (the skin and web elements between
two node rings, a chord or so either side of the station), and
:func:`windflutter.structure.equivalent_beam.section_properties` clamps its root ring, loads its tip
ring with six unit loads and reads, between two rings half a chord apart around the station: the 6 x 6
stiffness, the mass per length and inertia, the tension (elastic) centre, the shear centre and the
mass centre -- about the blade's reference axis, in the section axes of
:class:`~windflutter.model.blade.BeamProperties` (x along the span, y flapwise towards the suction
side, z along the chord towards the trailing edge, turned by the twist).  The result is a
:class:`BeamProperties` (for a beam model or a BeamDyn file) with the centres beside it, and the
table that compares it with the turbine file's 6 x 6 (PreComp or another cross-section code).

The segment's end rings restrain warping; the rings where the motion is read are a chord from them.
On a closed box that leaves torsion and the shear centre within 2-4 % of thin-walled theory
(tests/structure/test_equivalent_beam.py), bending and the centres of tension and mass within 0.1 %.
Near the root and the tip the window is cut off by the blade's ends (``clipped``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from windflutter.errors import InputError
from windflutter.mesh.settings import MeshSettings
from windflutter.model.blade import PERM_BEAMDYN_TO_SECTION
from windflutter.model.turbine import BeamProperties
from windflutter.mesh.shell_section import station_section
from windflutter.structure.equivalent_beam import section_properties

#: the reading rings half a chord apart; the segment's ends a chord beyond them (in stations)
RING_CHORDS, END_CHORDS = 0.5, 1.0


@dataclass(frozen=True)
class ShellBeamTable:
    """The shell blade's beam properties at ``s`` (span fraction of the reference axis).

    ``beam``: :class:`BeamProperties` (BeamSection order, about the reference axis, section axes);
    ``tension_centre``, ``shear_centre``, ``mass_centre`` (n, 2): (flapwise y, chordwise z) offsets
    from the reference axis (m); ``clipped`` (n,): the segment cut off by a blade end; ``asymmetry``
    (n,): the extraction's check (module :mod:`windflutter.structure.equivalent_beam`).
    """

    s: np.ndarray
    beam: BeamProperties
    tension_centre: np.ndarray
    shear_centre: np.ndarray
    mass_centre: np.ndarray
    clipped: np.ndarray
    asymmetry: np.ndarray


def station_planes(fe, sec):
    """(points (ns+1, 3) on the reference axis, station index of every node, node on a station plane)."""
    p = np.asarray(sec.origin, float)
    t = np.asarray(sec.e_span, float)
    t = t / np.linalg.norm(t, axis=1, keepdims=True)
    w = np.asarray(sec.width, float)
    P0 = np.vstack([p - 0.5 * w[:, None] * t, p[-1] + 0.5 * w[-1] * t[-1]])
    T = np.vstack([t, t[-1:]])
    X = np.asarray(fe.nodes, float)
    D = np.einsum("nsi,si->ns", X[:, None, :] - P0[None], T)
    st = np.argmin(np.abs(D), axis=1)
    return P0, st, np.abs(D[np.arange(len(X)), st]) < 0.2 * w.min()


def shell_segment(fe, st, on, k0: int, k1: int):
    """The shell sub-model between stations k0 and k1, and a function: station -> its ring's nodes."""
    conn = np.asarray(fe.shell_conn)
    seg, mp = fe.shell_part(np.all((st[conn] >= k0) & (st[conn] <= k1) & on[conn], axis=1))
    return seg, (lambda k: mp[np.flatnonzero(on & (st == k) & (mp >= 0))])


#: how a station's section is read: ``"segment"`` (a segment of the blade loaded through rigid end
#: rings, module docstring) or ``"section"`` (the station's ring extruded into a prism with periodic
#: ends, :mod:`windflutter.mesh.shell_section`: no end restraint, no taper)
EXTRACTIONS = ("segment", "section")


def shell_beam_table(turbine, n_stations: int = 20, settings: MeshSettings | None = None,
                     extraction: str = "segment") -> ShellBeamTable:
    """The beam properties of ``turbine``'s shell blade at ``n_stations`` stations (module docstring).

    ``settings``: the shell mesh (default: the default shell mesh of a blade clamped at the root);
    ``extraction``: one of :data:`EXTRACTIONS`.
    """
    from windflutter.mesh.turbine import build_model

    if not isinstance(n_stations, (int, np.integer)) or not 2 <= n_stations <= 200:
        raise InputError("n_stations", n_stations, "a whole number of stations in [2, 200]")
    if extraction not in EXTRACTIONS:
        raise InputError("extraction", extraction, f"one of {', '.join(EXTRACTIONS)}")
    st0 = settings or MeshSettings(model="shell", part="blade")
    if st0.model != "shell" or st0.part != "blade":
        raise InputError("settings", (st0.model, st0.part), "a shell model of the blade (part blade)")
    fe, sec = build_model(turbine, st0)
    P0, st, on = station_planes(fe, sec)
    ns = len(P0) - 1
    row = np.linalg.norm(np.diff(P0, axis=0), axis=1)
    chord = np.r_[sec.chord, sec.chord[-1]]
    ec = np.vstack([sec.e_chord, sec.e_chord[-1:]])
    js = np.unique(np.round(np.linspace(1, ns - 1, n_stations)).astype(int))
    rows = []
    for j in js:
        if extraction == "section":
            t = P0[min(j + 1, ns)] - P0[max(j - 1, 0)]
            t /= np.linalg.norm(t)
            r = station_section(fe, st, on, j, P0[j], t, np.cross(ec[j], t), chord[j])
            rows.append((float(np.sum(row[:j])), r, False))
            continue
        half = max(1, int(np.ceil(0.5 * RING_CHORDS * chord[j] / row[min(j, ns - 1)])))
        gap = max(2, int(np.ceil(END_CHORDS * chord[j] / row[min(j, ns - 1)])))
        ka, kb = max(1, j - half), min(ns - 1, j + half)
        k0, k1 = max(0, ka - gap), min(ns, kb + gap)
        clipped = (ka - gap < 0) or (kb + gap > ns)
        seg, ring = shell_segment(fe, st, on, k0, k1)
        e1 = P0[kb] - P0[ka]
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(ec[j], e1)  # flapwise, towards the suction side (e_chord x e_span)
        r = section_properties(seg, ring(k0), ring(k1), (ring(ka), ring(kb)), (P0[ka], P0[kb]), axis=e1, e2=e2)
        s_mid = 0.5 * (float(np.linalg.norm(P0[ka] - P0[0])) + float(np.linalg.norm(P0[kb] - P0[0])))
        rows.append((s_mid, r, clipped))
    L = float(np.sum(row))
    s = np.array([x[0] for x in rows]) / L
    K = np.array([x[1].stiffness for x in rows])
    M = np.array([x[1].mass for x in rows])
    tw = np.interp(s, turbine.blade.s, turbine.blade.twist)
    bp = BeamProperties(s=s, stiffness=0.5 * (K + K.transpose(0, 2, 1)), mass=M, twist=tw, length=L,
                        source=f"the shell model ({ns} x {fe_chord_count(fe, st)} elements), " +
                        ("unit loads on segments" if extraction == "segment" else "periodic prisms of the stations"))
    return ShellBeamTable(s=s, beam=bp, tension_centre=np.array([x[1].tension_centre for x in rows]),
                          shear_centre=np.array([x[1].shear_centre for x in rows]),
                          mass_centre=np.array([x[1].mass_centre for x in rows]),
                          clipped=np.array([x[2] for x in rows]), asymmetry=np.array([x[1].asymmetry for x in rows]))


#: a station whose extraction failed is left out of :func:`shell_blade_properties`: its stiffness not
#: positive definite, or its measured compliance asymmetric by more than this (interior stations of
#: the IEA 22 MW and NREL 5 MW blades: 0.05-0.2; the failures seen, a station or two near the tip
#: when the reading rings are an element apart: 1.3 and 14)
ASYMMETRY_LIMIT = 0.5


def usable_stations(table: ShellBeamTable) -> np.ndarray:
    """(n,) bool: the stations of ``table`` a beam model can use (:data:`ASYMMETRY_LIMIT`)."""
    pd = np.array([np.linalg.eigvalsh(0.5 * (k + k.T)).min() > 0 for k in table.beam.stiffness])
    return pd & (np.asarray(table.asymmetry) <= ASYMMETRY_LIMIT)


def shell_blade_properties(turbine, n_stations: int = 40, settings: MeshSettings | None = None,
                           extraction: str = "segment") -> BeamProperties:
    """The 6 x 6 stiffness and mass of ``turbine``'s shell blade (:func:`shell_beam_table`) as the beam
    model's blade properties.  Every station keeps its mass and twist (read from the shell's own
    elements); a station whose stiffness reading is not usable (:func:`usable_stations`) takes the
    stiffness interpolated along the span between the usable ones, constant beyond the end ones.
    (Dropping such a station whole, as before Dec 2026, held the last usable station's mass too: on
    the IEA 22 MW, whose two tip stations' readings fail with MITC4's shear, the section at r/R 0.94
    over the last 6 % of the span, its 2nd flap 8 % low.)  The stations cut by a blade end are kept
    (the root's and the tip's stiffness, read on a shorter segment).  Use it through
    :func:`with_shell_blade_properties`: the beam of the same blade as the shell model."""
    tab = shell_beam_table(turbine, n_stations, settings, extraction)
    ok = usable_stations(tab)
    if ok.sum() < 2:
        raise InputError("n_stations", n_stations, "more stations: fewer than two gave a usable section")
    b = tab.beam
    s = np.asarray(b.s, float)
    K = np.asarray(b.stiffness, float).reshape(len(s), 36)
    K = np.stack([np.interp(s, s[ok], K[ok, j]) for j in range(36)], axis=1).reshape(-1, 6, 6)
    return BeamProperties(s=b.s, stiffness=K, mass=b.mass, twist=b.twist, length=b.length,
                          source=f"{b.source}; the stiffness of {int(ok.sum())} of {len(ok)} stations usable")


def with_shell_blade_properties(turbine, n_stations: int = 40, settings: MeshSettings | None = None,
                                extraction: str = "segment"):
    """``turbine`` whose blade's 6 x 6 properties (``blade.beam``, what the beam model reads) are those
    of its own shell blade (:func:`shell_blade_properties`) instead of the file's: a beam model of the
    blade the shell model describes (the layup, meshed as ``settings``), for comparing the two models
    on the same blade (docs/mesh.md).  Everything else is ``turbine``'s."""
    bp = shell_blade_properties(turbine, n_stations, settings, extraction)
    return dataclasses.replace(turbine, blade=dataclasses.replace(turbine.blade, beam=bp))


def fe_chord_count(fe, st) -> int:
    """Skin nodes on the root station ring (the elements around a section)."""
    return int(np.sum(st == 0))


#: the table's columns: name, unit, description
COLUMNS = (("s", "-", "span fraction of the reference axis"), ("r", "m", "distance along the reference axis"),
           ("mass", "kg/m", "mass per length"),
           ("cm_flap", "m", "mass centre, flapwise offset from the reference axis"),
           ("cm_edge", "m", "mass centre, chordwise offset (towards the trailing edge)"),
           ("tc_flap", "m", "tension (elastic) centre, flapwise"), ("tc_edge", "m", "tension centre, chordwise"),
           ("sc_flap", "m", "shear centre, flapwise"), ("sc_edge", "m", "shear centre, chordwise"),
           ("EA", "N", "axial stiffness"), ("GJ", "N m^2", "torsion stiffness (1 / compliance)"),
           ("EI_flap", "N m^2", "flapwise bending stiffness about the tension centre"),
           ("EI_edge", "N m^2", "edgewise bending stiffness about the tension centre"),
           ("GA_flap", "N", "flapwise shear stiffness"), ("GA_edge", "N", "chordwise shear stiffness"),
           ("file_mass", "kg/m", "the turbine file's mass per length"), ("file_EA", "N", "the file's K[axial]"),
           ("file_GJ", "N m^2", "the file's K[torsion]"), ("file_EI_flap", "N m^2", "the file's flapwise K"),
           ("file_EI_edge", "N m^2", "the file's edgewise K"), ("clipped", "-", "1: segment cut by a blade end"),
           ("usable", "-", "1: the stiffness reading passed its checks (positive definite, compliance asymmetry "
                           "at most ASYMMETRY_LIMIT); 0: failed, not used by shell_blade_properties"))


def table_rows(table: ShellBeamTable, file_beam: BeamProperties | None) -> list[dict]:
    """One dict per station with :data:`COLUMNS` (the file's columns NaN without a 6 x 6)."""
    out = []
    ok = usable_stations(table)
    for i, s in enumerate(table.s):
        K, M = table.beam.stiffness[i], table.beam.mass[i]
        C = np.linalg.inv(K)
        Kb = np.linalg.inv(C[4:, 4:])  # bending about the tension centre
        d = {"s": s, "r": s * table.beam.length, "mass": M[0, 0],
             "cm_flap": table.mass_centre[i, 0], "cm_edge": table.mass_centre[i, 1],
             "tc_flap": table.tension_centre[i, 0], "tc_edge": table.tension_centre[i, 1],
             "sc_flap": table.shear_centre[i, 0], "sc_edge": table.shear_centre[i, 1],
             "EA": K[0, 0], "GJ": 1.0 / C[3, 3], "EI_flap": Kb[1, 1], "EI_edge": Kb[0, 0],
             "GA_flap": 1.0 / C[1, 1], "GA_edge": 1.0 / C[2, 2], "clipped": int(table.clipped[i]),
             "usable": int(ok[i])}
        f = {k: np.nan for k in ("file_mass", "file_EA", "file_GJ", "file_EI_flap", "file_EI_edge")}
        if file_beam is not None:
            Kf = np.array([np.interp(s, file_beam.s, file_beam.stiffness[:, a, b]) for a in range(6) for b in range(6)])
            Kf = Kf.reshape(6, 6)
            f = {"file_mass": float(np.interp(s, file_beam.s, file_beam.mass[:, 0, 0])), "file_EA": Kf[0, 0],
                 "file_GJ": Kf[3, 3], "file_EI_flap": Kf[5, 5], "file_EI_edge": Kf[4, 4]}
        d.update(f)
        out.append(d)
    return out


def write_csv(path, rows: list[dict]) -> None:
    """The table as CSV: a header of column names with units, one line per station."""
    names = [c[0] for c in COLUMNS]
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(",".join(f"{n} [{u}]" for n, u, _ in COLUMNS) + "\n")
        for r in rows:
            fh.write(",".join(f"{r[n]:.6g}" for n in names) + "\n")


def write_beamdyn_blade(path, beam: BeamProperties, title: str = "") -> None:
    """A BeamDyn blade file (``station_total`` blocks of eta, 6 x 6 K, 6 x 6 M in the BeamDyn order:
    x flapwise, y chordwise, z along the span), undamped.  BeamDyn needs stations at eta 0 and 1: where
    ``beam`` has none there, its end stations are repeated (constant extrapolation).  Read back by
    :func:`windflutter.model.beamdyn.read_beamdyn_blade`."""
    inv = np.argsort(PERM_BEAMDYN_TO_SECTION)  # section -> BeamDyn order
    K = beam.stiffness[:, inv][:, :, inv]
    M = beam.mass[:, inv][:, :, inv]
    s = np.asarray(beam.s, float)
    if s[0] > 1e-9:
        s, K, M = np.r_[0.0, s], np.concatenate([K[:1], K]), np.concatenate([M[:1], M])
    if s[-1] < 1 - 1e-9:
        s, K, M = np.r_[s, 1.0], np.concatenate([K, K[-1:]]), np.concatenate([M, M[-1:]])
    lines = ["------- BEAMDYN V1.00.* INDIVIDUAL BLADE INPUT FILE --------------------------",
             (title or "beam properties of a shell blade (windflutter beam-properties)")[:200],
             "---------------------- BLADE PARAMETERS --------------------------------------",
             f"{len(s):d}   station_total    - Number of blade input stations (-)",
             " 0   damp_type        - Damping type: 0: no damping; 1: damped",
             "---------------------- DAMPING COEFFICIENT------------------------------------",
             "   mu1        mu2        mu3        mu4        mu5        mu6",
             "   (-)        (-)        (-)        (-)        (-)        (-)",
             " 0.0 0.0 0.0 0.0 0.0 0.0",
             "---------------------- DISTRIBUTED PROPERTIES---------------------------------"]
    for i in range(len(s)):
        lines.append(f"  {s[i]:.6f}")
        lines += ["  " + "  ".join(f"{x: .6E}" for x in r) for r in K[i]]
        lines.append("")
        lines += ["  " + "  ".join(f"{x: .6E}" for x in r) for r in M[i]]
        lines.append("")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(lines) + "\n")


__all__ = ["ASYMMETRY_LIMIT", "COLUMNS", "ShellBeamTable", "shell_beam_table", "shell_blade_properties", "table_rows",
           "usable_stations", "with_shell_blade_properties", "write_beamdyn_blade", "write_csv"]
