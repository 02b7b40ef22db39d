"""Whole-turbine completion and consistency checks, common to every reader.

:func:`finish_turbine` is the last step of each reader: it fills the stated defaults (nacelle CG
at the tower top, zero inertias), records what the files do not give (``Turbine.missing``), and
checks what only the assembled turbine can show: the blade length against the rotor diameter,
the rotor apex against the hub height, precone and tilt, the lumped masses and inertias against
the rotor size, and the blade's stiffness and mass scale (a Rayleigh estimate of its first flap
and edge frequencies from the 6x6 tables at the file's stations).  Impossible -> ``InputError``;
unusual -> ``InputWarning`` kept in ``Turbine.warnings``.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.integrate import trapezoid

from windflutter.errors import InputError
from windflutter.model.plausibility import Notes
from windflutter.model.turbine import Turbine


#: lumped mass per rotor diameter cubed (kg/m^3) assumed when the files give none: the geometric
#: mean over the bundled reference turbines (NREL 5 MW, IEA 10, 15 and 22 MW: hub 0.0285, 0.0105,
#: 0.0049, 0.0053; nacelle 0.120, 0.0705, 0.0459, 0.0359), each of which lies within a factor 3.1
#: (hub) and 2 (nacelle) of it (``tests/model/test_own_files.py`` keeps these numbers true)
DEFAULT_MASS_PER_D3 = {"hub": 0.0094, "nacelle": 0.061}
#: where a file gives the mass, for the warning
_MASS_KEYS = {"hub": "components.hub.elastic_properties.mass (windIO) or a supplement's hub.mass",
              "nacelle": "components.drivetrain.elastic_properties.mass (windIO) or a supplement's nacelle.mass"}


def default_mass(turbine: Turbine, name: str, notes: Notes) -> float:
    """The assumed lumped mass (kg) of ``name`` (``"hub"`` or ``"nacelle"``) from the rotor diameter
    (:data:`DEFAULT_MASS_PER_D3`), with one warning naming the assumption; NaN without a diameter."""
    D = turbine.rotor_diameter
    if not (np.isfinite(D) and D > 0):
        return float("nan")
    c = DEFAULT_MASS_PER_D3[name]
    m = c * D**3
    notes.warn(f"{name}.mass", f"not in the files: {m:.4g} kg assumed, {c} kg/m^3 x rotor_diameter^3 (the geometric "
               f"mean of the reference turbines; theirs lie within a factor {3.1 if name == 'hub' else 2} of it); "
               f"give {_MASS_KEYS[name]} for the turbine's own")
    return float(m)


def structural_damping(t: Turbine, notes: Notes) -> None:
    """One warning when the files give the blade no structural damping (or all of it zero): a
    ``damping.model: file`` analysis then has an undamped blade, and an edgewise mode with little
    aerodynamic damping may come out unstable where the real blade's damping would not."""
    d = t.blade.damping
    ratios = [] if d is None else [*np.ravel(d.flap_ratio), *np.ravel(d.edge_ratio)]
    if d is not None and ((d.mu is not None and np.any(np.asarray(d.mu) > 0)) or np.any(np.asarray(ratios) > 0)):
        return
    where = f" ({d.source})" if d is not None and d.source else ""
    notes.warn("blade structural damping", f"zero{where}: with damping.model file the blade is undamped and its "
               "edgewise modes may be reported unstable; give the blade's damping (windIO structural_damping.mu, a "
               "supplement) or set damping.model / damping.ratio")


def finish_turbine(turbine: Turbine, files: tuple[str, ...] = ()) -> Turbine:
    """Defaults, missing data, consistency checks; returns the completed turbine."""
    notes_out = list(turbine.notes)
    hub, nac = turbine.hub, turbine.nacelle
    missing = [m for m in turbine.missing]
    notes = Notes(turbine.source)
    notes.items = list(turbine.warnings)
    if not np.isfinite(hub.mass):
        hub = dataclasses.replace(hub, mass=default_mass(turbine, "hub", notes))
    if not np.isfinite(nac.mass):
        nac = dataclasses.replace(nac, mass=default_mass(turbine, "nacelle", notes))
    for name, val in (("hub.mass", hub.mass), ("nacelle.mass", nac.mass)):
        if not np.isfinite(val) and name not in missing:
            missing.append(name)
    if not np.all(np.isfinite(nac.cg)):
        nac = dataclasses.replace(nac, cg=np.zeros(3))
        notes_out.append("nacelle CG not given: placed at the tower top")
    if not np.all(np.isfinite(nac.inertia)):
        nac = dataclasses.replace(nac, inertia=np.zeros((3, 3)))
        notes_out.append("nacelle inertia not given: zero (point mass)")
    if not np.all(np.isfinite(hub.inertia)):
        hub = dataclasses.replace(hub, inertia=np.zeros((3, 3)))
        notes_out.append("hub inertia not given: zero (point mass)")
    if any(not a.polars for a in turbine.airfoils.values()) and "airfoil polars" not in missing:
        missing.append("airfoil polars")
    if missing:
        notes_out.append("not in the files: " + ", ".join(missing))
    t = dataclasses.replace(turbine, hub=hub, nacelle=nac, notes=tuple(notes_out), missing=tuple(missing),
                            input_files=tuple(dict.fromkeys(turbine.input_files + tuple(files))))
    rigid_body_inertias(t, t.source)
    structural_damping(t, notes)
    rotor_geometry(t, notes)
    lumped_masses(t, notes)
    blade_scale(t, notes)
    return dataclasses.replace(t, warnings=tuple(notes.items))


def rigid_body_inertias(turbine: Turbine, source: str | None) -> None:
    """Hub and nacelle inertia tensors must be finite, symmetric positive semi-definite.

    A tensor that is not (e.g. a yaw inertia written into the Iyz slot of the 6-vector) would
    make the whole-turbine mass matrix indefinite; refuse it here, naming the field.
    """
    for name, body in (("hub", turbine.hub), ("nacelle", turbine.nacelle)):
        J = np.asarray(body.inertia, dtype=float)
        if J.shape != (3, 3) or not np.all(np.isfinite(J)):
            raise InputError(f"{name}.inertia", J.tolist(), "a finite 3x3 inertia tensor (kg m^2)", source)
        ev = np.linalg.eigvalsh(0.5 * (J + J.T))
        if ev.min() < -1e-9 * max(abs(ev).max(), 1.0):
            raise InputError(
                f"{name}.inertia", J.tolist(),
                "a positive semi-definite inertia tensor (Ixx, Iyy, Izz, Ixy, Ixz, Iyz order; "
                "products of inertia must not exceed the moments)", source,
            )


def _bands(notes: Notes, field: str, value: float, ok: tuple[float, float], possible: tuple[float, float],
           what: str) -> None:
    """Error outside ``possible``, warning outside ``ok`` (both closed intervals)."""
    if not (possible[0] <= value <= possible[1]):
        notes.error(field, value, f"{what} between {possible[0]:.3g} and {possible[1]:.3g}")
    if not (ok[0] <= value <= ok[1]):
        notes.warn(field, f"{value:.4g}: {what} outside the usual {ok[0]:.3g}..{ok[1]:.3g}")


def rotor_geometry(t: Turbine, notes: Notes) -> None:
    """Blade length vs rotor diameter, rotor apex vs hub height, cone and tilt angles.

    The rotor radius from the parts (hub radius + blade span, projected with the precone) must
    be within 25 % of half the rotor diameter (5 % usual); the apex height within 25 % of the hub
    height (5 % usual).  |precone| and |tilt| above 45 deg are impossible, above 15 deg unusual.
    """
    for field, ang in (("hub.precone", t.hub.precone), ("nacelle.shaft_tilt", t.nacelle.shaft_tilt)):
        _bands(notes, field + " (deg)", float(np.degrees(ang)), (-15.0, 15.0), (-45.0, 45.0), "an angle (deg)")
    span = float(t.blade.ref_axis[-1, 2] - t.blade.ref_axis[0, 2])
    radius = t.hub.radius + span * np.cos(t.hub.precone)
    if np.isfinite(t.rotor_diameter) and t.rotor_diameter > 0:
        ratio = radius / (0.5 * t.rotor_diameter)
        _bands(notes, "blade length + hub radius vs rotor_diameter / 2", float(ratio), (0.95, 1.05), (0.75, 1.25),
               f"a ratio (blade span {span:.4g} m, hub radius {t.hub.radius:.4g} m, rotor diameter "
               f"{t.rotor_diameter:.4g} m)")
    apex = float(t.rotor_apex[2])
    if np.isfinite(t.hub_height) and t.hub_height > 0:
        _bands(notes, "rotor apex height vs hub_height", apex / t.hub_height, (0.95, 1.05), (0.75, 1.25),
               f"a ratio (tower top {t.tower.top_z:.4g} m + shaft offsets give {apex:.4g} m, hub_height "
               f"{t.hub_height:.4g} m)")


def lumped_masses(t: Turbine, notes: Notes) -> None:
    """Hub and nacelle masses against the rotor size: mass / D^3 within 1e-5..10 kg/m^3 possible
    (reference turbines: hub 0.005-0.03, nacelle 0.035-0.12); the radius of gyration of each
    inertia below the rotor diameter (usual: below a quarter of it)."""
    D = t.rotor_diameter if np.isfinite(t.rotor_diameter) and t.rotor_diameter > 0 else 2 * t.tip_radius
    for name, body, ok in (("hub", t.hub, (5e-4, 0.2)), ("nacelle", t.nacelle, (2e-3, 1.0))):
        if not np.isfinite(body.mass):
            continue
        _bands(notes, f"{name}.mass / rotor_diameter^3 (kg/m^3)", body.mass / D**3, ok, (1e-5, 10.0),
               f"a mass scale ({name} mass {body.mass:.4g} kg, rotor diameter {D:.4g} m)")
        if body.mass > 0:
            rg = float(np.sqrt(np.max(np.linalg.eigvalsh(np.asarray(body.inertia, dtype=float))) / body.mass))
            _bands(notes, f"{name}.inertia radius of gyration / rotor_diameter", rg / D, (0.0, 0.25), (0.0, 1.0),
                   "a ratio")


def blade_scale(t: Turbine, notes: Notes) -> None:
    """The blade's 6x6 at its own stations against its geometry.

    * Mass per length / chord^2 (kg/m^3): 0.01..1e4 possible, 1..500 usual (NREL 5 MW: 5 at the
      tip to 60 at the root).
    * First flap and edge frequencies of the clamped blade, Rayleigh quotient with the shape
      (x/L)^2 (an upper bound, ~27 % high for a uniform beam): 0.01..100 Hz possible, 0.1..10 Hz
      usual (reference turbines 0.3-1.2 Hz).
    """
    bp = t.blade.beam
    if bp is None or not np.isfinite(bp.length) or bp.length <= 0:
        return
    where = f"blade 6x6 ({bp.source})"
    x = bp.s * bp.length
    m = bp.mass[:, 0, 0]
    chord = np.interp(bp.s, t.blade.s, t.blade.chord)
    ratio = m / chord**2
    i_lo, i_hi = int(np.argmin(ratio)), int(np.argmax(ratio))
    for i in (i_lo, i_hi):
        _bands(notes, f"{where} mass / chord^2 at station {i} (span {bp.s[i]:.4f})", float(ratio[i]), (1.0, 500.0),
               (0.01, 1e4), "a mass scale (kg/m^3)")
    L = bp.length
    kinetic = trapezoid(m * (x / L) ** 4, x)
    for name, EI in (("flapwise", bp.stiffness[:, 5, 5]), ("edgewise", bp.stiffness[:, 4, 4])):
        strain = trapezoid(EI * (2.0 / L**2) ** 2, x)
        f = float(np.sqrt(max(strain, 0.0) / kinetic) / (2 * np.pi)) if kinetic > 0 else np.nan
        _bands(notes, f"{where} first {name} frequency estimate (Hz)", f, (0.1, 10.0), (0.01, 100.0),
               "a frequency (Hz)")
