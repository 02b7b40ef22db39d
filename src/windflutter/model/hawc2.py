"""HAWC2 model reader: ``.htc`` (+ st, ae, pc files, HAWCStab2 operational data) -> :class:`Turbine`.

The bodies are found by the model's topology, not by their names: the blade is the body the
``aero`` block links (``link 1 mbdy_c2_def NAME``), its hub is the blade's parent in the
``orientation`` block, the shaft the hub's parent, the tower the ``base`` body, and the bodies
between tower and shaft (towertop, connector) carry the nacelle.  What each part gives:

* blade: c2_def (reference axis = the half-chord line, so ``pitch_axis = 0.5``; twist = -c2
  twist), the st set as full 6x6 about the c2 line (:mod:`.hawc2_beam`: elastic/shear-centre and
  CG offsets, structural pitch), ae chord and thickness, pc profiles interpolated in thickness
  at every ae station (HAWC2's rule);
* tower: st set (m, E, G, I, A) -> an equivalent tube (:mod:`.tower_tube`);
* nacelle: concentrated masses (and the distributed mass) of the bodies between tower and shaft,
  combined about their CG; hub: those of the shaft (except its first node) and hub bodies;
  generator: the shaft's first-node rotational inertia (as a low-speed-shaft inertia, gear ratio
  1); drivetrain stiffness: the shaft's torsional flexibility ``1 / integral(dl / G I_p)``;
* geometry: tilt, precone, overhang, ``Twr2Shft``, hub radius and heights from the placed bodies;
* operating curve: the ``hawcstab2`` block's ``operational_data_filename`` when present.
* blade damping: the blade body's ``damping_aniso`` (stiffness-proportional per bending direction:
  ``kx`` flapwise, ``ky`` edgewise, ``kz`` torsion) as the BeamSection-order ``mu``
  ``[kz, kx, ky, kz, ky, kx]`` (axial with torsion, each shear with its bending, BeamDyn's own
  pattern).  A blade ``damping_posdef`` (HAWC2 applies it per DOF direction, not per bending
  direction) and mass-proportional terms are not converted: the turbine then has no blade
  damping, and its notes say so.
Not read: constraints (a standard turbine topology is assumed), controllers.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.integrate import trapezoid

from windflutter.errors import InputError
from windflutter.model import plausibility as pl
from windflutter.model.beamprops import beamdyn_to_section
from windflutter.model.blade import BladeDamping
from windflutter.model.consistency import finish_turbine
from windflutter.model.hawc2_beam import hawc2_mass, hawc2_stiffness
from windflutter.model.hawc2_bodies import H2_TO_WF, Body, place_bodies, read_bodies, to_wf
from windflutter.model.hawc2_files import interpolate_profiles, read_ae, read_pc, read_st
from windflutter.model.hawc2_htc import Block, model_folder, parse_htc
from windflutter.model.operating import read_hawc2_opt
from windflutter.model.supplement import apply_supplement, find_supplement
from windflutter.model.tower_tube import equivalent_tube
from windflutter.model.turbine import Airfoil, BeamProperties, Blade, Hub, Nacelle, Polar, Turbine


def load_hawc2(path: Path, validate: bool = True) -> Turbine:
    """Read a HAWC2 model (``.htc``) and its sibling supplement, if any.

    File names in the htc are relative to the model folder: the htc's folder, or its parent when
    the htc lives in a folder named ``htc`` (HAWC2's usual layout).
    """
    src = str(path)
    base = model_folder(path)
    root = parse_htc(path)
    notes = pl.Notes(src)
    struct = root.child("new_htc_structure", "htc", src)
    bodies = read_bodies(struct, base, src)
    place_bodies(bodies, struct.child("orientation", "new_htc_structure", src), src)
    aero = root.child("aero", "htc", src)
    parts = _topology(struct, aero, bodies, src)
    files = [src]
    geo = _geometry(parts, src)
    blade, foils, b_files = _blade(parts["blade"], aero, base, src, notes)
    blade, damping_note = _blade_damping(blade, parts["blade"])
    tower, mat = _tower(parts["tower"], geo, src)
    hub, nac = _rotor_parts(parts, geo, src, notes)
    files += b_files + [str(parts["tower"].st_file)]
    curve = _operating_curve(root, base, files, src)
    nb = int(aero.numbers("nblades", 1, "aero", src, default=[sum(b.startswith("blade") for b in bodies) or 3])[0])
    span = float(blade.ref_axis[-1, 2])
    t = Turbine(
        name=path.stem, n_blades=nb, hub_height=float(geo["apex"][2]),
        rotor_diameter=2 * (hub.radius + span * np.cos(hub.precone)), rated_power=float("nan"),
        rated_rotor_speed=curve.rated_rotor_speed if curve is not None else float("nan"),
        blade=blade, tower=tower, hub=hub, nacelle=nac, airfoils=foils, materials={mat.name: mat},
        operating_curve=curve, source=src, source_format="HAWC2", warnings=tuple(notes.items),
        notes=("hub_height, rotor_diameter: from the placed bodies", damping_note,
               "not read from the htc: constraints (standard topology assumed), controller"),
    )
    supp, supp_source = find_supplement(None, path)
    t = apply_supplement(t, None, supp, base_dir=path.parent, source=supp_source or src)
    return finish_turbine(t, tuple(files) + ((supp_source,) if supp_source else ()))


def _topology(struct: Block, aero: Block, bodies: dict[str, Body], src: str) -> dict:
    """blade, hub, shaft, tower and the nacelle bodies, from the aero link and the orientation."""
    link = aero.values("link", "aero", src)
    if len(link) < 3 or link[2] not in bodies:
        raise InputError("aero.link", " ".join(link), "'link 1 mbdy_c2_def BLADE_BODY' naming a main_body", src)
    parent = {}
    orient = struct.child("orientation", "new_htc_structure", src)
    for rel in orient.children("relative"):
        parent[rel.values("mbdy2", "orientation.relative", src)[0]] = rel.values("mbdy1", "orientation.relative", src)[0]
    tower = orient.child("base", "orientation", src).values("body", "orientation.base", src)[0]
    chain, b = [], link[2]
    while b in parent:
        b = parent[b]
        chain.append(b)
    if len(chain) < 3 or chain[-1] != tower:
        raise InputError("orientation", " <- ".join([link[2]] + chain), "a chain blade <- hub <- shaft <- ... <- tower",
                         src)
    hub, shaft = chain[0], chain[1]
    hubs = [n for n, p in parent.items() if p == shaft]
    return {"blade": bodies[link[2]], "hub": bodies[hub], "hubs": [bodies[h] for h in hubs], "shaft": bodies[shaft],
            "nacelle": [bodies[n] for n in chain[2:-1]], "tower": bodies[tower]}


def _geometry(parts: dict, src: str) -> dict:
    """Tower base/top, apex, upwind shaft direction, tilt, overhang, Twr2Shft (windflutter frame)."""
    tw, sh = parts["tower"], parts["shaft"]
    base, top = to_wf(tw.to_global(tw.node(1, "tower", src))), to_wf(tw.to_global(tw.node("last", "tower", src)))
    if np.hypot(*(top - base)[:2]) > 1e-6 * abs(top[2] - base[2]) or top[2] <= base[2]:
        raise InputError("tower c2_def / orientation", (top - base).round(4).tolist(), "a vertical tower, base below top",
                         src)
    start, apex = to_wf(sh.to_global(sh.node(1, "shaft", src))), to_wf(sh.to_global(sh.node("last", "shaft", src)))
    up = (apex - start) / np.linalg.norm(apex - start)
    if up[0] >= 0 or abs(up[1]) > 1e-6:
        raise InputError("shaft orientation", up.round(4).tolist(), "an upwind rotor shaft in the vertical plane "
                         "(downwind rotors and yawed nacelles are not supported)", src)
    tilt = float(np.arctan2(up[2], -up[0]))
    overhang = float(apex[0] / np.cos(tilt))
    return {"base": base, "top": top, "apex": apex, "up": up, "tilt": tilt, "overhang": overhang,
            "twr2shft": float(apex[2] - top[2] + overhang * np.sin(tilt))}


# ----------------------------------------------------------------------------------------- blade
def _blade(body: Body, aero: Block, base: Path, src: str, notes: pl.Notes):
    """Blade reference axis (c2 line, windflutter blade frame), 6x6, ae layout, pc airfoils."""
    if body.st_file is None:
        raise InputError(f"main_body {body.name}.timoschenko_input", None, "an st file for the blade", src)
    st = read_st(body.st_file, *body.st_set)
    _check_st(st, body, notes)
    c2 = body.c2
    xyz = np.column_stack([c2[:, 1], -c2[:, 0], c2[:, 2]]) - np.array([c2[0, 1], -c2[0, 0], c2[0, 2]])
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xyz, axis=0), axis=1))])
    pl.span_axis(arc / arc[-1], xyz[:, 2], f"main_body {body.name}.c2_def z", notes)
    twist_c2 = -np.radians(c2[:, 3])
    s_st = st["r"] / st["r"][-1]
    K, M = hawc2_stiffness(st), hawc2_mass(st)
    field = f"{Path(body.st_file).name} set {body.st_set[0]} {body.st_set[1]}"
    pl.section_matrices(K, M, s_st, field, notes, source=str(body.st_file))
    Ks, Ms = beamdyn_to_section(K, M)
    beam = BeamProperties(s=s_st, stiffness=Ks, mass=Ms, twist=np.interp(s_st, arc / arc[-1], twist_c2),
                          length=float(arc[-1]), source=f"HAWC2 {field} (about the c2 line)")
    ae_f = _file(aero, "ae_filename", base, src)
    pc_f = _file(aero, "pc_filename", base, src)
    ae_set = int(aero.numbers("ae_sets", 1, "aero", src, default=[1])[0])
    ae = read_ae(ae_f, ae_set)
    s_ae = (ae["r"] - ae["r"][0]) / (ae["r"][-1] - ae["r"][0])
    pl.chord_twist(s_ae, ae["chord"], arc / arc[-1], twist_c2, float(arc[-1]), f"{ae_f.name} chord",
                   f"main_body {body.name}.c2_def twist", notes)
    foils, names = _airfoils(pc_f, ae, notes)
    s = np.unique(np.concatenate([arc / arc[-1], s_ae]))
    chord = np.interp(s, s_ae, ae["chord"])
    blade = Blade(s=s, ref_axis=np.stack([np.interp(s, arc / arc[-1], xyz[:, j]) for j in range(3)], axis=1),
                  arc_length=np.interp(s, arc / arc[-1], arc), chord=chord, twist=np.interp(s, arc / arc[-1], twist_c2),
                  pitch_axis=np.full(s.size, 0.5), section_offset_y=0.5 * chord,
                  relative_thickness=np.interp(s, s_ae, ae["tc"]), airfoil_positions=s_ae, airfoil_names=names,
                  beam=beam)
    return blade, foils, [str(body.st_file), str(ae_f), str(pc_f)]


def _blade_damping(blade: Blade, body: Body) -> tuple[Blade, str]:
    """The blade with the damping of its body's ``damping_aniso`` (module docstring), and a note."""
    from dataclasses import replace

    if body.damping is None:
        return blade, f"blade damping: none in main_body {body.name} (no damping_aniso)"
    key, (mx, my, mz, kx, ky, kz) = body.damping
    line = f"main_body {body.name}.{key} {mx:g} {my:g} {mz:g} {kx:g} {ky:g} {kz:g}"
    if key != "damping_aniso" or max(mx, my, mz) > 0:
        return blade, f"blade damping: not applied ({line}: only damping_aniso without mass terms is converted)"
    mu = np.array([kz, kx, ky, kz, ky, kx])
    return replace(blade, damping=BladeDamping(mu=mu, source=line)), f"blade damping: {line} as mu {mu.tolist()}"


def _check_st(st: dict, body: Body, notes: pl.Notes) -> None:
    s = st["r"] / max(st["r"][-1], 1e-300)
    where = f"{Path(body.st_file).name} set {body.st_set[0]} {body.st_set[1]}"
    sub = notes.for_file(str(body.st_file))
    pl.span_axis(s, st["r"], f"{where} r", sub)
    for key in ("m", "E", "G", "A", "I_x", "I_y", "I_p"):
        bad = ~(st[key] > 0)
        if bad.any():
            i = int(np.argmax(bad))
            sub.error(f"{where} column {key} at {pl.station(s, i)}", float(st[key][i]), "a positive value")


def _airfoils(pc_f: Path, ae: dict, notes: pl.Notes) -> tuple[dict[str, Airfoil], tuple[str, ...]]:
    """One airfoil per distinct (pc set, thickness) of the ae stations, blended in thickness."""
    foils: dict[str, Airfoil] = {}
    names = []
    sets: dict[int, list] = {}
    sub = notes.for_file(str(pc_f))
    for pc_set, tc in zip(ae["pc_set"], ae["tc"]):
        if pc_set not in sets:
            sets[pc_set] = read_pc(pc_f, int(pc_set))
            for q in sets[pc_set]:
                pl.polar(q.alpha, q.cl, q.cd, q.tc, f"pc set {pc_set} profile {q.name}", "deg", sub)
        name = f"pc{pc_set}_tc{100 * tc:.2f}"
        if name not in foils:
            al, cl, cd, cm = interpolate_profiles(sets[pc_set], float(tc))
            foils[name] = Airfoil(name=name, x=np.zeros(0), y=np.zeros(0), relative_thickness=float(tc),
                                  polars=(Polar(alpha=al, cl=cl, cd=cd, cm=cm, name=name, relative_thickness=float(tc)),))
        names.append(name)
    return foils, tuple(names)


def _file(block: Block, key: str, base: Path, src: str) -> Path:
    name = block.values(key, block.name, src)[0]
    f = Path(name) if Path(name).is_absolute() else base / name
    if not f.is_file():
        raise InputError(f"{block.name}.{key}", str(f), "an existing file", src)
    return f


# ------------------------------------------------------------------------------ tower and masses
def _tower(body: Body, geo: dict, src: str):
    """The tower body's st set -> equivalent tube (E, G and density from the file)."""
    if body.st_file is None:
        raise InputError(f"main_body {body.name}.timoschenko_input", None, "an st file for the tower", src)
    st = read_st(body.st_file, *body.st_set)
    where = f"{Path(body.st_file).name} set {body.st_set[0]} {body.st_set[1]}"
    for key in ("m", "E", "G", "A", "I_x", "I_y"):
        if np.any(~(st[key] > 0)):
            i = int(np.argmax(~(st[key] > 0)))
            raise InputError(f"{where} column {key} row {i + 1}", float(st[key][i]), "a positive value", str(body.st_file))
    rho = float(np.median(st["m"] / st["A"]))
    E, G = float(np.median(st["E"])), float(np.median(st["G"]))
    z = geo["base"][2] + st["r"] - st["r"][0]
    return equivalent_tube(z, st["m"], E * 0.5 * (st["I_x"] + st["I_y"]), E, G, rho, f"{where} m/I_x",
                           str(body.st_file), material_name="tower_steel_hawc2")


def _lumped(bodies: list[Body], src: str, skip_first_node: bool = False) -> tuple[float, np.ndarray, np.ndarray]:
    """Total mass (kg), CG (windflutter global, m) and inertia about the CG (global axes) of the
    bodies' concentrated masses (and their distributed mass, lumped at each segment's middle)."""
    ms, xs, Is = [], [], []
    for b in bodies:
        R = H2_TO_WF @ b.frame
        for node, x, y, z, m, ixx, iyy, izz in b.masses:
            if skip_first_node and int(node) == 1:
                continue
            p = b.node(int(node), f"main_body {b.name} concentrated_mass", src) + np.array([x, y, z])
            ms.append(m)
            xs.append(to_wf(b.to_global(p)))
            Is.append(R @ np.diag([ixx, iyy, izz]) @ R.T)
        if b.st_file is not None:
            st = read_st(b.st_file, *b.st_set)
            seg = np.interp(0.5 * (st["r"][1:] + st["r"][:-1]), st["r"], st["m"]) * np.diff(st["r"])
            arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(b.c2[:, :3], axis=0), axis=1))])
            for rm, dm in zip(0.5 * (st["r"][1:] + st["r"][:-1]), seg):
                ms.append(dm)
                xs.append(to_wf(b.to_global([np.interp(rm, arc, b.c2[:, j]) for j in range(3)])))
                Is.append(np.zeros((3, 3)))
    m = float(np.sum(ms))
    if m <= 0:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    X = np.array(xs)
    cg = (np.array(ms)[:, None] * X).sum(axis=0) / m
    d = X - cg
    I = np.sum(Is, axis=0) + np.einsum("k,kij->ij", np.array(ms), np.einsum("ki,ki->k", d, d)[:, None, None] * np.eye(3)
                                       - np.einsum("ki,kj->kij", d, d))
    return m, cg, 0.5 * (I + I.T)


def _rotor_parts(parts: dict, geo: dict, src: str, notes: pl.Notes) -> tuple[Hub, Nacelle]:
    """Hub (shaft except its first node, and the hub bodies), nacelle, generator, drivetrain."""
    up, apex = geo["up"], geo["apex"]
    shaft = parts["shaft"]
    m_hub, cg_hub, I_hub = _lumped([shaft] + parts["hubs"], src, skip_first_node=True)
    gen = sum(izz for node, *_, izz in shaft.masses if int(node) == 1)
    root = to_wf(parts["hub"].to_global(parts["hub"].node("last", "hub", src)))
    zb = H2_TO_WF @ parts["blade"].frame[:, 2]
    precone = float(np.arcsin(np.clip(zb @ up, -1.0, 1.0)))
    hub = Hub(mass=m_hub, inertia=np.diag([float(up @ I_hub @ up), 0.0, 0.0]),
              diameter=2 * float(np.linalg.norm(root - apex)), precone=precone,
              cg_offset=float((cg_hub - apex) @ -up) if m_hub > 0 else 0.0)
    m_nac, cg_nac, I_nac = _lumped(parts["nacelle"], src)
    st = read_st(shaft.st_file, *shaft.st_set) if shaft.st_file is not None else None
    k_dt = float("inf")
    if st is not None:
        k_dt = 1.0 / trapezoid(1.0 / (st["G"] * st["I_p"]), st["r"])
    if m_nac <= 0:
        notes.warn("nacelle", "no concentrated mass on the bodies between tower and shaft: nacelle mass 0")
    nac = Nacelle(mass=m_nac, inertia=I_nac, cg=cg_nac - geo["top"], overhang=geo["overhang"], shaft_tilt=geo["tilt"],
                  tower_to_shaft=geo["twr2shft"], generator_inertia=float(gen), gear_ratio=1.0,
                  drivetrain_torsional_stiffness=k_dt)
    return hub, nac


def _operating_curve(root: Block, base: Path, files: list, src: str):
    """HAWCStab2 ``operational_data_filename`` (wind, pitch deg, rpm ...), if the htc names one."""
    for hs2 in root.children("hawcstab2"):
        vals = hs2.values("operational_data_filename", "hawcstab2", src, default=[""])
        if vals and vals[0]:
            f = Path(vals[0]) if Path(vals[0]).is_absolute() else base / vals[0]
            if not f.is_file():
                raise InputError("hawcstab2.operational_data_filename", str(f), "an existing .opt file", src)
            files.append(str(f))
            return read_hawc2_opt(f)
    return None
