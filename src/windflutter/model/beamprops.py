"""Beam section properties: source conventions -> the ``BeamSection`` convention.

Conventions
-----------
* **BeamDyn** (``*_BeamDyn_Blade.dat``) and **windIO 6x6** (v2 ``K11..K66`` /
  ``inertia_matrix``, v1 ``six_x_six`` upper triangles): blade section frame with x flapwise
  (towards the suction side), y chordwise (towards the trailing edge), z along the span, rotated
  by the local structural twist.  Generalised forces ordered ``(F_x, F_y, F_z(axial), M_x, M_y,
  M_z(torsion))``; so ``K33 = EA``, ``K44`` = bending about the flapwise axis = *edgewise* EI,
  ``K55`` = *flapwise* EI, ``K66 = GJ``.  Evidence: NREL 5 MW at r/R = 0.5236, BeamDyn
  ``K44 = 2.5549e9`` = ElastoDyn ``EdgStff``, ``K55 = 5.3472e8`` = ``FlpStff``; the WISDEM
  windIO v2 file has the same numbers under ``K44``/``K55`` (the windIO schema text, which calls
  x the trailing-edge direction and K44 flapwise, does not match the data it ships with).
  Mass matrix ``[[m I, m S(c)^T], [m S(c), J]]`` with ``c = (cm_x, cm_y, 0)``, ``J11 = i_edge``
  (about x), ``J22 = i_flap``, ``J12 = -i_cp``, ``J33 = i_plr`` (checked against the IEA 15 MW
  BeamDyn file: ``M16 = -m cm_y``, ``M26 = m cm_x``, ``M45 = -i_cp``).
* **ElastoDyn** blade: only mass per length, flapwise and edgewise EI (plus a mass adjustment
  factor ``AdjBlMs``); the section is uncoupled.
* **BeamSection** (``windflutter.structure.fem``): x along the beam, y and z in the section plane;
  order ``(N, V_y, V_z, T, M_y, M_z)``.  For the blade we take section ``y`` = blade flapwise
  (BeamDyn x) and section ``z`` = chordwise towards the TE (BeamDyn y):
  ``(x, y, z)_section = (z, x, y)_BeamDyn``, a cyclic permutation (a proper rotation, no sign
  changes), so the conversion is ``K_s = K[P][:, P]`` with ``P = [2, 0, 1, 5, 3, 4]``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.model.turbine import BeamProperties, IsotropicMaterial, OrthotropicMaterial, Turbine

PERM_BEAMDYN_TO_SECTION = np.array([2, 0, 1, 5, 3, 4])


def beamdyn_to_section(K: np.ndarray, M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Reorder (n, 6, 6) BeamDyn/windIO stiffness and mass matrices into the BeamSection order."""
    P = PERM_BEAMDYN_TO_SECTION
    return K[:, P][:, :, P], M[:, P][:, :, P]


def beamdyn_mass_matrix(
    mass: np.ndarray,
    cm_x: np.ndarray,
    cm_y: np.ndarray,
    i_edge: np.ndarray,
    i_flap: np.ndarray,
    i_plr: np.ndarray | None = None,
    i_cp: np.ndarray | None = None,
) -> np.ndarray:
    """(n, 6, 6) BeamDyn-order mass matrices from windIO v2 ``inertia_matrix`` columns.

    ``i_plr`` defaults to ``i_edge + i_flap`` where missing/NaN.
    """
    n = mass.size
    i_cp = np.zeros(n) if i_cp is None else i_cp
    ip = i_edge + i_flap if i_plr is None else np.where(np.isfinite(i_plr), i_plr, i_edge + i_flap)
    M = np.zeros((n, 6, 6))
    for a in range(3):
        M[:, a, a] = mass
    myc, mxc = mass * cm_y, mass * cm_x
    M[:, 0, 5] = M[:, 5, 0] = -myc
    M[:, 1, 5] = M[:, 5, 1] = mxc
    M[:, 2, 3] = M[:, 3, 2] = myc
    M[:, 2, 4] = M[:, 4, 2] = -mxc
    M[:, 3, 3] = i_edge
    M[:, 4, 4] = i_flap
    M[:, 3, 4] = M[:, 4, 3] = -i_cp
    M[:, 5, 5] = ip
    return M


def repair_precomp_inertia(M: np.ndarray, field: str, source: str | None = None) -> np.ndarray:
    """Undo a known WISDEM windIO-writer defect in BeamDyn-order (n, 6, 6) section mass matrices.

    WISDEM (PreComp) files written before the fix of WISDEM issue #377 (2022) carry the edgewise
    mass moment of inertia twice, in ``i_edge`` and, negated, in ``i_cp`` (so ``M45 = M44``), and
    ``i_flap = 0`` (``M55 = 0``): a rank-deficient, indefinite 2x2 rotary block
    ``[[i_edge, i_edge], [i_edge, 0]]``.  The IEA 10 MW file shipped with WISDEM has it (windIO
    issue #54: BeamDyn rejects it because ``i_plr != i_edge + i_flap``).  Its ``i_plr`` is right, so
    with the perpendicular-axis theorem (exact for the section's mass moments about the same
    point) ``i_flap = i_plr - i_edge``; PreComp does not compute the product of inertia, so
    ``i_cp = 0`` (as WISDEM writes it since the fix).

    Only this exact signature is changed (every station with ``i_edge > 0`` has ``M55 = 0`` and
    ``M45 = M44``), with an :class:`~windflutter.errors.InputWarning` naming the field; any other
    matrix is returned unchanged.
    """
    import warnings

    from windflutter.errors import InputWarning

    ie, ifl, mcp, ip = M[:, 3, 3], M[:, 4, 4], M[:, 3, 4], M[:, 5, 5]
    on = ie > 0
    if not on.any() or np.any(ifl[on] != 0.0) or not np.allclose(mcp[on], ie[on], rtol=1e-9, atol=0.0):
        return M
    out = M.copy()
    out[:, 4, 4] = np.maximum(ip - ie, 0.0)
    out[:, 3, 4] = out[:, 4, 3] = 0.0
    where = f"{source}: " if source else ""
    warnings.warn(f"{where}{field}: i_flap is 0 and i_cp = -i_edge at all {int(on.sum())} stations (WISDEM "
                  "writer defect, WISDEM issue #377); using i_flap = i_plr - i_edge and i_cp = 0",
                  InputWarning, stacklevel=3)
    return out


def check_section_mass(M: np.ndarray, s: np.ndarray, field: str, source: str | None = None) -> None:
    """Raise :class:`InputError` if any (6, 6) section mass matrix (any order) is not symmetric
    positive semi-definite (tolerance 1e-9 of its largest entry), naming the station."""
    for k in range(M.shape[0]):
        A = M[k]
        scale = max(np.abs(A).max(), 1e-300)
        lam = np.linalg.eigvalsh(0.5 * (A + A.T)).min()
        if np.abs(A - A.T).max() > 1e-9 * scale or lam < -1e-9 * scale:
            raise InputError(f"{field} at span {float(s[k]):.4f}", f"smallest eigenvalue {lam:.4g}",
                             "a positive semi-definite section mass matrix: mass > 0, i_edge, i_flap >= 0, "
                             "i_cp^2 <= i_edge i_flap, i_plr = i_edge + i_flap (fix the file's inertia_matrix)",
                             source)


# ---------------------------------------------------------------------------------- file readers
def _numbers(line: str) -> list[float] | None:
    try:
        return [float(t) for t in line.replace(",", " ").split()]
    except ValueError:
        return None


def read_beamdyn_blade(path: str | Path, twist_deg_by_eta: tuple[np.ndarray, np.ndarray] | None = None,
                       length: float = float("nan")) -> BeamProperties:
    """Read a BeamDyn blade file (``station_total`` blocks of eta + 6x6 K + 6x6 M).

    Parameters
    ----------
    path : BeamDyn blade file.
    twist_deg_by_eta : optional (eta, twist_deg) of the BeamDyn main file key points, stored in the
        result (converted to rad); zeros otherwise.
    length : blade length (m) for :attr:`BeamProperties.length`.
    """
    p = Path(path)
    lines = p.read_text().splitlines()
    n_st = None
    start = None
    for i, ln in enumerate(lines):
        if "station_total" in ln:
            n_st = int(ln.split()[0])
        if "DISTRIBUTED PROPERTIES" in ln.upper():
            start = i + 1
            break
    if n_st is None or start is None:
        raise InputError("BeamDyn blade file", str(p), "a BeamDyn blade input file (station_total, DISTRIBUTED "
                         "PROPERTIES)")
    rows = [r for r in (_numbers(ln) for ln in lines[start:]) if r]
    eta, K, M = [], [], []
    i = 0
    while i < len(rows) and len(eta) < n_st:
        if len(rows[i]) == 1:
            eta.append(rows[i][0])
            K.append(rows[i + 1:i + 7])
            M.append(rows[i + 7:i + 13])
            i += 13
        else:
            i += 1
    if len(eta) != n_st:
        raise InputError("BeamDyn blade file", str(p), f"{n_st} stations, found {len(eta)}")
    eta_a = np.array(eta)
    Ks, Ms = beamdyn_to_section(np.array(K, dtype=float), np.array(M, dtype=float))
    tw = np.zeros_like(eta_a)
    if twist_deg_by_eta is not None:
        tw = np.radians(np.interp(eta_a, *twist_deg_by_eta))
    return BeamProperties(s=eta_a, stiffness=Ks, mass=Ms, twist=tw, length=float(length),
                          source=f"BeamDyn {p.name}")


def read_elastodyn_blade(path: str | Path, length: float, apply_mass_adjustment: bool = True,
                         GJ: np.ndarray | None = None, EA: np.ndarray | None = None) -> BeamProperties:
    """ElastoDyn blade file -> uncoupled sections (EA and GJ are not in ElastoDyn: pass them or
    they default to 1e3 x EI_max-scale placeholders flagged in ``source``).

    Mass per length is multiplied by ``AdjBlMs`` and the EIs by ``AdjFlSt``/``AdjEdSt`` when
    ``apply_mass_adjustment`` (Jonkman 2009's 17,740 kg includes AdjBlMs = 1.04536).
    """
    p = Path(path)
    adj, tab = _elastodyn_table(p, ("AdjBlMs", "AdjFlSt", "AdjEdSt"), "NBlInpSt", "BlFract", 6)
    frac, _, twist, mden, flp, edg = tab.T
    if not apply_mass_adjustment:
        adj = {k: 1.0 for k in adj}
    m = mden * adj["AdjBlMs"]
    EIflap, EIedge = flp * adj["AdjFlSt"], edg * adj["AdjEdSt"]
    big = 1e3 * max(EIflap.max(), EIedge.max())
    EA_ = EA if EA is not None else np.full_like(m, big)
    GJ_ = GJ if GJ is not None else np.full_like(m, big)
    # section y is the flapwise *direction*: bending about y is edgewise, about z flapwise
    Ks = _diagonal_sections([EA_, big, big, GJ_, EIedge, EIflap])
    Ms = _diagonal_sections([m, m, m, 0.0, 0.0, 0.0])
    src = f"ElastoDyn {p.name} (AdjBlMs={adj['AdjBlMs']})" + ("" if EA is not None else "; EA/GJ rigid placeholders")
    return BeamProperties(s=frac, stiffness=Ks, mass=Ms, twist=np.radians(twist), length=float(length), source=src)


def _elastodyn_table(p: Path, adj_keys: tuple[str, ...], count_key: str, header: str,
                     n_col: int) -> tuple[dict[str, float], np.ndarray]:
    """Adjustment factors (``adj_keys``, default 1) and the distributed-property table of an
    ElastoDyn blade/tower file: ``count_key`` rows of ``n_col`` numbers, starting two lines
    below the column-header line containing ``header`` (names line, units line)."""
    lines = p.read_text().splitlines()
    adj = dict.fromkeys(adj_keys, 1.0)
    n_st = None
    for ln in lines:
        tok = ln.split()
        if len(tok) >= 2 and tok[1] in adj:
            adj[tok[1]] = float(tok[0])
        if len(tok) >= 2 and tok[1] == count_key:
            n_st = int(tok[0])
    i0 = next((i for i, ln in enumerate(lines) if header in ln), None)
    if n_st is None or i0 is None:
        raise InputError("ElastoDyn file", str(p), f"an ElastoDyn input file with {count_key} and a {header} table")
    rows = [_numbers(ln) for ln in lines[i0 + 2:i0 + 2 + n_st]]
    if len(rows) != n_st or any(r is None or len(r) < n_col for r in rows):
        raise InputError(f"ElastoDyn file {header} table", str(p), f"{n_st} rows of {n_col} numbers")
    return adj, np.array([r[:n_col] for r in rows])


def _diagonal_sections(diag: list) -> np.ndarray:
    """(n, 6, 6) diagonal matrices from six entries, each a scalar or an (n,) array."""
    d = np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in diag])
    return np.einsum("jn,jk->njk", np.array(d), np.eye(6))


# ------------------------------------------------------------------------------------- functions
def blade_beam_sections(turbine: Turbine, source: str = "auto") -> BeamProperties:
    """Blade 6x6 properties about the reference axis in the BeamSection convention.

    ``source``: ``"file"`` - the properties that came with the turbine (windIO 6x6, or a
    BeamDyn/ElastoDyn/layup source named in its supplement); ``"layup"`` - thin-walled sections of
    the layup (:func:`windflutter.model.section.layup_beam_sections`); ``"auto"`` - file if
    present, else layup.
    """
    if source not in ("auto", "file", "layup"):
        raise InputError("source", source, "'auto', 'file' or 'layup'")
    if source == "layup" or (source == "auto" and turbine.blade.beam is None and turbine.blade.layup is not None):
        from windflutter.model.section import layup_beam_sections

        return layup_beam_sections(turbine)
    if turbine.blade.beam is None:
        raise InputError("components.blade.elastic_properties", None,
                         "blade 6x6 beam properties in the turbine file or its supplement", turbine.source)
    return turbine.blade.beam


def tube_section(D: float, t: float, material: IsotropicMaterial | OrthotropicMaterial,
                 mass_factor: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Exact properties of a circular tube (outer diameter D, wall t) in the BeamSection order.

    EA = E A, EI = E I, GJ = G J with A = pi (Ro^2 - Ri^2), I = pi/4 (Ro^4 - Ri^4), J = 2 I;
    shear areas with the thin-tube shear factor k = 0.5; mass per length rho A (x mass_factor for
    outfitting), mass moments rho I (y, z) and rho J (torsion).
    """
    Ro = 0.5 * D
    Ri = Ro - t
    A = np.pi * (Ro**2 - Ri**2)
    I = 0.25 * np.pi * (Ro**4 - Ri**4)
    J = 2.0 * I
    if isinstance(material, IsotropicMaterial):
        E, G, rho = material.E, material.G, material.rho
    else:
        E, G, rho = material.E1, material.G12, material.rho
    K = np.diag([E * A, 0.5 * G * A, 0.5 * G * A, G * J, E * I, E * I])
    m = rho * A * mass_factor
    Mm = np.diag([m, m, m, rho * J * mass_factor, rho * I * mass_factor, rho * I * mass_factor])
    return K, Mm


def tower_beam_sections(turbine: Turbine) -> BeamProperties:
    """Tower sections from outer diameter, wall layers and materials (circular tubes; layers
    stacked from the outside in).  Section frame: x up the tower axis, y = global x (downwind),
    z = global y; the tube is axisymmetric so the orientation only matters for the labels."""
    tw = turbine.tower
    n = tw.s.size
    K = np.zeros((n, 6, 6))
    M = np.zeros((n, 6, 6))
    # layers are concentric: a layer's outer diameter is D minus twice the walls outside it
    outside = np.zeros(n)
    for lay in tw.layers:
        mat = turbine.materials[lay.material]
        for j in range(n):
            Kj, Mj = tube_section(tw.outer_diameter[j] - 2 * outside[j], lay.thickness[j], mat,
                                  tw.outfitting_factor)
            K[j] += Kj
            M[j] += Mj
        outside = outside + lay.thickness
    return BeamProperties(s=tw.s, stiffness=K, mass=M, twist=np.zeros(n), length=tw.height,
                          source="thin-walled tube from outer_diameter/layers")


def read_elastodyn_tower(path: str | Path, height: float) -> BeamProperties:
    """ElastoDyn tower file -> uncoupled sections (mass per length x AdjTwMa, fore-aft and
    side-to-side EI x AdjFASt/AdjSSSt; EA, GJ and shear rigid placeholders).  Section frame as
    :func:`tower_beam_sections`: y = fore-aft direction (global x), so bending about z is fore-aft.
    """
    p = Path(path)
    adj, tab = _elastodyn_table(p, ("AdjTwMa", "AdjFASt", "AdjSSSt"), "NTwInpSt", "HtFract", 4)
    frac, mden, fa, ss = tab.T
    m = mden * adj["AdjTwMa"]
    EIfa, EIss = fa * adj["AdjFASt"], ss * adj["AdjSSSt"]
    big = 1e3 * EIfa.max()
    n = m.size
    K = _diagonal_sections([big, big, big, big, EIss, EIfa])
    M = _diagonal_sections([m, m, m, 0.0, 0.0, 0.0])
    return BeamProperties(s=frac, stiffness=K, mass=M, twist=np.zeros(n), length=float(height),
                          source=f"ElastoDyn {p.name}; EA/GJ/shear rigid placeholders")
