"""The sensitivity of an instability's onset rotor speed (implicit function theorem).

At the onset ``Omega*`` of a mode at a wind speed and pitch, its eigenvalue's real part is zero:
``sigma(Omega*, p) = 0``.  Then

    ``dOmega*/dp = -(d sigma/dp) / (d sigma/dOmega)``

with ``d sigma/dp`` the mode's design sensitivity at the onset (:func:`~windflutter.sensitivity.
point.point_sensitivities`, steady state held fixed) and ``d sigma/dOmega`` a central difference of
two points at ``Omega* +- dOmega`` (their steady states recomputed).  :func:`onset` finds the onset
of a named mode by the secant method on ``sigma``, for the nominal model or a changed one (the
reference of the derivative, tests/sensitivity/test_sensitivity_onset.py).
"""

from __future__ import annotations

from dataclasses import dataclass

from windflutter.errors import InputError
from windflutter.sensitivity.parameters import (BLADE_PROPERTIES, GLOBAL_PARAMETERS, change_words, is_relative,
                                                unit_change)
from windflutter.sensitivity.point import changed_strips_point, point_sensitivities
from windflutter.sensitivity.steady import point_totals
from windflutter.system.modes import point_modes
from windflutter.sensitivity.finite_difference import changed_blade, changed_model
from windflutter.system.blade import RotorBlade
from windflutter.system.damping import blade_mu
from windflutter.system.deflected import deflected_blade


def _named(modes, name: str):
    for m in modes:
        if m.identity_name == name:
            return m
    return None


def mode_sigma(point_of, rpm: float, name: str, max_hz: float, previous=None) -> tuple[float, list]:
    """(Re lambda (1/s) of the mode ``name``, the point's named modes) at ``rpm`` (RPM), the point
    system given by ``point_of(rpm)``."""
    modes = point_modes(point_of(rpm), max_hz, previous=previous)
    m = _named(modes, name)
    if m is None:
        raise InputError("mode", name, f"a mode of the point at {rpm:g} RPM below {max_hz:g} Hz")
    return float(m.eigenvalue.real), modes


def onset(point_of, name: str, rpm_a: float, rpm_b: float, max_hz: float, tol: float = 1e-5,
          max_iter: int = 20) -> float:
    """The rotor speed (RPM) where the mode ``name`` of ``point_of(rpm)`` crosses ``Re lambda = 0``,
    by the secant method from ``rpm_a``, ``rpm_b`` (near the onset, the mode damped at one of them
    and not at the other, or both close)."""
    fa, prev = mode_sigma(point_of, rpm_a, name, max_hz)
    fb, prev = mode_sigma(point_of, rpm_b, name, max_hz, prev)
    a, b = float(rpm_a), float(rpm_b)
    for _ in range(max_iter):
        if fb == fa:
            break
        c = b - fb * (b - a) / (fb - fa)
        a, fa = b, fb
        b = c
        fb, prev = mode_sigma(point_of, b, name, max_hz, prev)
        if abs(b - a) < tol:
            return b
    raise InputError("onset", name, f"a mode crossing Re lambda = 0 near {rpm_a:g}-{rpm_b:g} RPM (no convergence)")


@dataclass
class OnsetSensitivity:
    """``rpm`` the onset (RPM); ``dsigma_drpm`` (1/s per RPM); ``drpm[name]`` (RPM per unit of the
    parameter: the blade properties summed over the whole blade, and the global parameters)."""

    name: str
    wind_speed: float
    rpm: float
    dsigma_drpm: float
    drpm: dict
    #: ``d sigma/dp`` with the steady state's own change (else held at the onset)
    total: bool = False


def onset_sensitivity(om, wind_speed: float, name: str, rpm: float, pitch: float, max_hz: float,
                      d_rpm: float = 0.05, blade_properties=None, global_parameters=None,
                      total: bool = False) -> OnsetSensitivity:
    """:class:`OnsetSensitivity` of the mode ``name`` of the operating-point model ``om`` whose
    onset at ``wind_speed`` (m/s) and ``pitch`` (rad) is ``rpm`` (RPM); ``total``: ``d sigma/dp``
    with the steady state's own change (:func:`~windflutter.sensitivity.steady.point_totals`; the
    blade properties over the whole blade), else with the steady state at the onset held."""
    point_of = lambda r: om.at(wind_speed, rpm=r, pitch=pitch)  # noqa: E731
    s_plus, prev = mode_sigma(point_of, rpm + d_rpm, name, max_hz)
    s_minus, _ = mode_sigma(point_of, rpm - d_rpm, name, max_hz, prev)
    ds = (s_plus - s_minus) / (2 * d_rpm)
    ps = point_of(rpm)
    m = _named(point_modes(ps, max_hz, previous=prev), name)
    res = point_sensitivities(om, ps, [m], blade_properties, global_parameters)
    out = {k: -float(v[0].sum().real) / ds for k, v in res.blade.items()}
    out.update({k: -float(v[0].real) / ds for k, v in res.globals_.items()})
    if total:
        out = {k: -float(v[0].real) / ds for k, v in point_totals(om, ps, res).items()}
    return OnsetSensitivity(name=name, wind_speed=float(wind_speed), rpm=float(rpm), dsigma_drpm=ds, drpm=out,
                            total=bool(total))


def recomputed_point_of(om, wind_speed: float, pitch: float, name: str, p: float):
    """``point_of(rpm)`` of the turbine with the parameter ``name`` changed by ``p`` (a blade property
    over the whole blade, or a global parameter): its steady state recomputed at each rotor speed,
    the blade linearized about it on the nominal point's blade basis (the reference of the total
    onset derivative)."""
    g = GLOBAL_PARAMETERS.get(name)
    mod = om if g is not None and g.part == "strips" else changed_model(om, name, p)
    mu = blade_mu(mod.turbine) if mod.options.damping == "file" else None

    def point_of(rpm):
        ps0 = om.at(wind_speed, rpm=rpm, pitch=pitch)
        rb = mod.blade(pitch)
        if g is not None and g.part == "strips":
            rb = RotorBlade(rb.fe, rb.struct, g.strips(rb.sections, p), rb.apex, rb.axis, damping=rb.damping)
        d = deflected_blade(rb, mod.steady(rb, wind_speed, ps0.omega), ps0.omega, mu)
        return mod.assemble_point(d.blade, d.steady, d.ksigma, d.klink, wind_speed, ps0.omega, pitch,
                                  tip_frame=ps0.tip_frame, Phi=ps0.Phi)
    return point_of


def changed_point_of(om, wind_speed: float, pitch: float, name: str, p: float):
    """``point_of(rpm)`` of the model with the parameter ``name`` changed by ``p`` (a blade property
    over the whole blade, or a global parameter), the steady state at each rotor speed the nominal
    model's (as the sensitivities hold it)."""

    if name in BLADE_PROPERTIES:
        def point_of(rpm):
            ps = om.at(wind_speed, rpm=rpm, pitch=pitch)
            return om.assemble_point(changed_blade(om, ps, name, p), ps.steady, ps.ksigma, ps.klink, ps.wind_speed,
                                     ps.omega, ps.pitch, tip_frame=ps.tip_frame)
        return point_of
    g = GLOBAL_PARAMETERS[name]
    if g.part == "strips":
        return lambda rpm: changed_strips_point(om, om.at(wind_speed, rpm=rpm, pitch=pitch), g.strips, p, Phi=None)
    mod = om.variant(*g.change(om.turbine, om.options, p))
    if g.part == "aero":
        import dataclasses

        def point_of(rpm):
            ps = om.at(wind_speed, rpm=rpm, pitch=pitch)
            st = dataclasses.replace(ps.steady, air_density=mod.options.air_density)
            return mod.assemble_point(ps.blade, st, ps.ksigma, ps.klink, ps.wind_speed, ps.omega, ps.pitch,
                                      tip_frame=ps.tip_frame)
        return point_of
    return lambda rpm: mod.at(wind_speed, rpm=rpm, pitch=pitch)


def most_influential(sens: OnsetSensitivity, n: int = 2) -> list[str]:
    """The ``n`` parameters whose unit change moves the onset most."""
    return sorted(sens.drpm, key=lambda k: -abs(sens.drpm[k] * unit_change(k)))[:n]



def onset_lines(sens: OnsetSensitivity) -> list[str]:
    """The header and the ranked sentences of an onset's sensitivity (``windflutter sensitivity --onset``):
    ``"+1 % torsion stiffness (whole blade) raises the onset by 0.0522 RPM"``, largest shift first."""
    out = [f"onset of the {sens.name} at {sens.wind_speed:g} m/s: {sens.rpm:.4f} RPM (the operating curve's pitch "
           f"held, rotor speed raised); d Re(lambda)/d rpm = {sens.dsigma_drpm:.4g} 1/s per RPM; steady state "
           f"{'included' if sens.total else 'held fixed'}; largest onset shifts first"]
    for name in most_influential(sens, len(sens.drpm)):
        x = sens.drpm[name] * unit_change(name)
        where = " (whole blade)" if name in BLADE_PROPERTIES else ""
        out.append(f"  {change_words(name)}{where} {'raises' if x >= 0 else 'lowers'} the onset by {abs(x):.3g} RPM")
    return out


def onset_dataset(sens: OnsetSensitivity):
    """The :class:`xarray.Dataset` of an onset's sensitivity: ``drpm`` (RPM per unit of each parameter)
    and ``drpm_unit_change`` (RPM for +1 % or +1 cm) on ``parameter``; the onset in the attributes."""
    import xarray as xr

    names = list(sens.drpm)
    per = "per unit of the parameter (relative ones: per +100 %; offsets: per m)"
    return xr.Dataset(
        {"drpm": ("parameter", [sens.drpm[n] for n in names], {
            "units": "rpm", "long_name": "d onset rotor speed / d parameter (blade properties over the whole blade) "
                                         + per}),
         "drpm_unit_change": ("parameter", [sens.drpm[n] * unit_change(n) for n in names], {
             "units": "rpm", "long_name": "onset shift for +1 % of a relative parameter, +1 cm of an offset"})},
        coords={"parameter": names, "parameter_unit": ("parameter", ["1" if is_relative(n) else "m" for n in names])},
        attrs={"mode": sens.name, "wind_speed_m_s": sens.wind_speed, "onset_rpm": sens.rpm,
               "dsigma_drpm_per_s_per_rpm": sens.dsigma_drpm,
               "held_fixed": ("the blade basis" if sens.total else
                              "the steady state at the onset (deflected shape, stress, inflow) and the blade basis")})
