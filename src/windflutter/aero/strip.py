"""The thesis's strip aerodynamics: Theodorsen's frequency-domain matrices (p-k).

For every strip of an :class:`~windflutter.aero.sections.AeroSections` at an
:class:`~windflutter.aero.flow.OperatingPoint` (relative flow, inflow axes ``e1`` lift, ``e2``
pitch, ``e3`` drag and the section motion ``q = (h, alpha, s)``: :mod:`windflutter.aero.flow`):

* Theodorsen's forces (Bisplinghoff-Ashley-Halfman / Hodges & Pierce form with h positive
  *down*; here rewritten for h up), frozen at ``C(k_j)``, ``k_j = omega b_j / U_j``:
  ``F_j = (Ma_j s^2 + Da_j s + Ka_j) q_j`` per unit span, times the strip width;
* global matrices by consistent virtual work: ``A = P^T blockdiag(A_j) P`` with
  ``P = E motion_map`` (``E`` picks (e1.u, e2.theta, e3.u) of each section).

The coupled equation of motion is then ``(Ms - Ma) u'' + (Ds + G - Da) u' + (Ks - Kr - Ka) u = 0``.

Variants (seed ch. 3.2, eqs. 3.49-3.54): ``"potential"`` (lift slope 2 pi, no drag) and
``"viscous"`` (circulatory 2 pi replaced by the polar's fitted ``Cl_alpha``; drag
``D = rho U^2 b Cd_alpha alpha_unsteady`` along ``e3`` with
``alpha_unsteady = L_circ / (Cl_alpha rho U^2 b)``; apparent-mass terms optionally scaled by
``Cl_alpha / 2 pi``).  This is the seed's model, kept number for number; the state-space and
mean-load operators are in :mod:`windflutter.aero.unsteady` (docs/aero_operators.md).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
import scipy.sparse as sp

from windflutter.aero.flow import OperatingPoint, SectionFlow, section_flow, section_map  # noqa: F401 (re-export)
from windflutter.aero.polars import fit_polar
from windflutter.aero.sections import AeroSections
from windflutter.aero.statespace import block_diagonal
from windflutter.aero.theodorsen import theodorsen
from windflutter.errors import InputError

#: Theodorsen's function (the one implementation, :func:`windflutter.aero.theodorsen.theodorsen`).
theodorsen_c = theodorsen


@dataclass(frozen=True)
class AeroOptions:
    """Which strip model.

    Parameters
    ----------
    model : ``"potential"`` or ``"viscous"``.
    apparent_mass_scaling : scale apparent-mass (non-circulatory) terms by ``Cl_alpha / 2 pi``
        (viscous only; the seed does this).
    lift_slope : optional per-section ``Cl_alpha`` (1/rad) overriding the polar fits (viscous),
        shape (ns,) or scalar.
    drag_slope : optional per-section ``Cd_alpha`` (1/rad), same rules.
    steady_loads : add the quasi-steady damping of the *mean* loads (HAWCStab2 has it, the seed
        does not): a section moving with ``s'`` along the relative wind and ``h'`` across it
        changes the dynamic pressure (``2 U s'``) and turns the wind (by ``-h'/U``), so the mean
        lift, drag and moment ``Cl0, Cd0, Cm0`` -- from the airfoil polars at each strip's
        steady angle of attack, in both models -- give forces proportional to the section
        velocity: the edgewise aerodynamic damping of a rotor blade.  Needs polars.
    """

    model: str = "potential"
    apparent_mass_scaling: bool = False
    lift_slope: np.ndarray | float | None = None
    drag_slope: np.ndarray | float | None = None
    steady_loads: bool = False

    def __post_init__(self):
        if self.model not in ("potential", "viscous"):
            raise InputError("aero.model", self.model, "'potential' or 'viscous'")


@dataclass(frozen=True)
class SectionParts:
    """The frequency-independent pieces of the Theodorsen section matrices (per unit span).

    ``Ma`` and ``Da_nc`` (ns, 3, 3) are the apparent-mass terms (``Da_nc`` also holds the
    quasi-steady damping of the mean loads, when given).  The circulatory part is rank
    one per section -- one downwash ``Q`` drives one lift, whose moment and drag are fixed
    multiples of it: ``Da_c = C circ row col_d^T``, ``Ka_c = C circ row col_k^T`` with
    ``circ = cla rho U b`` (ns,), ``row = (1, moment arm, Cd_a / Cl_a)`` and the downwash
    coefficients ``col_d = (-1, b (1/2 - a), 0)`` (of q'), ``col_k = (0, U, 0)`` (of q), all (ns, 3).
    """

    Ma: np.ndarray
    Da_nc: np.ndarray
    circ: np.ndarray
    row: np.ndarray
    col_d: np.ndarray
    col_k: np.ndarray

    def matrices(self, C):
        """``(Ma, Da, Ka)`` (ns, 3, 3) complex for Theodorsen values ``C`` (ns,)."""
        q = (np.asarray(C) * self.circ)[:, None, None]
        Da = self.Da_nc + q * (self.row[:, :, None] * self.col_d[:, None, :])
        Ka = q * (self.row[:, :, None] * self.col_k[:, None, :])
        return self.Ma.astype(complex), Da, Ka


def apparent_mass(b, a, U, rho, scale=1.0):
    """Theodorsen's non-circulatory (apparent-mass) terms per unit span, ``q = (h up, alpha, s)``.

    ``b, a, U`` (ns,) semi-chord (m), elastic axis aft of mid-chord (semi-chords), speed (m/s);
    ``rho`` (kg/m^3); ``scale`` scalar or (ns,) factor (1: flat plate).  Returns ``(Ma, Da)``
    (ns, 3, 3) real with the forces ``Ma q'' + Da q'``.  With ``h_down = -h``::

        L_nc = pi rho b^2 (h_down'' + U alpha' - b a alpha'')
        M_nc = pi rho b^2 (b a h_down'' - U b (1/2 - a) alpha' - b^2 (1/8 + a^2) alpha'')
    """
    b, a, U = (np.asarray(x, float) for x in (b, a, U))
    ns = b.shape[0]
    am = np.broadcast_to(np.asarray(scale, float), (ns,))
    Ma = np.zeros((ns, 3, 3))
    Da = np.zeros((ns, 3, 3))
    pr = np.pi * rho
    Ma[:, 0, 0] = -pr * b**2 * am
    Ma[:, 0, 1] = -pr * b**3 * a * am
    Ma[:, 1, 0] = -pr * b**3 * a * am
    Ma[:, 1, 1] = -pr * b**4 * (0.125 + a**2) * am
    Da[:, 0, 1] = pr * b**2 * U * am
    Da[:, 1, 1] = -pr * b**3 * U * (0.5 - a) * am
    return Ma, Da


def section_parts(b, a, U, rho, cla=2 * np.pi, cda=0.0, am_scale=1.0, ac_shift=0.0,
                  steady=None) -> SectionParts:
    """Frequency-independent pieces of :func:`section_matrices` (same parameters, no ``C``).

    ``steady``: optional ``(Cl0, Cd0, Cm0)`` mean coefficients per section (scalars or (ns,);
    ``Cm0`` about the quarter chord).  With the section velocity ``h'`` (along e1, across the
    wind) and ``s'`` (along e3, with the wind) the relative wind is ``(U - s') e3 - h' e1``: the
    dynamic pressure changes by ``-rho U s'`` and the wind turns by ``-h'/U``, which tilts the
    mean lift towards e3 and the mean drag towards -e1.  To first order (the change of the
    angle of attack, ``-h'/U``, is Theodorsen's circulatory term already):
    ``dL = -rho c U (Cd0 h' / 2 + Cl0 s')``, ``dD = rho c U (Cl0 h' / 2 - Cd0 s')``,
    ``dM = arm dL - rho c^2 U Cm0 s'`` (``arm``: the lift's moment arm about the elastic axis).
    """
    b, a, U = (np.asarray(x, float) for x in (b, a, U))
    ns = b.shape[0]
    cla = np.broadcast_to(np.asarray(cla, float), (ns,))
    cda = np.broadcast_to(np.asarray(cda, float), (ns,))
    dac = np.broadcast_to(np.asarray(ac_shift, float), (ns,))
    Ma, Da = apparent_mass(b, a, U, rho, am_scale)
    # circulatory: Q = C [h_down' + U alpha + b (1/2 - a) alpha'] -> L_c = cla rho U b Q; the
    # moment about the elastic axis is b (a + 1/2) L_c with the lift at the quarter chord, the
    # drag D = (Cd_a / Cl_a) L_c
    drag = np.where(cla != 0, cda / np.where(cla != 0, cla, 1.0), 0.0)
    arm = b * (a + 0.5 - 2.0 * dac)
    row = np.stack([np.ones(ns), arm, drag], axis=1)
    if steady is not None:
        cl0, cd0, cm0 = (np.broadcast_to(np.asarray(x, float), (ns,)) for x in steady)
        rcu = rho * 2.0 * b * U  # rho c U
        dL_h, dL_s = -0.5 * rcu * cd0, -rcu * cl0
        Da[:, 0, 0] += dL_h
        Da[:, 0, 2] += dL_s
        Da[:, 2, 0] += 0.5 * rcu * cl0
        Da[:, 2, 2] += -rcu * cd0
        Da[:, 1, 0] += arm * dL_h
        Da[:, 1, 2] += arm * dL_s - rcu * 2.0 * b * cm0
    zero = np.zeros(ns)
    col_d = np.stack([-np.ones(ns), b * (0.5 - a), zero], axis=1)
    col_k = np.stack([zero, U, zero], axis=1)
    return SectionParts(Ma=Ma, Da_nc=Da, circ=cla * rho * U * b, row=row, col_d=col_d, col_k=col_k)


def section_matrices(b, a, U, C, rho, cla=2 * np.pi, cda=0.0, am_scale=1.0, ac_shift=0.0, steady=None):
    """Theodorsen section matrices per unit span in ``q = (h up, alpha nose-up, s along U)``.

    Parameters
    ----------
    b : (ns,) semi-chord (m).  a : (ns,) elastic axis aft of mid-chord (semi-chords).
    U : (ns,) relative speed (m/s).  C : (ns,) complex Theodorsen values C(k_j).
    rho : air density (kg/m^3).  cla, cda : lift and drag slopes (1/rad), scalars or (ns,).
    am_scale : factor on the apparent-mass terms (1, or Cl_alpha / 2 pi).
    ac_shift : aerodynamic centre aft of the quarter chord (fraction of chord, ``-Cm_alpha /
        Cl_alpha`` of a polar), scalar or (ns,); the circulatory lift acts there, so its moment
        arm about the elastic axis is ``b (a + 1/2) - 2 b ac_shift``.  0 (default): Theodorsen's
        quarter chord, as in the seed's eqs. 3.49-3.54.
    steady : optional mean ``(Cl0, Cd0, Cm0)``: the quasi-steady mean-load damping of
        :func:`section_parts`; None (default) is the seed's model.

    Returns
    -------
    Ma, Da, Ka : (ns, 3, 3) complex, so that the section forces (lift along e1 (N/m), moment
    about e2 (N m/m), drag along e3 (N/m)) are ``Ma q'' + Da q' + Ka q``.  The pieces that do
    not depend on ``C`` are :func:`section_parts`.
    """
    return section_parts(b, a, U, rho, cla, cda, am_scale, ac_shift, steady).matrices(C)


def mean_coefficients(sections: AeroSections, alpha: np.ndarray):
    """Mean ``(Cl0, Cd0, Cm0)`` (ns,) of every strip from its polar table at angle ``alpha`` (rad).

    Linear interpolation of the tabulated polar (``Polar.alpha`` increasing); angles outside a
    table take its end values.
    """
    if not sections.polars:
        raise InputError("sections.polars", "[]", "airfoil polars for the mean-load damping (steady_loads)")
    idx = np.asarray(sections.airfoil, dtype=np.int64)
    alpha = np.asarray(alpha, float)
    out = np.zeros((3, sections.n_sections))
    for k in np.unique(idx):  # one pass per airfoil, vectorized over its strips
        p, sel = sections.polars[int(k)], idx == k
        for row, c in enumerate((p.cl, p.cd, p.cm)):
            out[row, sel] = np.interp(alpha[sel], np.asarray(p.alpha, float), np.asarray(c, float))
    return out[0], out[1], out[2]


def lift_drag_slopes(sections: AeroSections, options: AeroOptions):
    """Per-section (Cl_alpha, Cd_alpha) for the chosen model (1/rad)."""
    ns = sections.n_sections
    if options.model == "potential":
        cla = np.full(ns, 2 * np.pi) if options.lift_slope is None else np.broadcast_to(
            np.asarray(options.lift_slope, float), (ns,)).copy()
        return cla, np.zeros(ns)

    fits = [fit_polar(p) for p in sections.polars] if sections.polars else []
    idx = np.asarray(sections.airfoil, dtype=np.int64)
    if options.lift_slope is not None:
        cla = np.broadcast_to(np.asarray(options.lift_slope, float), (ns,)).copy()
    elif fits:
        cla = np.array([fits[i].cl_alpha for i in idx])
    else:
        raise InputError("sections.polars", "[]", "airfoil polars for the viscous model (or a lift_slope)")
    if options.drag_slope is not None:
        cda = np.broadcast_to(np.asarray(options.drag_slope, float), (ns,)).copy()
    elif fits:
        cda = np.array([fits[i].cd_alpha for i in idx])
    else:
        cda = np.zeros(ns)
    return cla, cda


@dataclass
class StripAero:
    """Precomputed strip geometry for one operating point; call :meth:`matrices` per frequency.

    Attributes
    ----------
    flow : the section flow.  P : (3 ns, n_dof) section-motion map.  width : strip widths (m).
    cla, cda : slopes used (1/rad).  steady : mean ``(Cl0, Cd0, Cm0)`` at the strips' angles of
    attack with ``options.steady_loads``, else None.
    circulation : ``k -> C(k)`` (vectorized), exact Theodorsen by default; e.g.
        :func:`~windflutter.aero.theodorsen.jones` or a :class:`~windflutter.aero.theodorsen.RogerRFA`
        for p-k with the rational approximation a state-space operator realises.
    """

    sections: AeroSections
    op: OperatingPoint
    options: AeroOptions = field(default_factory=AeroOptions)
    circulation: Callable = theodorsen

    def __post_init__(self):
        self.flow = section_flow(self.sections, self.op)
        self.P = section_map(self.sections, self.flow)
        self.PT = self.P.T.tocsr()
        self.width = np.asarray(self.sections.width, float)
        self.b = np.asarray(self.sections.semi_chord, float)
        self.a = np.asarray(self.sections.elastic_axis, float)
        self.cla, self.cda = lift_drag_slopes(self.sections, self.options)
        if self.options.model == "viscous" and self.options.apparent_mass_scaling:
            self.am = self.cla / (2 * np.pi)
        else:
            self.am = np.ones_like(self.cla)
        self.steady = mean_coefficients(self.sections, self.flow.alpha) if self.options.steady_loads else None

    #: frequency domain only (C(k) frozen at the oscillation frequency): no state-space form
    time_domain: ClassVar[bool] = False
    n_states: ClassVar[int] = 0

    def state_space(self):
        """Not available: Theodorsen's C(k) has no finite state-space realisation (use
        :class:`~windflutter.aero.operators.StateSpaceAero` with a rational C)."""
        raise InputError("aero.model", f"thesis ({self.options.model})",
                         "a state-space operator (UnsteadyOptions) for the first-order system")

    def reduced_frequency(self, omega: float) -> np.ndarray:
        """``k_j = omega b_j / U_j`` (-)."""
        return abs(omega) * self.b / self.flow.U

    def section_blocks(self, omega: float):
        """(ns, 3, 3) Ma, Da, Ka blocks (times strip width) at circular frequency ``omega`` (rad/s)."""
        Ma, Da, Ka = self.parts().matrices(self.circulation(self.reduced_frequency(omega)))
        w = self.width[:, None, None]
        return Ma * w, Da * w, Ka * w

    def _assemble(self, blocks: np.ndarray) -> sp.csr_matrix:
        return (self.PT @ block_diagonal(blocks) @ self.P).tocsr()

    def matrices(self, omega: float):
        """Global ``(Ma, Da, Ka)``, sparse complex (n_dof, n_dof), at frequency ``omega`` (rad/s)."""
        Ma, Da, Ka = self.section_blocks(omega)
        return self._assemble(Ma), self._assemble(Da), self._assemble(Ka)

    def parts(self) -> SectionParts:
        """The frequency-independent section pieces (:func:`section_parts`) of these strips."""
        return section_parts(self.b, self.a, self.flow.U, self.op.air_density, self.cla, self.cda, self.am,
                             steady=self.steady)

    def projected(self, Phi: np.ndarray):
        """Return a function ``omega -> (Ma, Da, Ka)`` projected on the basis ``Phi`` (n_dof, m).

        ``Phi`` is in the unconstrained DOF numbering.  The apparent-mass terms are projected
        once; the circulatory terms are rank one per strip (:class:`SectionParts`), so a call
        costs two real ``(m x ns) (ns x 2m)`` products: ``A^T diag(q) [Bd Bk]`` with
        ``A_j = row_j^T R_j``, ``B_j = col_j^T R_j`` and ``q_j = C(k_j) circ_j width_j``.
        """
        PPhi = self.P @ Phi
        PPhi = PPhi.toarray() if sp.issparse(PPhi) else np.asarray(PPhi)
        ns = self.sections.n_sections
        R = PPhi.reshape(ns, 3, -1)  # (ns, 3, m)
        m = R.shape[2]
        pt = self.parts()
        w = self.width[:, None, None]
        Rf = R.reshape(3 * ns, m).T

        def nc(blk):
            return Rf @ np.matmul(blk * w, R).reshape(3 * ns, m)

        Ma_p, Dnc_p = nc(pt.Ma), nc(pt.Da_nc)
        A = np.einsum("ja,jam->jm", pt.row, R)
        B = np.concatenate([np.einsum("ja,jam->jm", pt.col_d, R), np.einsum("ja,jam->jm", pt.col_k, R)], axis=1)
        return ProjectedAero(Ma=Ma_p.astype(complex), Dnc=Dnc_p, A=A, B=B, qs=pt.circ * self.width,
                             k_of=self.reduced_frequency, c_func=self.circulation)


def _at_times(A: np.ndarray, G: np.ndarray) -> np.ndarray:
    """``A^T G`` for a complex ``G``: two real products when ``A`` is real (half the work)."""
    if np.iscomplexobj(A):
        return A.T @ G
    return A.T @ G.real + 1j * (A.T @ G.imag)


@dataclass
class ProjectedAero:
    """Strip aero projected on a basis (:meth:`StripAero.projected`): ``omega -> (Ma, Da, Ka)``.

    ``Ma``, ``Dnc`` (m, m): the frequency-independent terms; the circulatory ones are
    ``A^T diag(C(k) qs) [Bd Bk]`` with ``A`` (ns, m) and ``B = [Bd Bk]`` (ns, 2m).
    """

    Ma: np.ndarray
    Dnc: np.ndarray
    A: np.ndarray
    B: np.ndarray
    qs: np.ndarray
    k_of: object
    c_func: Callable = theodorsen

    def __call__(self, omega: float):
        m = self.Ma.shape[0]
        cq = self.c_func(self.k_of(omega)) * self.qs
        DK = _at_times(self.A, cq[:, None] * self.B)
        return self.Ma, self.Dnc + DK[:, :m], DK[:, m:]

    def qep_parts(self, omega: float, lam: complex):
        """``lam Da + Ka`` of the aero at ``omega`` and ``x -> Da x``, without forming ``Da``, ``Ka``.

        ``lam Da_c + Ka_c = A^T diag(C qs) (lam Bd + Bk)``: one (m x ns)(ns x m) product against
        the two (m x ns)(ns x 2m) of :meth:`__call__` (the Newton steps of the p-k search).
        """
        m = self.Ma.shape[0]
        cq = self.c_func(self.k_of(omega)) * self.qs
        Bd, Bk = self.B[:, :m], self.B[:, m:]
        LK = _at_times(self.A, cq[:, None] * (lam * Bd + Bk))
        Dnc = self.Dnc

        def apply_Da(x):
            return Dnc @ x + self.A.T @ (cq * (Bd @ x))

        return lam * Dnc + LK, apply_Da


def aero_matrices(sections: AeroSections, op: OperatingPoint, omega: float,
                  options: AeroOptions | None = None):
    """Sparse complex ``(Ma, Da, Ka)`` (n_dof, n_dof) of all strips at frequency ``omega`` (rad/s).

    Convenience wrapper of :class:`StripAero` (build that once when sweeping frequency).
    """
    return StripAero(sections, op, options or AeroOptions()).matrices(omega)
