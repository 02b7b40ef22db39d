"""The output folder of a run: checks before the run, its record (``analysis.yaml``), resume.

* :func:`check_run_folder` -- before anything is computed: ``OUTDIR`` can be written, is not a
  file, and the names the run writes (``results.nc``, ``points/``, ``analysis.yaml``,
  ``report.html``, ``figures/``, ``animations/``) are not of the wrong kind.
* :func:`run_fingerprint` -- what a resumed run must share with the interrupted one: the
  analysis config's fingerprint (settings that change results), the turbine's *content*
  (:func:`turbine_digest`: every number and string the reader produced from the turbine file,
  the files it references and its supplement; or the bytes of the file given to a plug-in
  analyser) and the package version.
* :func:`write_run_record` / :func:`check_resume` -- ``OUTDIR/analysis.yaml`` holds the three
  parts and the resolved config; ``--resume`` refuses, in one line, a folder without it (or with
  an unreadable one) and any part that differs.
"""

from __future__ import annotations

import dataclasses
import hashlib
import re
from pathlib import Path
from typing import Any

import numpy as np

from windflutter.version import __version__
from windflutter.errors import InputError
from windflutter.files import check_output_folder, dump_yaml, load_yaml
from windflutter.model.bundled import bundled_turbines, resolve_turbine_path
from windflutter.post import store

RUN_FILE = "analysis.yaml"
#: names a run writes into OUTDIR, and whether each is a folder
RUN_ENTRIES = {store.RESULTS_FILE: False, store.POINTS_DIR: True, RUN_FILE: False, "report.html": False,
               "figures": True, "animations": True}
#: metadata fields of the turbine left out of its digest (where the numbers came from, not what they are)
_DIGEST_SKIP = frozenset({"source", "notes"})


def check_run_folder(outdir: str | Path, field: str = "-o") -> Path:
    """``outdir`` as a :class:`~pathlib.Path` once it is a folder the run can use (nothing is
    created); :class:`InputError` naming ``field`` otherwise."""
    p = check_output_folder(outdir, field)
    for name, is_dir in RUN_ENTRIES.items():
        q = p / name
        if q.exists() and q.is_dir() != is_dir:
            kind = "a folder" if is_dir else "a file"
            raise InputError(field, str(outdir), f"an output folder whose {name} is {kind} (it is not; "
                             "remove it or choose another folder)")
    points = p / store.POINTS_DIR
    for q in sorted(points.glob("p[0-9]*.nc")) if points.is_dir() else ():
        if q.is_dir():
            raise InputError(field, str(outdir), f"an output folder whose {store.POINTS_DIR}/{q.name} is a "
                             "file (it is a folder; remove it)")
    return p


# --------------------------------------------------------------------------------------------
# fingerprints
# --------------------------------------------------------------------------------------------
def _feed(h: Any, obj: Any, depth: int = 0) -> None:
    """Feed a canonical serialisation of ``obj`` into the hash ``h``."""
    if depth > 50:
        raise InputError("turbine", type(obj).__name__, "a turbine description nested less than 50 levels")
    put = h.update
    if obj is None or isinstance(obj, (bool, int, str, np.bool_, np.integer)):
        put(f"{type(obj).__name__}:{obj!r};".encode())
    elif isinstance(obj, (float, np.floating)):
        put(f"f:{float(obj).hex()};".encode())
    elif isinstance(obj, complex):
        put(f"c:{obj.real.hex()},{obj.imag.hex()};".encode())
    elif isinstance(obj, np.ndarray):
        a = np.ascontiguousarray(obj)
        put(f"a:{a.dtype.str}:{a.shape};".encode())
        put(a.tobytes() if a.dtype != object else repr(a.tolist()).encode())
    elif isinstance(obj, dict):
        put(b"{")
        for k in sorted(obj, key=str):
            put(f"{k!s}=".encode())
            _feed(h, obj[k], depth + 1)
        put(b"}")
    elif isinstance(obj, (list, tuple)):
        put(f"[{len(obj)}:".encode())
        for x in obj:
            _feed(h, x, depth + 1)
        put(b"]")
    elif dataclasses.is_dataclass(obj):
        put(f"<{type(obj).__qualname__}".encode())
        for f in dataclasses.fields(obj):
            if f.name not in _DIGEST_SKIP:
                put(f" {f.name}=".encode())
                _feed(h, getattr(obj, f.name), depth + 1)
        put(b">")
    elif hasattr(obj, "__dict__"):
        put(f"<{type(obj).__qualname__}".encode())
        _feed(h, {k: v for k, v in vars(obj).items() if k not in _DIGEST_SKIP and not k.startswith("_")},
              depth + 1)
        put(b">")
    else:
        put(f"{type(obj).__qualname__}:{obj!r};".encode())


def turbine_digest(turbine: Any) -> str:
    """Hash of what a turbine *is*.

    A loaded turbine (the built-in solver's) is hashed by content: every array, number and
    string of the object, so any change of the turbine file, of a file it references or of its
    supplement that reaches the model changes the digest, while moving the files does not
    (``source`` and ``notes``, which hold paths, are left out).  Files listed in an optional
    ``source_files`` attribute are hashed byte for byte as well.  A plug-in analyser receives the
    ``TURBINE`` argument as given: an existing file is hashed by its bytes, anything else as text.
    """
    h = hashlib.sha256()
    if isinstance(turbine, (str, Path)):
        p = Path(turbine)
        if p.is_file():
            h.update(b"file:")
            h.update(p.read_bytes())
        else:
            h.update(f"name:{turbine}".encode())
        return h.hexdigest()[:16]
    _feed(h, turbine)
    for f in getattr(turbine, "source_files", None) or ():
        fp = Path(f)
        h.update(f"file:{fp.name}:".encode())
        h.update(fp.read_bytes() if fp.is_file() else b"<missing>")
    return h.hexdigest()[:16]


def run_fingerprint(config_fp: str, turbine_fp: str, version: str = __version__) -> str:
    """The run's fingerprint: config, turbine content and package version together."""
    return hashlib.sha256(f"{config_fp}|{turbine_fp}|{version}".encode()).hexdigest()[:16]


# --------------------------------------------------------------------------------------------
# the run record and resume
# --------------------------------------------------------------------------------------------
def run_record(config: Any, turbine: Any, turbine_name: str | None) -> dict[str, Any]:
    """The content of ``OUTDIR/analysis.yaml`` for a run of ``config`` on ``turbine``."""
    cfp, tfp = config.fingerprint(), turbine_digest(turbine)
    return {"fingerprint": run_fingerprint(cfp, tfp), "config_fingerprint": cfp, "turbine_fingerprint": tfp,
            "windflutter_version": __version__, "turbine": turbine_name, "config": config.to_dict()}


def write_run_record(outdir: Path, record: dict[str, Any]) -> Path:
    return store.atomic_write_text(dump_yaml(record), Path(outdir) / RUN_FILE)


_HINT = "; run without --resume to start afresh, or choose another -o folder"


def read_run_record(outdir: str | Path) -> dict[str, Any]:
    """The stored record of the run in ``outdir``, for ``--resume``.

    Raises
    ------
    InputError
        (field ``--resume``) no ``analysis.yaml`` (not the folder of an earlier run), or one that
        cannot be used: a folder, unreadable, not UTF-8, not YAML, not a mapping, no fingerprint.
    """
    path = Path(outdir) / RUN_FILE
    if not path.exists():
        raise InputError("--resume", str(outdir), f"the folder of an earlier run (it has no {RUN_FILE}{_HINT})")
    try:
        stored = load_yaml(path, RUN_FILE)
    except InputError as exc:
        raise InputError("--resume", str(outdir), f"a readable {RUN_FILE} ({exc.expected}{_HINT})") from None
    if not isinstance(stored, dict) or not isinstance(stored.get("fingerprint"), str):
        raise InputError("--resume", str(outdir), f"a {RUN_FILE} written by windflutter run (it has no "
                         f"fingerprint{_HINT})")
    return stored


def check_resume(outdir: str | Path, record: dict[str, Any]) -> None:
    """Refuse (one line, field ``--resume``) to resume ``outdir`` with another run ``record``:
    any problem of :func:`read_run_record`, another windflutter version, another turbine or
    another analysis config."""
    stored = read_run_record(outdir)
    checks = (("windflutter_version", "windflutter version"), ("turbine_fingerprint", "turbine (its content)"),
              ("config_fingerprint", "analysis config"), ("fingerprint", "run fingerprint"))
    for key, what in checks:
        old, new = stored.get(key), record[key]
        if old != new:
            raise InputError("--resume", str(outdir), f"the same {what} as the interrupted run (stored "
                             f"{old}, now {new}){_HINT}")


def run_folder_name(turbine: Any) -> str:
    """The default output folder name of a run (``out/<this>``): a bundled name as given in its
    canonical spelling (``"nrel5mw"``), else the turbine file's name without its suffix; for a
    :class:`~windflutter.model.Turbine`, of the file it was read from."""
    src = turbine if isinstance(turbine, (str, Path)) else (getattr(turbine, "source", "") or "")
    bundled = {path: name for name, path in bundled_turbines().items()}
    if isinstance(src, str) and src and not Path(src).exists():
        try:
            src = resolve_turbine_path(src)
        except InputError:
            pass
    stem = bundled.get(Path(src), Path(str(src)).stem) if str(src) else ""
    if not stem and not isinstance(turbine, (str, Path)):
        stem = str(getattr(turbine, "name", ""))
    safe = re.sub(r"[^A-Za-z0-9._+-]+", "_", stem).strip("._")
    return safe or "turbine"
