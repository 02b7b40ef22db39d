"""State-space unsteady strip aerodynamics with mean-load terms and local polar slopes.

Per strip (semi-chord ``b``, chord ``c = 2 b``, elastic axis ``a b`` aft of mid-chord, relative
speed ``U``, steady angle of attack ``alpha0``, ``q0 = rho U^2 / 2``) the section moves with
``q = (h, alpha, s)`` (:mod:`windflutter.aero.flow`).  The model linearized here is the
quasi-steady strip force (docs/aero_operators.md, "The strip model and its linearization",
derives every term)::

    W  = U e3 - v34              relative wind at the 3/4-chord point (velocity v34 there)
    L  = 1/2 rho c |W|^2 Cl(alpha_E)  normal to W (or to the effective inflow, see below)
    D  = 1/2 rho c |W|^2 Cd(alpha_E)  along W
    M  = 1/2 rho c^2 |W|^2 Cm(alpha_E) + moment of L and D acting at the quarter chord

with the chord at its true angle ``alpha0 + alpha`` to the wind (3/4-chord point at
``d34 = b (1/2 - a)`` aft of the elastic axis, quarter chord ``d14 = b (a + 1/2)`` ahead).
Linearized about the steady state (first order in ``alpha, h', alpha', s'``)::

    theta' = (-h' + d34 cos(alpha0) alpha') / U          turn of the wind at 3/4 chord (rad)
    alpha34 = alpha + theta'                               3/4-chord angle of attack change
    dp = rho U (-s' + d34 sin(alpha0) alpha')              dynamic-pressure change (Pa)
    alpha_E = C(s) alpha34                                 effective (circulatory) angle

and the forces ``(L, M, D)`` per unit span::

    q0 F(dCl, dCd, dCm) alpha_E          circulatory, LOCAL slopes (2 pi, 0, 0 for the flat plate)
  + F(Cl0, Cd0, Cm0) dp                  dynamic pressure of the mean loads
  + q0 F(Cd0, 0, 0) theta'               the drag turns with the wind
  + q0 F(0, -Cl0, 0) theta_L             the lift turns with its inflow
  + (0, d14 q0 c (Cd0 cos a0 - Cl0 sin a0), 0) alpha   the quarter chord moves when pitching
  + apparent mass (Theodorsen's non-circulatory terms, scaled)

where ``F(l, d, m) = c (l, d14 (cos(alpha0) l + sin(alpha0) d) + c m, d)`` (lift and drag at the
quarter chord, its moment about the elastic axis, the polar moment) and ``theta_L`` is the
lift's turn: ``theta'`` (``lift_direction="instantaneous"``: normal to the instantaneous wind) or
``alpha_E - alpha`` (``"effective"``, the default: normal to the effective inflow of the lag
states, as in the Beddoes-Leishman-type model of Hansen, Gaunaa & Madsen 2004 used by HAWC2 /
HAWCStab2).  Both are the same in the quasi-steady limit.

``C(s)`` is realised per strip by lag states (``s`` the Laplace variable, ``sbar = s b / U``)::

    C(sbar) = A0 + sum_j c_j sbar / (sbar + beta_j)   ->   z_j' = (beta_j U / b) (alpha34 - z_j),
    alpha_E = (A0 + sum_j c_j) alpha34 - sum_j c_j z_j

(R.T. Jones' two poles by default, the project's Roger fit ``theodorsen_rfa(n)`` as option; no
states and ``C = 1`` for the quasi-steady operator).  With ``dynamic_stall`` one more state, the
separation point ``f`` of Oye's model: ``f' = (f_st'(alpha0) alpha_E - f) / tau``, ``tau =
T_f b / U`` (``T_f = 6`` by default: Hansen et al. 2004; OpenFAST AeroDyn UA documentation, Oye
model: "usually chosen around 6" in units of ``c / 2U``), the lift ``q0 c dCl/df f`` acting at the
quarter chord and the circulatory lift slope reduced by ``dCl/df f_st'`` so that the
quasi-steady limit keeps the local slope of the polar (:mod:`windflutter.aero.linearization`).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from windflutter.aero.linearization import SLOPE_STEP, StripLinearization
from windflutter.aero.statespace import StripStateSpace
from windflutter.aero.strip import apparent_mass
from windflutter.aero.theodorsen import RogerRFA, jones_rfa, theodorsen_rfa
from windflutter.errors import InputError

__all__ = ["Circulation", "UnsteadyOptions", "circulation", "strip_state_space"]


@dataclass(frozen=True)
class Circulation:
    """A rational ``C(sbar) = A0 + sum_j gains_j sbar / (sbar + poles_j)`` (``sbar = s b / U``).

    poles : (n,) ``beta_j > 0`` (reduced).  gains : (n,) ``c_j``.  A0 : static value (1).
    """

    poles: np.ndarray
    gains: np.ndarray
    A0: float = 1.0

    @property
    def n_lag(self) -> int:
        return int(np.size(self.poles))

    @property
    def c_inf(self) -> float:
        """``C`` at infinite frequency, ``A0 + sum c_j`` (the instantaneous part)."""
        return float(self.A0 + np.sum(self.gains))

    def __call__(self, k):
        """``C(i k)`` (complex, vectorized): the p-k form of this approximation."""
        s = 1j * np.asarray(k, float)
        out = np.full(s.shape, self.A0, dtype=complex)
        for beta, c in zip(self.poles, self.gains):
            out = out + c * s / (s + beta)
        return out

    @staticmethod
    def from_rfa(rfa: RogerRFA) -> "Circulation":
        """From a scalar Roger fit of C(k) without polynomial terms."""
        if np.ndim(rfa.A0) != 0 or abs(float(rfa.A1)) > 0 or abs(float(rfa.A2)) > 0:
            raise InputError("circulation", "RogerRFA", "a scalar Roger fit of C(k) without s, s^2 terms")
        poles = np.asarray(rfa.poles, float)
        if np.any(~np.isfinite(poles)) or np.any(poles <= 0):
            raise InputError("circulation.poles", poles, "positive lag poles")
        return Circulation(poles, np.asarray(rfa.lags, float).reshape(-1), float(rfa.A0))


def circulation(kind="jones", n_lag: int = 4) -> Circulation:
    """The lag realisation: ``"jones"`` (R.T. Jones, NACA Rep. 681: 2 poles), ``"rfa"`` (the
    project's Roger fit with ``n_lag`` optimised poles, :func:`theodorsen_rfa`),
    ``"quasi_steady"`` (C = 1, no states), a :class:`~windflutter.aero.theodorsen.RogerRFA` or a
    :class:`Circulation`."""
    if isinstance(kind, Circulation):
        return kind
    if isinstance(kind, RogerRFA):
        return Circulation.from_rfa(kind)
    if kind == "jones":
        return Circulation.from_rfa(jones_rfa())
    if kind == "quasi_steady":
        return Circulation(np.zeros(0), np.zeros(0), 1.0)
    if kind == "rfa":
        if isinstance(n_lag, bool) or not isinstance(n_lag, (int, np.integer)) or n_lag < 1:
            raise InputError("n_lag", n_lag, "an integer >= 1 (lag poles of the Roger fit)")
        return _roger(int(n_lag))
    raise InputError("circulation", kind, "'jones', 'rfa', 'quasi_steady' or a RogerRFA")


@functools.lru_cache(maxsize=8)
def _roger(n_lag: int) -> Circulation:
    """The Roger fit of C(k) with ``n_lag`` optimised poles, fitted once per process."""
    return Circulation.from_rfa(theodorsen_rfa(n_lag))


#: ``T_f`` of Oye's separation lag (semi-chords travelled): method p's and the time domain's default
SEPARATION_TIME = 6.0


@dataclass(frozen=True)
class UnsteadyOptions:
    """Choices of the state-space / quasi-steady strip operator (module docstring).

    Parameters
    ----------
    circulation : ``"jones"`` (default), ``"rfa"``, ``"quasi_steady"`` or a RogerRFA.
    n_lag : poles of the ``"rfa"`` fit.
    polar : ``"table"`` (the strips' polars, local slopes) or ``"flat_plate"`` (Cl = 2 pi alpha,
        Cd = Cm = 0: the potential-flow variant, no polars needed).
    mean_loads : the mean-load terms (Cl0, Cd0, Cm0: dynamic pressure, turning of lift and drag,
        quarter-chord arm); on by default.
    lift_direction : ``"effective"`` (default) or ``"instantaneous"``.
    apparent_mass : factor on Theodorsen's non-circulatory terms (1 = flat plate, 0 = none).
    dynamic_stall : the separation-point lag of Oye's model (one more state per strip).
    separation_time : ``T_f`` of the separation lag, in units of ``b / U`` (6).
    slope_step : half-width (rad) of the centred differences of the polar (1 deg).
    """

    circulation: object = "jones"
    n_lag: int = 4
    polar: str = "table"
    mean_loads: bool = True
    lift_direction: str = "effective"
    apparent_mass: float = 1.0
    dynamic_stall: bool = False
    separation_time: float = SEPARATION_TIME
    slope_step: float = SLOPE_STEP

    def __post_init__(self):
        for name, choices in (("polar", ("table", "flat_plate")), ("lift_direction", ("effective", "instantaneous"))):
            if getattr(self, name) not in choices:
                raise InputError(f"aero.{name}", getattr(self, name), f"one of {choices}")
        for name in ("mean_loads", "dynamic_stall"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                raise InputError(f"aero.{name}", getattr(self, name), "true or false")
        for name, lo in (("apparent_mass", 0.0), ("separation_time", 1e-12), ("slope_step", 1e-12)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v < lo:
                raise InputError(f"aero.{name}", v, "a non-negative number" if lo == 0 else "a positive number")
        if self.dynamic_stall and self.polar != "table":
            raise InputError("aero.dynamic_stall", True, "polar tables (polar='table') for the separation point")
        circulation(self.circulation, self.n_lag)  # validates


def _force_vectors(c, d14, ca, sa, l, d, m):
    """``F(l, d, m) = c (l, d14 (cos a0 l + sin a0 d) + c m, d)`` (ns, 3): lift and drag at the
    quarter chord and the polar moment, as (lift, moment about the elastic axis, drag)."""
    return c[:, None] * np.stack([l, d14 * (ca * l + sa * d) + c * m, d], axis=1)


def _outer(g, r):
    return g[:, :, None] * r[:, None, :]


def strip_state_space(b, a, U, rho: float, lin: StripLinearization, options: UnsteadyOptions | None = None,
                      circ: Circulation | None = None) -> StripStateSpace:
    """Per-unit-span state-space aerodynamics of strips (module docstring), vectorized.

    Parameters
    ----------
    b, a, U : (ns,) semi-chord (m), elastic axis aft of mid-chord (semi-chords), speed (m/s).
    rho : air density (kg/m^3).
    lin : steady linearization at each strip's angle of attack
        (:func:`~windflutter.aero.linearization.polar_linearization` or ``flat_plate_linearization``).
    options : :class:`UnsteadyOptions`.  circ : the lag realisation (default from ``options``).

    Returns
    -------
    :class:`~windflutter.aero.statespace.StripStateSpace` per unit span (``nz = n_lag`` states,
    ``+ 1`` with dynamic stall).
    """
    o = options or UnsteadyOptions()
    cf = circ if circ is not None else circulation(o.circulation, o.n_lag)
    b, a, U = (np.asarray(x, float) for x in (b, a, U))
    ns = b.shape[0]
    if lin.n_sections != ns:
        raise InputError("linearization", lin.n_sections, f"one steady state per strip ({ns})")
    c, q0 = 2.0 * b, 0.5 * rho * U**2
    d14, d34 = b * (a + 0.5), b * (0.5 - a)
    ca, sa = np.cos(lin.alpha), np.sin(lin.alpha)
    zero, one = np.zeros(ns), np.ones(ns)
    e_a = np.stack([zero, one, zero], axis=1)                        # alpha of q
    v_th = np.stack([-1.0 / U, d34 * ca / U, zero], axis=1)          # theta' per q'
    v_p = rho * U[:, None] * np.stack([zero, d34 * sa, -one], axis=1)  # dp per q'
    sep = lin.separation if o.dynamic_stall else None
    if o.dynamic_stall and sep is None:
        raise InputError("linearization.separation", None, "the separation state (polar_linearization(..., separation=True))")
    dcl_att = lin.dcl - (sep.dcl_df * sep.df if sep is not None else 0.0)
    G = q0[:, None] * _force_vectors(c, d14, ca, sa, dcl_att, lin.dcd, lin.dcm)  # per alpha_E
    Ma, Da = apparent_mass(b, a, U, rho, o.apparent_mass)
    Ka = np.zeros((ns, 3, 3))
    if o.mean_loads:
        Da += _outer(_force_vectors(c, d14, ca, sa, lin.cl, lin.cd, lin.cm), v_p)
        Da += _outer(q0[:, None] * _force_vectors(c, d14, ca, sa, lin.cd, zero, zero), v_th)
        GL = q0[:, None] * _force_vectors(c, d14, ca, sa, zero, -lin.cl, zero)
        if o.lift_direction == "instantaneous":
            Da += _outer(GL, v_th)
        else:  # theta_L = alpha_E - alpha
            G = G + GL
            Ka -= _outer(GL, e_a)
        Ka[:, 1, 1] += d14 * q0 * c * (lin.cd * ca - lin.cl * sa)
    ci = cf.c_inf
    Ka += ci * _outer(G, e_a)
    Da += ci * _outer(G, v_th)
    nl = cf.n_lag
    nz = nl + (1 if sep is not None else 0)
    Cz = np.zeros((ns, 3, nz))
    Az = np.zeros((ns, nz, nz))
    Bq = np.zeros((ns, nz, 3))
    Bv = np.zeros((ns, nz, 3))
    for j, (beta, cj) in enumerate(zip(cf.poles, cf.gains)):  # loop over the (2..6) poles only
        lam = beta * U / b
        Cz[:, :, j] = -cj * G
        Az[:, j, j] = -lam
        Bq[:, j] = lam[:, None] * e_a
        Bv[:, j] = lam[:, None] * v_th
    if sep is not None:
        rate = U / (o.separation_time * b)
        g = sep.df * rate  # f' = rate (f_st' alpha_E - f)
        Az[:, nl, :nl] = -g[:, None] * cf.gains[None, :]
        Az[:, nl, nl] = -rate
        Bq[:, nl] = (ci * g)[:, None] * e_a
        Bv[:, nl] = (ci * g)[:, None] * v_th
        Cz[:, :, nl] = q0[:, None] * _force_vectors(c, d14, ca, sa, sep.dcl_df, zero, zero)
    return StripStateSpace(Ma, Da, Ka, Cz, Az, Bq, Bv)
