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

import numpy as np

from windflutter.errors import InputError, InputWarning
from windflutter.model.blade import PERM_BEAMDYN_TO_SECTION
from windflutter.model.section import layup_beam_sections
from windflutter.model.turbine import BeamProperties, IsotropicMaterial, OrthotropicMaterial, Turbine


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
