"""Issue 33: what moves the IEA 22 MW shell's 1st torsion away from the beam of the same blade
(docs/notes/shell_same_blade.md section 3).

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/shell_torsion_diagnosis.py [V ...]
(default 8 11 m/s; about a minute per wind speed single thread, plus 40 s to build the models).

The blade alone, clamped at the root, no aerodynamic operator, no Coriolis; the default shell mesh
against the beam on the shell's extracted properties (40 stations).  Per wind speed (the operating
curve's rotor speed and pitch, each model's own steady state):
* the 1st torsion (the lowest mode between 3.5 and 4.6 Hz with the largest torsion share) of the
  undeformed blade, of the deflected blade without and with its steady-stress stiffness;
* the first-order shift ``phi^T K_sigma phi / (2 omega^2)`` of the steady stress on the deflected
  blade's torsion mode ``phi`` (mass-normalized): the beam's by resultant (axial, shear, torsion,
  bending); the shell's complete initial stress (structure/shell_stress.py) of its stress balanced on
  the bent geometry (system/deflected_shell.py ``balanced_stress``), of the carried stress alone, and
  the carried membrane-only one, the latter by membrane resultant (Nxx spanwise, Nyy hoop, Nxy) and load (centrifugal,
  aerodynamic); the modes between 3 and 8 Hz with their torsion share and tip-panel share (with
  either stress);
* the same on the undeformed blade with the linear steady stress (the classical initial-stress
  matrix of both models: the beam's linear steady state, ``corotational=False``).
"""

from __future__ import annotations

import sys
import warnings

import numpy as np
import scipy.sparse as sp

from windflutter.mesh.shell_beam import with_shell_blade_properties
from windflutter.model import load_turbine
from windflutter.structure.corotational import beam_tangent, linear_resultants, reference_configuration
from windflutter.structure.labels import blade_motion_components
from windflutter.structure.modal import symmetric_eigs
from windflutter.structure.prestress import geometric_stiffness, membrane_geometric_stiffness
from windflutter.structure.shell import shell_membrane_resultants
from windflutter.system.deflected import deflected_blade
from windflutter.system.deflected_shell import deflected_shell_blade, steady_stress_stiffness
from windflutter.system.operational import OperationalModel, OperationalOptions

BEAM_GROUPS = {"axial": [0, 6], "shear": [1, 2, 7, 8], "torsion": [3, 9], "bending": [4, 5, 10, 11]}


def clamped_modes(rb, ksigma, omega: float):
    """(f Hz, mass-normalized full-numbering modes, shares flap/edge/torsion) of the clamped blade's
    14 lowest modes under ``K + ksigma - omega^2 K_r``."""
    st = rb.struct
    K = st.K - omega**2 * rb.Kr1 + (ksigma if ksigma is not None else 0)
    Kq = sp.csc_matrix(st.T.T @ K @ st.T)
    w2, X = symmetric_eigs(0.5 * (Kq + Kq.T), sp.csc_matrix(st.T.T @ st.M @ st.T), 14, shift=0.0, v0=np.ones(st.nq))
    f = np.sqrt(np.maximum(w2, 0.0)) / (2 * np.pi)
    P = np.asarray(st.T @ X)
    e = np.sum(np.asarray(rb.sections.width)[None, :, None] * blade_motion_components(rb.sections, P) ** 2, axis=1)
    return f, P, e / e.sum(axis=0)


def torsion(rb, ksigma, omega: float):
    """(f Hz, mass-normalized full-numbering mode, shares flap/edge/torsion) of the clamped blade's
    1st torsion under ``K + ksigma - omega^2 K_r``."""
    f, P, sh = clamped_modes(rb, ksigma, omega)
    m = int(np.argmax(np.where((f > 3.5) & (f < 4.6), sh[2], -1.0)))
    return f[m], P[:, m], sh[:, m]


def tip_panels(rb, ksigma, omega: float) -> str:
    """The clamped blade's modes between 3 and 8 Hz under ``K + ksigma - omega^2 K_r``: frequency
    (Hz), torsion share and the share of the mode's kinetic energy (diagonal of M) in the outer 3 %
    of the span (a tip-panel mode: most of it)."""
    st = rb.struct
    f, P, sh = clamped_modes(rb, ksigma, omega)
    x = np.asarray(rb.fe.nodes, float)
    t = np.asarray(rb.sections.e_span, float)[-1]
    s = (x - x[np.argmin(x @ t)]) @ t
    m = st.M.diagonal().reshape(-1, 6)[:, :3].sum(axis=1)
    ke = m[:, None] * np.sum(P.reshape(-1, 6, P.shape[1])[:, :3, :] ** 2, axis=1)
    tip = ke[s > 0.97 * s.max()].sum(axis=0) / ke.sum(axis=0)
    return ", ".join(f"{f[k]:.2f} Hz (torsion {sh[2, k]:.2f}, tip {tip[k]:.2f})" for k in range(len(f)) if 3.0 < f[k] < 8.0)


def shift(K, f: float, phi: np.ndarray) -> float:
    """First-order relative frequency shift (%) of ``K`` on the mode ``phi``."""
    return 100.0 * 0.5 * float(phi @ (K @ phi)) / (2 * np.pi * f) ** 2


def beam_point(obm, obl, V: float) -> None:
    omega, pitch = obm.operating_point(V)
    rb = obm.blade(pitch)
    d = deflected_blade(rb, obm.steady(rb, V, omega), omega)
    f0 = torsion(rb, None, omega)[0]
    f, phi, sh = torsion(d.blade, None, omega)
    g = d.equilibrium.tangent.resultants
    parts = {}
    for lab, idx in BEAM_GROUPS.items():
        gm = np.zeros_like(g)
        gm[:, idx] = g[:, idx]
        parts[lab] = round(shift(beam_tangent(rb.fe, d.equilibrium.config, resultants=gm).K_geo, f, phi), 2)
    print(f"  beam : undeformed {f0:.3f} Hz; deflected {f:.3f} Hz (shares {np.round(sh, 2)}), with its stress "
          f"{torsion(d.blade, d.ksigma, omega)[0]:.3f} Hz; first order {shift(d.ksigma, f, phi):+.2f} % = {parts}")
    rl = obl.blade(pitch)
    K = beam_tangent(rl.fe, reference_configuration(rl.fe), resultants=linear_resultants(rl.fe, obl.steady(rl, V, omega).u)).K_geo
    f0, phi0, _ = torsion(rl, None, omega)
    print(f"         undeformed with the linear stress: first order {shift(K, f0, phi0):+.2f} %")


def shell_point(osh, V: float) -> None:
    omega, pitch = osh.operating_point(V)
    rb = osh.blade(pitch)
    st = osh.steady(rb, V, omega)
    d = deflected_shell_blade(rb, st, omega)
    f0, phi0, _ = torsion(rb, None, omega)
    f, phi, sh = torsion(d.blade, None, omega)
    N = shell_membrane_resultants(rb.fe, st.u)
    Ncf = shell_membrane_resultants(rb.fe, rb.unit_prestress()[2] * omega**2)
    fk = torsion(d.blade, d.ksigma, omega)
    Km = steady_stress_stiffness(rb.fe, d.blade.fe, st.u, d.rotations, complete=False)
    fm = torsion(d.blade, Km, omega)
    print(f"  shell: undeformed {f0:.3f} Hz; deflected {f:.3f} Hz (shares {np.round(sh, 2)}); with its stress: "
          f"complete {fk[0]:.3f} Hz (shares {np.round(fk[2], 2)}), membrane-only {fm[0]:.3f} Hz (shares "
          f"{np.round(fm[2], 2)}); first order complete {shift(d.ksigma, f, phi):+.2f} %, membrane-only "
          f"{shift(Km, f, phi):+.2f} %")
    comp = {c: round(shift(membrane_geometric_stiffness(d.blade.fe, N * np.eye(3)[i]), f, phi), 2)
            for i, c in enumerate(("Nxx", "Nyy", "Nxy"))}
    load = {lab: round(shift(membrane_geometric_stiffness(d.blade.fe, M), f, phi), 2)
            for lab, M in (("centrifugal", Ncf), ("aerodynamic", N - Ncf))}
    print(f"         membrane-only by resultant {comp} and load {load}")
    carried = deflected_shell_blade(rb, st, omega, balance=False).ksigma
    print(f"         the carried stress alone (not balanced on the bent geometry, the route before 5 Dec 2026): "
          f"first order complete {shift(carried, f, phi):+.2f} %")
    print(f"         modes 3-8 Hz, complete: {tip_panels(d.blade, d.ksigma, omega)}")
    print(f"         modes 3-8 Hz, membrane-only: {tip_panels(d.blade, Km, omega)}")
    Km0 = geometric_stiffness(rb.fe, st.u, shell="membrane")
    print(f"         undeformed with the linear stress: first order complete {shift(st.Ksigma, f0, phi0):+.2f} %, "
          f"membrane-only {shift(Km0, f0, phi0):+.2f} %")


def main(speeds) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = load_turbine("iea22mw")
        ts = with_shell_blade_properties(t, 40)
        osh = OperationalModel(t, OperationalOptions(model="shell", part="rotor"))
        obm = OperationalModel(ts, OperationalOptions(model="beam", part="rotor"))
        obl = OperationalModel(ts, OperationalOptions(model="beam", part="rotor", corotational=False))
        for V in speeds:
            omega, pitch = osh.operating_point(V)
            print(f"{V:g} m/s ({omega * 30 / np.pi:.2f} RPM, pitch {np.degrees(pitch):.1f} deg)", flush=True)
            beam_point(obm, obl, V)
            shell_point(osh, V)


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or [8.0, 11.0])
