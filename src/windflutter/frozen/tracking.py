"""Names of the seed model's modes (frozen azimuth, p-k and thesis searches) in the field's terms.

The modes a p-k search tracks are named at the first rotor speed of the sweep, where they are
still close to the structural modes they grew from, by :func:`windflutter.structure.labels.
label_modes` -- the vocabulary of ``windflutter modes`` and, with multi-blade whirl in place of
collective/asymmetric, of ``campbell`` (``"1st torsion asymmetric"``, ``"2nd flap collective"``,
``"1st tower fore-aft"``).  A flutter mode keeps the name of the mode it grew from: at onset a
classical-flutter mode is a flap-torsion mixture whose largest part can be either.  Orders count
the tracked modes of a kind in frequency order in families of one per blade (``label_modes``);
a copy of a blade mode that the tower takes over at a frozen azimuth can shift the later orders
of its kind by one.
"""

from __future__ import annotations

import numpy as np
from windflutter.structure.labels import blade_motion_components, label_modes
from windflutter.system.identity import identity_name
from windflutter.system.reference import StructuralReference

__all__ = ["real_shapes", "mode_names", "has_torsion"]


def real_shapes(vectors: np.ndarray) -> np.ndarray:
    """(n, m) real shapes of complex mode shapes (columns): each turned so that its largest
    component is real, then its real part (a lightly damped mode's shape is nearly real)."""
    V = np.asarray(vectors)
    if not np.iscomplexobj(V):
        return V.astype(float)
    k = np.argmax(np.abs(V), axis=0)
    ph = V[k, np.arange(V.shape[1])]
    return np.real(V * (np.abs(ph) / np.where(ph == 0, 1.0, ph))[None, :])


def mode_names(fe, M, shapes: np.ndarray, frequencies: np.ndarray, sections, reference=None) -> list[str]:
    """Names of the modes ``shapes`` (n_dof, m; full numbering, any order) at ``frequencies`` (Hz).

    Parameters
    ----------
    fe : the model (node groups).  M : its full-numbering mass matrix.
    shapes : mode shapes (real or complex).  frequencies : (m,) their frequencies (Hz).
    sections : the model's aerodynamic strips.
    reference : the blade's structural identities (:class:`~windflutter.system.identity.
        StructuralReference`): a blade mode is then named as method p names it, by the blade's own
        mode it is most of (``"2nd flap collective"``, ``"1st torsion asymmetric"``), not by its
        rank in frequency; tower modes keep :func:`~windflutter.structure.labels.label_modes`'s names.
    """

    f = np.asarray(frequencies, float)
    order = np.argsort(f, kind="stable")
    X = real_shapes(shapes)[:, order]
    names = label_modes(fe, M, X, sections)
    if reference is not None and sections is not None and sections.n_sections:

        ids = frozen_blade_identities(sections, blade_motion_components(sections, X), reference)
        for j, ident in enumerate(ids):
            if ident is not None and "tower" not in names[j]:
                family, order_, whirl = ident
                names[j] = identity_name(family, whirl, order_)
    out = [""] * len(f)
    for j, i in enumerate(order):
        out[i] = names[j]
    return out


def has_torsion(name: str) -> bool:
    """A blade-torsion name (``"1st torsion asymmetric"``)."""
    return " torsion" in f" {name}" and "tower" not in name


def frozen_blade_identities(sections, comps: np.ndarray, reference: StructuralReference) -> list:
    """``(family, order, whirl)`` of each mode of a frozen-azimuth rotor model by its blades' strip
    motion ``comps`` (3, ns, n: :func:`~windflutter.structure.labels.blade_motion_components` of the
    whole model, strips tagged by ``sections.blade``): each blade's motion is expanded in the
    reference modes' strip signatures (least squares), the reference mode with the largest summed
    square amplitude over the blades names it (meant for structural modes, nearly pure: the strain
    weighting of :func:`windflutter.system.identity.participations` would weight up the least-squares noise of the high
    reference modes), and its blade amplitudes ``c_b`` give the whirl --
    ``collective`` when the collective part carries more than half (``N mean(c)^2 > sum c^2 / 2``),
    else ``asymmetric`` (a frozen azimuth has no whirl).  None for every mode when the blades' strips
    do not match the reference's."""
    blade = np.asarray(sections.blade)
    nb = int(blade.max()) + 1 if blade.size else 0
    w = np.sqrt(np.asarray(sections.width, float))
    per = [np.flatnonzero(blade == b) for b in range(nb)]
    if not nb or any(3 * len(ix) != reference.signatures.shape[0] for ix in per):
        return [None] * comps.shape[-1]
    # the lowest reference modes, at most one per strip: the fit stays three times overdetermined
    R = reference.signatures[:, :len(per[0])]
    C = []
    for ix in per:
        s = (comps[:, ix, :] * w[ix][None, :, None]).reshape(3 * len(ix), -1)
        C.append(np.linalg.lstsq(R, s, rcond=None)[0])  # (n_ref, n)
    C = np.stack(C)  # (nb, n_ref, n)
    energy = np.sum(np.abs(C) ** 2, axis=0)
    out = []
    for i in range(comps.shape[-1]):
        j = int(np.argmax(energy[:, i]))
        c = C[:, j, i]
        fam, order, _ = reference.blade[j]
        whirl = "collective" if nb * abs(np.mean(c)) ** 2 > 0.5 * np.sum(np.abs(c) ** 2) else "asymmetric"
        out.append((fam, order, whirl))
    return out
