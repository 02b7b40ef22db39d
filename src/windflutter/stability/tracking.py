"""Mode labels from the motion at the aerodynamic sections (the MAC lives in
:mod:`windflutter.linalg_tools`; re-exported here for older imports)."""

from __future__ import annotations

import numpy as np

from windflutter.linalg_tools import mac, mac_matrix  # noqa: F401  (re-exported)


def label_mode(x_dof: np.ndarray, sections, P=None, tower_dofs: np.ndarray | None = None) -> str:
    """Label a mode from its motion at the aerodynamic sections.

    Parameters
    ----------
    x_dof : (n_dof,) mode shape, unconstrained numbering.
    sections : :class:`~windflutter.aero.sections.AeroSections`.
    P : (3 ns, n_dof) section-motion map (h, alpha, s) of a :class:`StripAero`; when None the
        global translations/rotations of ``motion_map`` are used.
    tower_dofs : translational DOFs of the tower, to detect tower modes.

    Returns
    -------
    str like ``"flap b1 r/R=1.00"``, ``"torsion b2 r/R=0.80"``, ``"edge ..."``, ``"tower"``.
    """
    ns = sections.n_sections
    b = np.asarray(sections.semi_chord, float)
    q = (P @ x_dof).reshape(ns, 3)
    h, al, s = np.abs(q[:, 0]), np.abs(q[:, 1]) * b, np.abs(q[:, 2])
    energy = np.array([np.sum(h**2), np.sum(al**2), np.sum(s**2)])
    blade_e = h**2 + al**2 + s**2
    if tower_dofs is not None and tower_dofs.size:
        t = np.max(np.abs(x_dof[tower_dofs]))
        if t > np.sqrt(blade_e.max(initial=0.0)):
            return "tower"
    names = ("flap", "torsion", "edge")
    order = np.argsort(energy)[::-1]
    kind = names[order[0]]
    if energy[order[1]] > 0.3 * energy[order[0]]:  # strongly coupled, e.g. flap-torsion flutter
        kind = f"{kind}-{names[order[1]]}"
    j = int(np.argmax(blade_e))
    r = np.asarray(sections.radius, float)
    blade = np.asarray(sections.blade)[j]
    rr = r[j] / r[np.asarray(sections.blade) == blade].max()
    return f"{kind} b{int(blade) + 1} r/R={rr:.2f}"
