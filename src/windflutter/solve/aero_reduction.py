"""Aerodynamic static-correction vectors for the solver's projected aeroelastic model.

The solver's :class:`~windflutter.solve.aeroelastic.AeroelasticModel` projects the coupled
system on the union of structural modes at reference rotor speeds. Aerodynamic loads are
distributed over the span in shapes those modes represent only partly; divergence (a static
instability) is the most sensitive to the missing residual flexibility. On the NREL 5 MW beam
model (10 m/s, potential flow, p-k) 30 modes per reference speed put the divergence onset 9 %
and the flutter onset 2.9 % above the full-order values (``docs/notes/performance_rounds.md``,
"Full vs reduced on the NREL 5 MW turbine").

:class:`MTAAeroelasticModel` is that model with the basis augmented by modal-truncation-
augmentation vectors (:func:`windflutter.solve.reduction.static_correction_modes`) for the aero
forces the retained modes generate, ``(Ma, Da, Ka)(omega) Phi``, at given reference operating
points. It changes nothing else (same projection, same search), so it is a drop-in for
``AeroelasticModel(...)`` -- the solver's ``TurbineStability.model`` can construct it instead.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError, ValidityWarning
from windflutter.solve.aeroelastic import AeroelasticModel
from windflutter.solve.reduction import static_correction_modes

__all__ = ["MTAAeroelasticModel"]


@dataclass
class MTAAeroelasticModel(AeroelasticModel):
    """:class:`AeroelasticModel` whose modal basis carries aero static-correction vectors.

    Parameters
    ----------
    mta_points
        Reference points ``(wind_speed m/s, rotor_speed rad/s, frequency rad/s)`` whose aero
        matrices generate the load shapes; default (when empty): every ``omega_ref`` rotor speed
        at every ``mta_wind_speeds`` value and frequency 0 (quasi-steady aerodynamics).
    mta_wind_speeds
        Wind speeds (m/s) of the default reference points. For a map, give fixed values (e.g.
        the ends of the wind range), not the point being analysed: the model is cached per
        pitch and shared between wind speeds, so a basis tied to the first analysed point would
        make results depend on the order the points are run in.
    mta_tol
        Relative cut-off of the correction directions (Gram eigenvalue of the unit-mass-norm
        static responses, see :func:`windflutter.structure.modal.m_orthonormalize`): a direction
        is kept when it carries more than ``sqrt(mta_tol)`` of the largest one's amplitude.
        ``1e-8`` (the default) is safe on every turbine checked.  ``1e-4`` keeps 44 of the 114
        directions on the NREL 5 MW whole turbine (basis 99 instead of 169, half the search
        time, onsets within 1.2e-4 of full order) but puts the seed 20 MW whole turbine's
        flutter 2.2 % and divergence 4.6 % low (1e-6: 0.4 % / 0.6 %; 1e-8: 0.02 % / 0.01 %;
        ``docs/notes/performance_rounds.md``, "A cut-off that did not hold").
    """

    mta_points: tuple = ()
    mta_wind_speeds: tuple = (10.0,)
    mta_tol: float = 1e-8

    def _basis(self) -> np.ndarray:
        V = super()._basis()
        points = self.mta_points or tuple((float(v), om, 0.0) for v in np.atleast_1d(self.mta_wind_speeds)
                                          for om in self.omega_ref)
        T = self.structure.T
        TT = T.T.tocsr()
        TV = T @ V
        loads = []
        with warnings.catch_warnings():  # the basis's own points are not analysed: no validity
            warnings.simplefilter("ignore", ValidityWarning)  # warnings about them (issue 34)
            for p in points:
                if len(p) != 3:
                    raise InputError("mta_points", p, "(wind_speed m/s, rotor_speed rad/s, frequency rad/s)")
                strip = self.strip(float(p[0]), float(p[1]))
                for A in strip.matrices(float(p[2])):
                    loads.append(np.asarray(TT @ (A @ TV)))
        # static responses with the stiffness at the lowest reference speed (the structure at
        # rest, omega_ref[0] = 0 by default).  At the largest (40 RPM, several times the rated
        # speed) the initial stress of every resultant (rigid_sections) turns the responses' shape
        # so far that the seed 20 MW's divergence came out 1.0 % high against full order (0.01 %
        # with the axial initial stress alone); with the unstressed structure every case of
        # tests/perf/test_perf_turbine_reduction.py is within its 0.5 %, with a basis of the same size
        om = min(self.omega_ref) if self.omega_ref else 0.0
        K = sp.csc_matrix(self.Kr0 - om**2 * self.Kr1 + om**2 * self.Ks1)
        C = static_correction_modes(K, self.Mr, V, np.hstack(loads), tol=self.mta_tol)
        self.n_correction = C.shape[1]
        return np.hstack([V, C])
