"""Fixed-wing mode: a straight uniform cantilever wing (beam elements + strip aero + p-k).

The wing lies along global +y from the clamped root at the origin; the free stream is along +x,
z is up.  The beam reference axis is the elastic axis.  Section frame: x along the span, y
towards the leading edge, z up, so the flap bending stiffness is ``EIy``.
Strips sit at element mid-points with the mean of the two nodes' motion (one strip per element).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
import scipy.sparse as sp

from windflutter.aero.sections import AeroSections, Polar
from windflutter.aero.strip import AeroOptions
from windflutter.errors import InputError
from windflutter.solve.aeroelastic import AeroelasticModel, StructuralMatrices
from windflutter.frozen.search import pk_search, thesis_search
from windflutter.results import Onset
from windflutter.structure.assembly import assemble
from windflutter.structure.fem import BeamSection, FEModel


@dataclass(frozen=True)
class WingConfig:
    """Uniform cantilever wing (SI units).

    span (m), chord (m), elastic_axis and mass_axis (fraction of chord from the leading edge),
    bending_stiffness EI (N m^2), torsion_stiffness GJ (N m^2), mass (kg/m), inertia (kg m^2/m,
    about the elastic axis), air_density (kg/m^3), lift_slope (1/rad, default 2 pi),
    n_elements, chordwise/axial stiffness factor over EI (rigid in-plane by default),
    structural damping ratio (none by default), speed range for the search (m/s).
    """

    span: float
    chord: float
    elastic_axis: float
    mass_axis: float
    bending_stiffness: float
    torsion_stiffness: float
    mass: float
    inertia: float
    air_density: float = 1.225
    lift_slope: float = 2 * np.pi
    n_elements: int = 20
    n_modes: int = 12
    speed_min: float = 1.0
    speed_max: float = 400.0
    speed_step: float = 10.0

    def __post_init__(self):
        for name in ("span", "chord", "bending_stiffness", "torsion_stiffness", "mass", "inertia",
                     "air_density", "lift_slope", "speed_max", "speed_step", "speed_min"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v <= 0:
                raise InputError(name, v, "a positive number")
        for name in ("elastic_axis", "mass_axis"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (0.0 <= v <= 1.0):
                raise InputError(name, v, "a fraction of the chord from the leading edge in [0, 1]")
        if isinstance(self.n_elements, bool) or not isinstance(self.n_elements, int) or self.n_elements < 1:
            raise InputError("n_elements", self.n_elements, "a positive integer")
        if isinstance(self.n_modes, bool) or not isinstance(self.n_modes, int) or self.n_modes < 2:
            raise InputError("n_modes", self.n_modes, "an integer >= 2")
        d = (self.mass_axis - self.elastic_axis) * self.chord
        if self.inertia <= self.mass * d**2 * (1 - 1e-12):
            raise InputError("inertia", self.inertia,
                             f"more than mass * (mass-axis offset)^2 = {self.mass * d**2:.6g} kg m^2/m")
        if self.speed_min >= self.speed_max:
            raise InputError("speed_min", self.speed_min, f"less than speed_max = {self.speed_max}")

    @staticmethod
    def from_dict(d: dict, source: str | None = None) -> "WingConfig":
        """Build from a mapping (YAML); unknown or missing keys raise :class:`InputError`."""
        if not isinstance(d, dict):
            raise InputError("config", type(d).__name__, "a mapping of wing properties", source)
        names = {f.name for f in fields(WingConfig)}
        for k in d:
            if k not in names:
                raise InputError(str(k), d[k], f"one of {sorted(names)}", source)
        required = ("span", "chord", "elastic_axis", "mass_axis", "bending_stiffness", "torsion_stiffness",
                    "mass", "inertia")
        for k in required:
            if k not in d:
                raise InputError(k, None, "a value (required)", source)
        vals = {}
        for k, v in d.items():
            if isinstance(v, str):  # YAML 1.1 reads 9.77e6 as a string
                try:
                    v = float(v)
                except ValueError:
                    raise InputError(k, v, "a number", source) from None
            if k in ("n_elements", "n_modes"):
                if isinstance(v, float) and v.is_integer():
                    v = int(v)
            elif isinstance(v, int) and not isinstance(v, bool):
                v = float(v)
            vals[k] = v
        try:
            return WingConfig(**vals)
        except InputError as e:
            raise InputError(e.field, e.value, e.expected, source) from None


def build_wing(cfg: WingConfig) -> tuple[FEModel, AeroSections]:
    """Beam FE model and strips of the wing (root clamped at node 0)."""
    n = cfg.n_elements
    y = np.linspace(0.0, cfg.span, n + 1)
    nodes = np.column_stack([np.zeros(n + 1), y, np.zeros(n + 1)])
    EI, GJ = cfg.bending_stiffness, cfg.torsion_stiffness
    d = (cfg.mass_axis - cfg.elastic_axis) * cfg.chord  # mass axis aft of EA (m)
    # section y points to the leading edge: the mass centre is at y = -d
    sec = BeamSection.from_properties(EA=1e4 * EI, EIy=EI, EIz=1e4 * EI, GJ=GJ, mass_per_length=cfg.mass,
                                      Ixx_mass=cfg.inertia, Iyy_mass=1e-9 * cfg.inertia,
                                      Izz_mass=cfg.mass * d**2 + 1e-9 * cfg.inertia, cg=(-d, 0.0))
    conn = np.column_stack([np.arange(n), np.arange(1, n + 1)])
    fe = FEModel(nodes=nodes, beam_conn=conn, beam_section=np.zeros(n, dtype=np.int64),
                 beam_orient=np.tile([-1.0, 0.0, 0.0], (n, 1)), beam_sections=[sec],
                 spc={0: (0, 1, 2, 3, 4, 5)}, node_groups={"wing": np.arange(n + 1)})
    # strips at element mid-points
    rows, cols, vals = [], [], []
    for c in range(6):
        for end in (0, 1):
            rows.append(6 * np.arange(n) + c)
            cols.append(6 * conn[:, end] + c)
            vals.append(np.full(n, 0.5))
    mm = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                       shape=(6 * n, fe.n_dof))
    ym = 0.5 * (y[:-1] + y[1:])
    a = 2.0 * cfg.elastic_axis - 1.0
    polar = Polar(alpha=np.radians([-5.0, 0.0, 5.0]), cl=cfg.lift_slope * np.radians([-5.0, 0.0, 5.0]),
                  cd=np.zeros(3), cm=np.zeros(3), name="wing")
    sections = AeroSections(
        blade=np.zeros(n, dtype=np.int64), radius=ym, width=np.diff(y), chord=np.full(n, cfg.chord),
        elastic_axis=np.full(n, a), origin=np.column_stack([np.zeros(n), ym, np.zeros(n)]),
        e_chord=np.tile([1.0, 0.0, 0.0], (n, 1)), e_span=np.tile([0.0, 1.0, 0.0], (n, 1)),
        airfoil=np.zeros(n, dtype=np.int64), polars=[polar], twist=np.zeros(n), motion_map=mm)
    return fe, sections


def wing_model(cfg: WingConfig, n_modes: int | None = None) -> AeroelasticModel:
    """The aeroelastic model of the wing (modal basis of ``cfg.n_modes`` modes unless given)."""
    fe, sections = build_wing(cfg)
    st = assemble(fe)
    aero = AeroOptions(model="potential", lift_slope=cfg.lift_slope)
    nm = cfg.n_modes if n_modes is None else n_modes
    return AeroelasticModel(structure=StructuralMatrices.from_structural(st), sections=sections, aero=aero,
                            air_density=cfg.air_density, n_modes=nm if nm and nm < 6 * cfg.n_elements else None)


@dataclass
class WingResult:
    """Flutter speed (m/s), frequency (rad/s), divergence speed (m/s) or None."""

    flutter_speed: float | None
    flutter_frequency: float | None
    divergence_speed: float | None
    onset: Onset

    def as_dict(self) -> dict:
        return {"flutter_speed": self.flutter_speed, "flutter_frequency": self.flutter_frequency,
                "divergence_speed": self.divergence_speed}


def analyse_wing(cfg: WingConfig, method: str = "pk", n_modes: int | None = None, xtol: float = 1e-3) -> WingResult:
    """Flutter and divergence of the wing over ``speed_min..speed_max`` (m/s)."""
    model = wing_model(cfg, n_modes)
    grid = np.arange(cfg.speed_min, cfg.speed_max + 0.5 * cfg.speed_step, cfg.speed_step)
    if method == "pk":
        on = pk_search(lambda V: model.at(V, 0.0), grid, n_track=min(6, model.size), xtol=xtol)
    elif method == "thesis":
        on = thesis_search(lambda V: model.at(V, 0.0), grid)
    else:
        raise InputError("method", method, "'pk' or 'thesis'")
    return WingResult(on.flutter, on.flutter_frequency, on.divergence, on)
