"""Natural modes of a turbine model (parked or rotating), labelled: the engine of ``windflutter modes``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.errors import InputError
from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry
from windflutter.rotor.rotating import rotor_matrices
from windflutter.structure import assemble, modes
from windflutter.structure.labels import label_modes
from windflutter.units import RPM


@dataclass
class ModesResult:
    """Frequencies (Hz, ascending), labels, and the model/modes they come from."""

    frequencies_hz: np.ndarray
    labels: list[str]
    fe: object
    sections: object
    modes: object
    struct: object


def rotating_stiffness(fe, struct, turbine, omega: float):
    """Extra stiffness ``Ksigma - Kr`` (full numbering) at rotor speed ``omega`` (rad/s):
    centrifugal stiffening (geometric stiffness of the static centrifugal prestress) and spin
    softening, from :func:`windflutter.rotor.rotating.rotor_matrices` (Coriolis is left out of
    natural frequencies, as in BModes)."""

    _, Kr, Ks = rotor_matrices(fe, struct, omega, rotor_geometry(turbine), prestress=True)
    return (Ks - Kr).tocsr()


def turbine_modes(turbine, settings: MeshSettings | None = None, n_modes: int = 10, rpm: float = 0.0) -> ModesResult:
    """Build the model, assemble it and return its lowest ``n_modes`` labelled modes.

    Parameters
    ----------
    turbine : :class:`~windflutter.model.turbine.Turbine`.
    settings : mesh settings (model, part, counts, pitch, azimuth).
    n_modes : number of modes.
    rpm : rotor speed (rev/min); > 0 adds centrifugal stiffening and spin softening.
    """

    if not (np.isfinite(rpm) and rpm >= 0):
        raise InputError("rpm", rpm, "a non-negative rotor speed (rev/min)")
    st = settings or MeshSettings()
    if rpm > 0 and st.part == "tower":
        raise InputError("part", st.part, "blade, rotor or turbine when --rpm > 0 (the tower-only model has no rotor)")
    fe, sec = build_model(turbine, st)
    struct = assemble(fe)
    K_extra = rotating_stiffness(fe, struct, turbine, rpm * RPM) if rpm > 0 else None
    md = modes(struct, n_modes, K_extra=K_extra)
    labels = label_modes(fe, struct.M, md.shapes, sec)
    return ModesResult(np.asarray(md.freq), labels, fe, sec, md, struct)
