r"""Aero-work diagnostic: where does the flutter mode take its energy from?

Derivation
----------
Let a structure move harmonically, ``x(t) = Re(x̂ e^{iωt})`` (complex amplitude x̂), and let the
aerodynamic force on it be ``f(t) = Re(f̂ e^{iωt})``.  For the frequency-domain aerodynamic
matrices of the coupled equation (``Mt = Ms − Ma`` etc., i.e. the aero force is
``Ma ẍ + Da ẋ + Ka x``)::

    f̂ = (−ω² Ma + iω Da + Ka) x̂  =: A(ω) x̂.

The work done *by the air on the structure* over one period T = 2π/ω is
``W = ∫₀ᵀ f(t)·ẋ(t) dt`` with ``ẋ = Re(iω x̂ e^{iωt})``.  The period mean of a product of two
harmonics is ``⟨Re(a e^{iωt}) Re(b e^{iωt})⟩ = ½ Re(a b̄)``, so

    W = T · ½ Re(f̂ᴴ (iω x̂)) = π Re(i f̂ᴴ x̂) = −π Im(f̂ᴴ x̂) = π Im(x̂ᴴ f̂) = π Im(x̂ᴴ A x̂).

Term by term, DOF j receives ``W_j = π Im(conj(x̂_j) f̂_j)`` and ``W = Σ_j W_j``.  ``W > 0``: the
air feeds energy into the mode (destabilising); ``W < 0``: aerodynamic damping.  Only the part
of A out of phase with the motion does work; the symmetric real part (stiffness, mass) does none
over a cycle.  At the flutter onset the mode is neutrally stable, so W equals the energy the
structural damping dissipates per cycle, ``π ω x̂ᴴ Ds x̂`` (zero without structural damping);
W changes sign across the onset.  Tests (``tests/workflow/test_aerowork.py``) check the formula
against a time-domain quadrature of ``∫ f·ẋ dt`` and the sign change on a typical section.

Per span station and section DOF
--------------------------------
Each aerodynamic strip has plunge h (along the lift direction e1), pitch α (about the span axis
e2) and edgewise s (along the relative wind e3).  Their conjugate generalised forces are the
lift ``e1·F``, the moment ``e2·M`` and the drag-direction force ``e3·F``.  The station's work
splits into ``W_h = π Im(ĥ* L̂)``, ``W_α = π Im(α̂* M̂)``, ``W_s = π Im(ŝ* D̂)`` (J per cycle,
for the mode's normalisation; W scales with the square of the amplitude).

Everything here is plain NumPy; no solver is needed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "work_per_dof",
    "total_work",
    "harmonic_force",
    "to_section_dofs",
    "section_work",
    "normalise_mode",
    "ModeDiagnostics",
    "flutter_mode_diagnostics",
]


def work_per_dof(x_hat: ArrayLike, f_hat: ArrayLike) -> np.ndarray:
    """Work per cycle done by the harmonic force on each DOF, ``π Im(conj(x̂) f̂)``.

    Parameters
    ----------
    x_hat : complex amplitudes of the motion (m or rad).
    f_hat : complex amplitudes of the conjugate forces (N or N·m), same shape.

    Returns
    -------
    numpy.ndarray
        Work per cycle (J), the shape of the inputs.  Positive: energy into the structure.
    """
    x = np.asarray(x_hat, complex)
    f = np.asarray(f_hat, complex)
    return np.pi * np.imag(np.conj(x) * f)


def harmonic_force(x_hat: ArrayLike, omega: float, Ma=None, Da=None, Ka=None) -> np.ndarray:
    """Aero force amplitude ``(−ω² Ma + iω Da + Ka) x̂`` (dense or sparse matrices; None = 0)."""
    x = np.asarray(x_hat, complex)
    f = np.zeros_like(x)
    if Ma is not None:
        f = f - omega**2 * (Ma @ x)
    if Da is not None:
        f = f + 1j * omega * (Da @ x)
    if Ka is not None:
        f = f + Ka @ x
    return f


def total_work(x_hat: ArrayLike, A: np.ndarray) -> float:
    """``π Im(x̂ᴴ A x̂)``: total aero work per cycle for ``f̂ = A x̂`` (J)."""
    x = np.asarray(x_hat, complex)
    return float(np.pi * np.imag(np.vdot(x, A @ x)))


def to_section_dofs(u6: ArrayLike, e_lift: ArrayLike, e_span: ArrayLike, e_drag: ArrayLike) -> np.ndarray:
    """Project rigid section motions (or forces) on the section DOFs.

    Parameters
    ----------
    u6 : (ns, 6) complex translations (3) and rotations (3) per section, global axes — or forces
        (3) and moments (3).
    e_lift, e_span, e_drag : (ns, 3) unit vectors: lift direction (plunge), span (pitch axis),
        relative-wind direction (edgewise).

    Returns
    -------
    numpy.ndarray
        (ns, 3) complex: plunge h = e1·u, pitch α = e2·θ, edgewise s = e3·u — or lift,
        pitching moment and drag-direction force for force input.  The two are work-conjugate.
    """
    u = np.asarray(u6, complex).reshape(-1, 6)
    e1 = np.asarray(e_lift, float).reshape(-1, 3)
    e2 = np.asarray(e_span, float).reshape(-1, 3)
    e3 = np.asarray(e_drag, float).reshape(-1, 3)
    return np.stack([np.einsum("ij,ij->i", u[:, :3], e1),
                     np.einsum("ij,ij->i", u[:, 3:], e2),
                     np.einsum("ij,ij->i", u[:, :3], e3)], axis=1)


def section_work(motion: ArrayLike, force: ArrayLike) -> np.ndarray:
    """Aero work per cycle per station and section DOF (plunge, pitch, edgewise), J.

    Parameters
    ----------
    motion : (ns, 3) complex section DOF amplitudes (h m, α rad, s m).
    force : (ns, 3) complex conjugate aero forces (lift N, moment N·m, drag-direction force N),
        on the whole strip (already multiplied by the strip width).
    """
    return work_per_dof(np.asarray(motion, complex).reshape(-1, 3), np.asarray(force, complex).reshape(-1, 3))


def normalise_mode(phi: ArrayLike, reference: ArrayLike | None = None) -> np.ndarray:
    """Scale a complex mode so the entry of largest modulus (of ``reference`` if given, a
    boolean mask or index array into ``phi``) becomes real and 1."""
    p = np.asarray(phi, complex)
    flat = p.ravel()
    idx = np.arange(flat.size) if reference is None else np.arange(flat.size)[np.asarray(reference).ravel()]
    if idx.size == 0 or not np.any(flat[idx]):
        return p
    j = idx[np.argmax(np.abs(flat[idx]))]
    return p / flat[j]


@dataclass
class ModeDiagnostics:
    """Flutter-mode pictures along one blade.

    Attributes
    ----------
    blade : index of the blade shown (largest modal amplitude).
    radius : (nb,) radii of its strips (m).
    shape : (nb, 3) complex flap (m, along chord x span: suction side), edge (m, along the
        chord towards the trailing edge) and torsion (rad, about the span axis) at the strips'
        elastic-axis points; the mode is scaled so that the largest |flap| or |edge| of the
        shown blade is 1 m with zero phase.
    work : (nb, 3) aero work per cycle (J) on plunge, pitch and edgewise, summed over all
        blades at the same strip position (all blades' strips when counts differ: shown blade
        only), for that scaling.
    work_total : total over every strip of the rotor (J).
    """

    blade: int
    radius: np.ndarray
    shape: np.ndarray
    work: np.ndarray
    work_total: float


def flutter_mode_diagnostics(u: ArrayLike, strip, sections, omega: float) -> ModeDiagnostics:
    """Mode shape and aero work of a structural mode ``u`` on a turbine's strips.

    Parameters
    ----------
    u : (n_dof,) complex mode in the unconstrained DOF numbering (``6 node + c``).
    strip : :class:`windflutter.aero.strip.StripAero` of the operating point (gives the section
        motion map ``P`` (3 ns, n_dof) onto (h, α, s) and the per-strip matrices
        ``section_blocks(omega)`` already multiplied by the strip widths).
    sections : the :class:`~windflutter.aero.sections.AeroSections`.
    omega : frequency of the mode (rad/s); the aero forces are the harmonic ones at ``omega``.
    """
    u = np.asarray(u, complex).ravel()
    ns = sections.n_sections
    m6 = np.asarray(sections.motion_map @ u).reshape(ns, 6)
    span = np.asarray(sections.e_span, float)
    chord = np.asarray(sections.e_chord, float)
    span = span / np.linalg.norm(span, axis=1, keepdims=True)
    chord = chord / np.linalg.norm(chord, axis=1, keepdims=True)
    flapdir = np.cross(chord, span)
    shape = np.stack([np.einsum("ij,ij->i", m6[:, :3], flapdir),
                      np.einsum("ij,ij->i", m6[:, :3], chord),
                      np.einsum("ij,ij->i", m6[:, 3:], span)], axis=1)
    blade_of = np.asarray(sections.blade, dtype=np.int64)
    blades = np.unique(blade_of)
    amp = [np.abs(shape[blade_of == b, :2]).max(initial=0.0) for b in blades]
    b_show = int(blades[int(np.argmax(amp))])
    sel = np.where(blade_of == b_show)[0]
    trans = shape[sel, :2].ravel()
    ref = trans[np.argmax(np.abs(trans))] if trans.size and np.abs(trans).max() > 0 else 1.0
    scale = 1.0 / ref
    u = u * scale
    shape = shape * scale
    q = np.asarray(strip.P @ u).reshape(ns, 3)
    Ma, Da, Ka = strip.section_blocks(omega)
    A = -omega**2 * Ma + 1j * omega * Da + Ka
    f = np.einsum("jab,jb->ja", A, q)
    w = section_work(q, f)
    counts = [np.sum(blade_of == b) for b in blades]
    if len(set(counts)) == 1:
        order = np.argsort(np.asarray(sections.radius)[sel], kind="stable")
        w_sum = np.zeros((sel.size, 3))
        for b in blades:
            idx = np.where(blade_of == b)[0]
            idx = idx[np.argsort(np.asarray(sections.radius)[idx], kind="stable")]
            w_sum[order] += w[idx]
        work = w_sum
    else:
        work = w[sel]
    r = np.asarray(sections.radius, float)[sel]
    return ModeDiagnostics(b_show, r, shape[sel], work, float(w.sum()))
