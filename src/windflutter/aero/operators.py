"""Aerodynamic operators of strips behind one protocol (composition: geometry + section law).

An operator is built for one set of strips (:class:`~windflutter.aero.sections.AeroSections`:
beam strips, shell spline strips or the seed's skin sub-strips, :mod:`windflutter.aero.skin`) at
one :class:`~windflutter.aero.flow.OperatingPoint`.  It is the composition of

* the strip geometry at the operating point: relative flow, inflow axes, steady angle of attack
  (:func:`~windflutter.aero.flow.section_flow`) and the section map ``P`` (3 ns, n_dof) from the
  structural DOFs to ``q = (h, alpha, s)`` (:func:`~windflutter.aero.flow.section_map`);
* a section law: Theodorsen's frequency-domain matrices (the thesis, :class:`StripAero`) or the
  state-space law with mean loads and local slopes (:func:`~windflutter.aero.unsteady.strip_state_space`,
  :class:`StateSpaceAero`);
* optionally the ``parent`` strip of each sub-strip (skin distribution), used to project faster
  and to merge the lag states of sub-strips.

Every operator satisfies :class:`AeroOperator`.  :func:`make_operator` picks the operator from
the options' type: :class:`~windflutter.aero.strip.AeroOptions` -> the thesis model,
:class:`~windflutter.aero.unsteady.UnsteadyOptions` -> the state-space (or quasi-steady) model.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np
import scipy.sparse as sp

from windflutter.aero.flow import OperatingPoint, SectionFlow, section_flow, section_map
from windflutter.aero.linearization import StripLinearization, flat_plate_linearization, polar_linearization
from windflutter.aero.sections import AeroSections
from windflutter.aero.skin import SkinStripAero
from windflutter.aero.statespace import ProjectedStateSpace, StripStateSpace, block_diagonal, project
from windflutter.aero.strip import AeroOptions, StripAero
from windflutter.aero.unsteady import UnsteadyOptions, circulation, strip_state_space
from windflutter.errors import InputError

__all__ = ["AeroOperator", "StateSpaceAero", "make_operator"]


@runtime_checkable
class AeroOperator(Protocol):
    """What every strip operator provides (all arrays over strips; forces times strip widths).

    Attributes
    ----------
    flow : the strips' relative flow and inflow axes.  P : (3 ns, n_dof) sparse section map.
    width : (ns,) strip widths (m).  time_domain : True if :meth:`state_space` exists (a finite
    set of aerodynamic states).  n_states : states per strip (0 for frequency-domain and
    quasi-steady operators).

    Methods
    -------
    section_blocks(omega) : complex ``(Ma, Da, Ka)`` (ns, 3, 3) for harmonic motion at ``omega``
        (rad/s): p-k's form (C(k) at ``k = omega b / U``, or the states eliminated at ``i omega``).
    matrices(omega) : the same assembled on the structural DOFs (sparse, n_dof x n_dof).
    projected(Phi) : on a basis ``Phi`` (n_dof, m): a callable ``omega -> (Ma, Da, Ka)`` (m, m);
        for time-domain operators a :class:`~windflutter.aero.statespace.ProjectedStateSpace`
        (also callable so) with the first-order pieces.
    state_space() : :class:`~windflutter.aero.statespace.StripStateSpace` (time-domain operators;
        the others raise :class:`~windflutter.errors.InputError`).
    """

    flow: SectionFlow
    P: sp.csr_matrix
    width: np.ndarray
    time_domain: bool
    n_states: int

    def section_blocks(self, omega: float): ...

    def matrices(self, omega: float): ...

    def projected(self, Phi): ...

    def state_space(self) -> StripStateSpace: ...


def _parent_map(parent, ns: int):
    if parent is None:
        return None
    par = np.asarray(parent)
    if par.shape != (ns,) or not np.issubdtype(par.dtype, np.integer) or (ns and par.min() < 0):
        raise InputError("parent", par.shape, f"one non-negative parent strip index per sub-strip ({ns},)")
    return par


class StateSpaceAero:
    """State-space strip operator (lag states of a rational C, mean loads, local slopes).

    Parameters
    ----------
    sections : strips.  op : operating point.  options : :class:`UnsteadyOptions`.
    parent : optional (ns,) parent strip of each sub-strip (skin distribution): the projection
        merges the lag states of a parent's sub-strips (:meth:`ProjectedStateSpace.compress`).
    linearization : optional :class:`~windflutter.aero.linearization.StripLinearization` to use
        instead of the polars at the flow's angles of attack (e.g. from a deflected steady state).

    Attributes
    ----------
    flow, P, PT, width, b, a : strip geometry.  linearization : the steady state used.
    law : per-unit-span :class:`StripStateSpace`.  ss : the same times the strip widths.
    """

    time_domain = True

    def __init__(self, sections: AeroSections, op: OperatingPoint, options: UnsteadyOptions | None = None,
                 parent=None, linearization: StripLinearization | None = None):
        self.sections, self.op = sections, op
        self.options = options or UnsteadyOptions()
        self.flow = section_flow(sections, op)
        self.P = section_map(sections, self.flow)
        self.PT = self.P.T.tocsr()
        self.width = np.asarray(sections.width, float)
        self.b = np.asarray(sections.semi_chord, float)
        self.a = np.asarray(sections.elastic_axis, float)
        self.parent = _parent_map(parent, sections.n_sections)
        o = self.options
        if linearization is None:
            if o.polar == "flat_plate":
                linearization = flat_plate_linearization(self.flow.alpha)
            else:
                linearization = polar_linearization(sections, self.flow.alpha, o.slope_step, o.dynamic_stall)
        self.linearization = linearization
        self.circulation = circulation(o.circulation, o.n_lag)
        self.law = strip_state_space(self.b, self.a, self.flow.U, op.air_density, linearization, o, self.circulation)
        self.ss = self.law.scaled(self.width)

    @property
    def n_states(self) -> int:
        return self.ss.n_states

    def state_space(self) -> StripStateSpace:
        """The strips' first-order aerodynamics (forces times strip widths)."""
        return self.ss

    def section_blocks(self, omega: float):
        return self.ss.frequency_blocks(omega)

    def matrices(self, omega: float):
        return tuple((self.PT @ block_diagonal(X) @ self.P).tocsr() for X in self.section_blocks(omega))

    def section_motion(self, Phi) -> np.ndarray:
        """``R = P Phi`` (3 ns, m) dense: the ``(h, alpha, s)`` of every strip for each basis vector."""
        R = self.P @ Phi
        return R.toarray() if sp.issparse(R) else np.asarray(R)

    def projected(self, Phi, rtol: float = 1e-12) -> ProjectedStateSpace:
        """:func:`~windflutter.aero.statespace.project` on ``R = P Phi``; with a parent map the
        sub-strips' states are merged per parent (exact to ``rtol``)."""
        pss = project(self.ss, self.section_motion(Phi))
        return pss if self.parent is None else pss.compress(self.parent, rtol)


def make_operator(sections: AeroSections, op: OperatingPoint, options=None, parent=None) -> AeroOperator:
    """The operator for ``options``: :class:`~windflutter.aero.strip.AeroOptions` (or None) -> the
    thesis's Theodorsen strips (with a parent map: the skin's fast projection), or
    :class:`~windflutter.aero.unsteady.UnsteadyOptions` -> :class:`StateSpaceAero`."""
    if options is None or isinstance(options, AeroOptions):
        if parent is None:
            return StripAero(sections, op, options or AeroOptions())

        return SkinStripAero(sections, op, options or AeroOptions(), parent=np.asarray(parent))
    if isinstance(options, UnsteadyOptions):
        return StateSpaceAero(sections, op, options, parent=parent)
    raise InputError("aero options", type(options).__name__, "AeroOptions (thesis) or UnsteadyOptions (state space)")
