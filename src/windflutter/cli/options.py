"""One options vocabulary for every command: flags declared once, checked by the config's specs.

A :class:`Flag` either *sets a config field* (``path="solver.basis_modes"``: its type, bounds and
doc are that field's :class:`~windflutter.schema.Spec`, and its value goes into the analysis
config as an override, validated by :func:`windflutter.config.config_from_dict` like a config
file) or is *command-only* (``spec=Spec(...)``: e.g. ``modes --n``), checked by the same
:class:`~windflutter.schema.Spec` code.  Values arrive as text; numbers are parsed permissively
(``1e6``, ``inf``) and then refused by the spec, so a command line and a config file give the
same message for the same value.

An error names the flag the user typed and, for a config flag, the config field:
``--basis-modes = 0: expected an integer in [1, 500] (config field solver.basis_modes)``.
"""

from __future__ import annotations

import argparse
import re
from dataclasses import dataclass
from typing import Any, Callable

from windflutter.config import PLOT_FORMATS, field_specs, n_points_for_step
from windflutter.errors import InputError, one_line
from windflutter.schema import Spec


#: the config fields' specs by dotted name
SPECS = field_specs()


class OneLineParser(argparse.ArgumentParser):
    """``argparse`` parser whose usage errors are one line (``PROG: error: ...``), exit code 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(2, f"{self.prog}: error: {one_line(message)} (see {self.prog} --help)\n")


def scalar(text: str) -> Any:
    """A command-line value: an int, else a float (``1e6``, ``inf``), else the text itself."""
    t = text.strip()
    if re.fullmatch(r"[-+]?\d+", t) and len(t) < 400:
        return int(t)
    try:
        return float(t)
    except ValueError:
        return text


@dataclass(frozen=True)
class Flag:
    """One command-line option.

    Parameters
    ----------
    name : the flag, e.g. ``"--basis-modes"``.
    path : the config field it sets (``None``: a command-only flag with its own ``spec``).
    spec : a command-only flag's :class:`~windflutter.schema.Spec`.
    nargs : as for ``argparse`` (``"+"``: a list).
    default : the command's default (``None``: the config's, or absent).
    to_config : for flags that set several fields or translate a value (``--rpm``,
        ``--physics``): ``to_config(value) -> nested dict`` of config overrides.
    metavar, help : shown by ``--help`` (default: from the spec's doc).
    """

    name: str
    path: str | None = None
    spec: Spec | None = None
    nargs: Any = None
    default: Any = None
    to_config: Callable[[Any], dict] | None = None
    metavar: Any = None
    help: str | None = None

    @property
    def dest(self) -> str:
        return self.name.lstrip("-").replace("-", "_")

    def the_spec(self) -> Spec:
        if self.spec is not None:
            return self.spec
        assert self.path is not None, self.name
        return SPECS[self.path]

    def add_to(self, parser: argparse.ArgumentParser) -> None:
        spec = self.the_spec() if (self.spec is not None or self.path) else None
        kw: dict[str, Any] = {"dest": self.dest, "default": None}
        if spec is not None and spec.kind == "bool" and self.nargs is None:
            kw["action"] = argparse.BooleanOptionalAction  # --x / --no-x (defaults may be true)
        else:
            kw.update(type=scalar if spec is None or spec.kind in ("float", "int", "custom") else str,
                      nargs=self.nargs)
            if self.metavar is not None:
                kw["metavar"] = self.metavar
            elif spec is not None and spec.choices:
                kw["metavar"] = "{" + ",".join(spec.choices) + "}"
        notes = []
        if spec is not None and spec.kind in ("float", "int") and spec.range_text():
            unit = f" {spec.unit}" if spec.unit and spec.unit != "-" else ""
            notes.append(f"in {spec.range_text()}{unit}")
        if self.default is not None:
            d = self.default
            notes.append(f"default {' '.join(map(str, d)) if isinstance(d, list) else d}")
        if self.path:
            notes.append(f"config {self.path}")
        words = (self.help or (spec.doc if spec is not None else "")) + (f" ({'; '.join(notes)})" if notes else "")
        kw["help"] = words.replace("%", "%%")
        parser.add_argument(self.name, **kw)


def add_flags(parser: argparse.ArgumentParser, flags: tuple[Flag, ...]) -> None:
    for f in flags:
        f.add_to(parser)


def _set(d: dict, dotted: str, value: Any) -> None:
    *head, last = dotted.split(".")
    for k in head:
        d = d.setdefault(k, {})
    d[last] = value


def _merge_into(d: dict, extra: dict) -> None:
    for k, v in extra.items():
        if isinstance(v, dict) and isinstance(d.get(k), dict):
            _merge_into(d[k], v)
        else:
            d[k] = v


def config_overrides(args: argparse.Namespace, flags: tuple[Flag, ...]) -> dict:
    """Nested config overrides from the config flags given on the command line (or with a
    command default)."""
    out: dict = {}
    for f in flags:
        if f.path is None and f.to_config is None:
            continue
        v = getattr(args, f.dest, None)
        v = f.default if v is None else v
        if v is None:
            continue
        if f.to_config is not None:
            _merge_into(out, f.to_config(v if f.spec is None else f.spec.check(v, f.name)))
        else:
            _set(out, f.path, v)
    return out


def command_values(args: argparse.Namespace, flags: tuple[Flag, ...], with_paths: bool = False) -> dict[str, Any]:
    """The command-only flags' values (their default where not given), each checked by its
    spec; ``with_paths``: also the config flags, checked by their config field's spec (for
    commands that take those settings without building an analysis config)."""
    out = {}
    for f in flags:
        if f.to_config is not None or (f.spec is None and not (with_paths and f.path)):
            continue
        v = getattr(args, f.dest, None)
        v = f.default if v is None else v
        out[f.dest] = None if v is None else f.the_spec().check(v, f.name)
    return out


def _field_root(field: str) -> str:
    return re.sub(r"\[\d+\]$", "", field)


def flag_error(exc: InputError, args: argparse.Namespace, flags: tuple[Flag, ...],
               paths: dict[str, str] | None = None) -> InputError:
    """``exc`` renamed to the flag the user typed, when a given flag set that config field.

    ``paths`` adds config fields set by ``to_config`` flags (``{"rotor_speed.max_rpm": "--rpm"}``).
    """
    root = _field_root(exc.field)
    names = {f.path: f for f in flags if f.path}
    flag = names.get(root)
    if flag is None and paths and root in paths:
        flag = next((f for f in flags if f.name == paths[root]), None)
    given = getattr(args, flag.dest, None) if flag is not None else None
    if given is None or given is False:  # (0 is a given value)
        return exc
    return InputError(flag.name, exc.value, f"{exc.expected} (config field {exc.field})")


# --------------------------------------------------------------------------------------------
# the flags shared by `run` and `stability` (each sets a config field)
# --------------------------------------------------------------------------------------------
#: config fields set by ``--rpm MIN MAX STEP`` and ``--max-tip-mach``
RPM_PATHS = {"rotor_speed.min_rpm": "--rpm", "rotor_speed.max_rpm": "--rpm", "rotor_speed.n_points": "--rpm",
             "rotor_speed.max_tip_mach": "--max-tip-mach"}
#: output files of figures: the config's ``output.formats``
PLOT_EXTENSIONS = tuple(f".{x}" for x in PLOT_FORMATS)


def _rpm_grid(v: list) -> dict:
    lo, hi, step = v
    n = n_points_for_step(lo, hi, step, "--rpm STEP")
    return {"rotor_speed": {"min_rpm": lo, "max_rpm": hi, "n_points": n}}


def rpm_flag(default: list | None = None) -> Flag:
    return Flag("--rpm", nargs=3, metavar=("MIN", "MAX", "STEP"), to_config=_rpm_grid, default=default,
                help="rotor-speed grid (RPM): search range and step of the sweep (config rotor_speed.min_rpm, "
                     "max_rpm and n_points)")


def _tip_mach(v: Any) -> dict:
    none = isinstance(v, str) and v.strip().lower() in ("none", "null")
    return {"rotor_speed": {"max_tip_mach": None if none else v}}


#: ``--max-tip-mach M`` (``none``: no bound), beside ``--rpm`` in the commands that search
TIP_MACH_FLAG = Flag("--max-tip-mach", metavar="M", to_config=_tip_mach,
                     help="method p: the search also ends where the blade tip's speed relative to the wind reaches "
                          "this Mach number (default 0.5, where the incompressible strips end; none: --rpm's MAX "
                          "alone; config rotor_speed.max_tip_mach)")

PHYSICS = Flag("--physics", spec=Spec("choice", choices=("full", "thesis"),
                                      doc="full: with the centrifugal stress stiffness K_sigma and the rigid-section "
                                          "rotating-frame terms; thesis: without either, as the seed (config "
                                          "solver.geometric_stiffness and solver.rigid_sections)"),
               to_config=lambda v: {"solver": {"geometric_stiffness": v == "full", "rigid_sections": v == "full"}})

SOLVER_FLAGS = (
    PHYSICS,
    Flag("--air-density", "air_density", metavar="RHO"),
    Flag("--n-span", "model.n_aero_sections", metavar="N", help="blade elements (one aerodynamic strip each) "
         "along the span"),
    Flag("--part", "model.part"),
    Flag("--tip-closure", "model.tip_closure"),
    Flag("--shell-shear", "model.shell_shear"),
    Flag("--reduction", "solver.reduction"),
    Flag("--basis-modes", "solver.basis_modes", metavar="N"),
    Flag("--n-tracked", "solver.n_tracked", metavar="N"),
    Flag("--aero-distribution", "solver.aero_distribution"),
    Flag("--mean-loads", "solver.mean_loads"),
    Flag("--induction", "solver.induction"),
    Flag("--high-thrust", "solver.high_thrust"),
    Flag("--deflection", "solver.deflection"),
    Flag("--corotational", "solver.corotational"),
    Flag("--structure", "solver.structure"),
    Flag("--circulation", "solver.circulation"),
    Flag("--dynamic-stall", "solver.dynamic_stall"),
    Flag("--drivetrain", "model.drivetrain"),
    Flag("--damping", "damping.model"),
)

# --------------------------------------------------------------------------------------------
# every other config field that changes a result: a flag derived from its name
# --------------------------------------------------------------------------------------------
#: sections whose flags are the bare field names (``--basis-modes``); the fields of the other
#: sections carry the section (``--damping-tower-ratio``, ``--operating-rated-rpm``)
BARE_SECTIONS = ("", "solver", "model", "rotor_speed")
#: config fields without a flag: set by a command's own flags (``--wind-speeds``, ``--aero``,
#: ``--method``, ``--model``, ``--rpm``, ``--physics``) or changing no result (text, output files)
NO_FLAG = ("wind_speeds", "aero", "method", "model.type", "title", "output.") + tuple(RPM_PATHS) + (
    "solver.geometric_stiffness", "solver.rigid_sections")


def derived_flag(path: str) -> Flag:
    """The flag of config field ``path``: ``--`` and its name with ``-`` for ``_``, after its
    section's name unless the section is one of :data:`BARE_SECTIONS`."""
    head, _, last = path.rpartition(".")
    name = last if head in BARE_SECTIONS else f"{head}_{last}"
    kind = SPECS[path].kind
    return Flag("--" + name.replace("_", "-"), path, metavar={"float": "X", "int": "N"}.get(kind))


def derived_flags(sections: tuple[str, ...], taken: tuple[Flag, ...]) -> tuple[Flag, ...]:
    """Derived flags of the fields of ``sections`` (``""``: top level) that neither
    :data:`NO_FLAG` nor a flag of ``taken`` covers."""
    from windflutter.config import declared_fields  # noqa: PLC0415

    have = {f.path for f in taken if f.path}
    out = []
    for path, _, _ in declared_fields():
        head = path.rpartition(".")[0]
        if head in sections and path not in have and not any(path == n or (n.endswith(".") and path.startswith(n))
                                                              for n in NO_FLAG):
            out.append(derived_flag(path))
    return tuple(out)


SOLVER_FLAGS = SOLVER_FLAGS + derived_flags(("", "solver", "model", "rotor_speed", "damping"), SOLVER_FLAGS)
#: ``run`` only: the Campbell of the run and the operating margins of its verdict
RUN_FLAGS = derived_flags(("campbell", "operating"), ())
