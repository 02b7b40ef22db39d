"""Turbines shipped with windflutter (``src/windflutter/data``), addressable by short name."""

from __future__ import annotations

from pathlib import Path

from windflutter.errors import InputError

DATA_DIR = Path(__file__).resolve().parent.parent / "data"

_BUNDLED = {
    "nrel5mw": "turbines/NREL-5MW.yaml",
    "iea15mw": "turbines/IEA-15-240-RWT.yaml",
    "iea22mw": "turbines/IEA-22-280-RWT.yaml",
    "iea10mw": "turbines/IEA-10-198-RWT.yaml",
    "nrel5mw_v1": "turbines/windIO_v1/NREL-5MW.yaml",
    "iea15mw_v1": "turbines/windIO_v1/IEA-15-240-RWT.yaml",
    "iea22mw_v1": "turbines/windIO_v1/IEA-22-280-RWT.yaml",
    "iea10mw_v1": "turbines/windIO_v1/IEA-10-198-RWT.yaml",
    "seed5mw": "seed/seed5mw.yaml",
    "seed20mw": "seed/seed20mw.yaml",
    "nrel5mw_openfast": "nrel5mw/NREL-5MW_Onshore.fst",
    "nrel5mw_hawc2": "nrel5mw/hawc2/htc/NREL_5MW.htc",
    "iea15mw_openfast": "iea15mw/openfast/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile.fst",
}


def bundled_turbines() -> dict[str, Path]:
    """Name -> file of every bundled turbine."""
    return {k: DATA_DIR / v for k, v in _BUNDLED.items()}


def resolve_turbine_path(path_or_name: str | Path) -> Path:
    """A bundled name (case-insensitive, ``-``/``_`` ignored) or an existing path."""
    if isinstance(path_or_name, str):
        key = path_or_name.strip().lower().replace("-", "").replace(" ", "")
        key_nu = key.replace("_", "")
        for name, rel in _BUNDLED.items():
            if key == name or key_nu == name.replace("_", ""):
                return DATA_DIR / rel
    p = Path(path_or_name)
    if p.is_file():
        return p
    raise InputError("turbine", str(path_or_name),
                     f"an existing turbine file or a bundled name ({', '.join(_BUNDLED)})")
