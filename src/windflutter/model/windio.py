"""windIO turbine reader (ontology v1.x and v2.x) -> :class:`~windflutter.model.turbine.Turbine`.

Steps:

1. YAML parsing with YAML-1.2 numbers (``5e-05`` is a float), duplicate keys refused, nesting
   bounded (:mod:`.yamlio`).
2. Version detection: ``windIO_version: '2.x'`` -> v2; no version key (or '1.x') -> v1
   (``outer_shape_bem``, ``internal_structure_2d_fem``, ``nacelle``); anything else is refused.
3. Validation.  v2: the windIO 2.1.1 JSON schema (``windIO.validate`` machinery, non-restrictive:
   extra keys allowed) - every violation is reported as :class:`InputError` with its path in the
   file.  v1: windIO 2.x ships no v1 schema, so v1 files get the structural checks of our own
   readers (required keys, types, array lengths, ranges) - the same checks also run on v2 files.
4. Physical plausibility at the file's stations (:mod:`.plausibility`), conversion to SI/radians
   (v2 files give angles in degrees and rotor speeds in rpm; v1 files radians and rad/s).
5. Supplementary data (hub/nacelle masses, operating curve, damping ...) from a ``windflutter:``
   block in the file or a sibling ``<stem>.windflutter.yaml`` (:mod:`.supplement`), then the
   whole-turbine consistency checks (:mod:`.consistency`).

The modules ``windio_blade``, ``windio_layup`` and ``windio_parts`` hold the per-component
readers; :func:`windflutter.model.load_turbine` chooses this reader for ``.yaml`` files.
"""

from __future__ import annotations

import dataclasses
import functools
from pathlib import Path

from windflutter.errors import InputError
from windflutter.model import plausibility as pl
from windflutter.model import windio_blade, windio_parts
from windflutter.model.checks import Reader, join
from windflutter.model.consistency import finish_turbine
from windflutter.model.registry import load_turbine as _load
from windflutter.model.supplement import apply_supplement, find_supplement
from windflutter.model.turbine import Turbine
from windflutter.model.windio_common import V1, V2, Keys
from windflutter.model.yamlio import load_yaml_file

SUPPORTED_MAJOR = (1, 2)


# ------------------------------------------------------------------------------------ validation
@functools.lru_cache(maxsize=1)
def _v2_validator():
    """jsonschema validator for the windIO 2.x turbine schema (cached: building it is slow)."""
    import jsonschema
    import windIO
    from windIO.validator import registry  # the $ref registry windIO uses for its own validate()

    # the project's C-accelerated loader: the same dict as windIO.load_yaml's, 0.05 s against 0.34 s
    schema = load_yaml_file(Path(windIO.__file__).parent / "schemas" / "turbine" / "turbine_schema.yaml")
    cls = jsonschema.validators.validator_for(schema)
    return cls(schema, registry=registry)


def validate_windio_v2(data: dict, source: str | None = None) -> None:
    """Validate against the windIO 2.1.1 turbine schema (extra keys allowed).

    Raises
    ------
    InputError
        For the first violation (the one deepest in the file among the best matches), with its
        dotted path, offending value and the schema's message.
    """
    import jsonschema

    validator = _v2_validator()
    # the 'windflutter' supplement block is our extension (the schema forbids unknown top-level keys)
    data = {k: v for k, v in data.items() if k != "windflutter"}
    errors = list(validator.iter_errors(data))
    if not errors:
        return
    err = max(errors, key=jsonschema.exceptions.relevance)
    # descend into oneOf/anyOf contexts: take the alternative (schema branch) with the fewest
    # errors - the one the user most likely meant - and its deepest error
    while err.context:
        branches: dict = {}
        for c in err.context:
            branches.setdefault(c.schema_path[0] if c.schema_path else 0, []).append(c)
        fewest = min(branches.values(), key=len)
        err = max(fewest, key=lambda c: len(c.absolute_path))
    path = ""
    for part in err.absolute_path:
        path = join(path, part)
    raise InputError(path or "<top level>", err.instance, f"windIO schema: {err.message}", source)


def windio_major_version(data: dict, source: str | None = None) -> int:
    """1 for windIO 1.x files (no ``windIO_version`` key, or '1.x'), 2 for 2.x; any other
    version is refused (a '9.9' file is not read as 2.x)."""
    v = data.get("windIO_version")
    if v is None:
        return 1
    try:
        major = int(str(v).strip().split(".")[0])
    except ValueError:
        major = -1
    if major not in SUPPORTED_MAJOR:
        raise InputError("windIO_version", v, "a supported windIO version: 1.x or 2.x (e.g. '2.0')", source)
    return major


# ----------------------------------------------------------------------------------- the reader
def load_windio(path: Path, validate: bool = True) -> Turbine:
    """Read a windIO v1/v2 file (or a windflutter seed file) with its supplement.

    Parameters
    ----------
    path : the YAML file.
    validate : run the windIO schema validation (v2 files; ~0.2-1 s for large files).
    """
    data = load_yaml_file(path)
    source = str(path)
    turbine, raw = read_windio_dict(data, source=source, validate=validate)
    supp, supp_source = find_supplement(data, path)
    turbine = apply_supplement(turbine, raw, supp, base_dir=path.parent, source=supp_source or source)
    files = (source,) + ((supp_source,) if supp_source and supp_source != source else ())
    return finish_turbine(turbine, files)


def read_windio_dict(data: dict, source: str | None = None, validate: bool = True) -> tuple[Turbine, dict]:
    """Convert a parsed windIO dict to a :class:`Turbine` (without supplement); also returns the
    dict (for the supplement step)."""
    major = windio_major_version(data, source)
    if major >= 2:
        if validate:
            validate_windio_v2(data, source)
        return _read(data, V2, Reader(source), f"{data.get('windIO_version')}"), data
    return _read(data, V1, Reader(source), "1.x"), data


def _read(data: dict, k: Keys, r: Reader, version: str) -> Turbine:
    notes = pl.Notes(r.source)
    with pl.collected(notes):
        t = _read_parts(data, k, r, version, notes)
    return dataclasses.replace(t, warnings=tuple(notes.items))


def _read_parts(data: dict, k: Keys, r: Reader, version: str, notes: pl.Notes) -> Turbine:
    asm = r.mapping(data, "", "assembly")
    comps = r.mapping(data, "", "components")
    materials, ply_t = windio_parts.materials(data, r, k, notes)
    foils = windio_blade.airfoils(data, r, k, notes)
    blade = windio_blade.blade(r.mapping(comps, "components", "blade"), r, k, foils, materials, notes)
    tower = windio_parts.tower(r.mapping(comps, "components", "tower"), r, k, materials)
    hub = windio_parts.hub(r.mapping(comps, "components", "hub"), r, k, data)
    nac = windio_parts.nacelle(comps, r, k, tower)
    radius = 0.5 * r.number(asm, "assembly", "rotor_diameter", positive=True)
    control = windio_parts.control(data.get("control"), r, k, radius, notes)
    orient = str(asm.get("rotor_orientation", "upwind")).lower()
    rated_speed = control.max_rotor_speed
    ctrl = data.get("control") or {}
    if "rated_rotor_speed" in ctrl:
        rated_speed = r.number(ctrl, "control", "rated_rotor_speed", positive=True) * k.speed
    return Turbine(
        name=str(data.get("name", Path(r.source or "turbine").stem)),
        n_blades=int(r.number(asm, "assembly", "number_of_blades", positive=True)),
        hub_height=r.number(asm, "assembly", "hub_height", positive=True),
        rotor_diameter=2.0 * radius,
        rated_power=r.number(asm, "assembly", "rated_power", positive=True),
        rated_rotor_speed=float(rated_speed),
        blade=blade, tower=tower, hub=hub, nacelle=nac, airfoils=foils, materials=materials,
        ply_thickness=ply_t, control=control,
        rotor_orientation="downwind" if orient.startswith("down") else "upwind",
        source=r.source or "", windio_version=version, source_format=f"windIO {version}",
    )


def load_turbine(path_or_name: str | Path, validate: bool = True) -> Turbine:
    """Any turbine file or bundled name: :func:`windflutter.model.registry.load_turbine` (kept
    here for existing imports)."""
    return _load(path_or_name, validate=validate)
