"""Method p's modes at an operating point, the reference the time-domain tests compare with."""

from __future__ import annotations

import warnings


def method_p_in_wind(turbine, wind, n_span):
    """Method p's modes (whole turbine, no structural damping) at the operating point:
    ``({name: eigenvalue}, rotor speed (RPM), pitch (deg))``."""
    from windflutter import api

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        p = api.campbell(turbine, [wind], model={"n_aero_sections": n_span}, damping={"model": "none"}).points[0]
    return {m.name: complex(m.eigenvalue) for m in p.modes}, p.rotor_speed_rpm, p.pitch_deg


def assert_identified_like(run, ref: dict, names) -> None:
    """Each named mode of method p (``ref``: name -> eigenvalue) found in the time-domain run's
    identified modes (the nearest eigenvalue): frequency within 0.5 %, damping ratio within 10 %
    (relative) or 0.2 points (issue 30's band)."""
    import numpy as np
    import pytest

    for name in names:
        lam = ref[name]
        f_ref, z_ref = abs(lam.imag) / (2 * np.pi), -lam.real / abs(lam)
        m = min(run.modes, key=lambda x: abs(x.lam - lam))
        assert m.frequency_hz == pytest.approx(f_ref, rel=5e-3), (name, m.frequency_hz, f_ref)
        assert abs(m.zeta - z_ref) <= max(0.1 * abs(z_ref), 2e-3), (name, m.zeta, z_ref)


def assert_checks_agree(res) -> None:
    """Each rotor speed of an onset confirmation (``confirm_onset``'s checks): a clean fit (residual
    below 1e-2, growth-rate spread below 20 % of it), damping ratio within 10 % (relative) or 0.2
    points of the eigenvalue's, frequency within 0.5 %."""
    import pytest

    for c in res.checks:
        assert c.residual < 1e-2 and c.sigma_spread < 0.2 * abs(c.sigma_sim)
        assert abs(c.zeta_sim - c.zeta_eig) <= max(0.1 * abs(c.zeta_eig), 2e-3)
        assert c.frequency_sim_hz == pytest.approx(c.frequency_eig_hz, rel=5e-3)


def method_p_blade_modes(turbine, wind, n_span, **options):
    """Method p's rotating-frame eigenvalues of the blade modes on a clamped hub (``model.part:
    rotor``, no structural damping): the mean of each BW/FW pair, ``lambda_BW,FW = lambda_r -+ i
    Omega``; ``({(family, order): eigenvalue}, rotor speed (RPM), pitch (deg))``.  ``options``:
    more config overrides (e.g. ``solver={"reduction": "none"}``)."""
    from windflutter import api

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = api.campbell(turbine, [wind], model={"part": "rotor", "n_aero_sections": n_span},
                           damping={"model": "none"}, **options)
    p = res.points[0]
    pairs = {}
    for m in p.modes:
        if m.whirl in ("BW", "FW"):
            pairs.setdefault((m.family, m.order), {})[m.whirl] = complex(m.eigenvalue)
    lam = {k: 0.5 * (v["BW"] + v["FW"]) for k, v in pairs.items() if len(v) == 2}
    return lam, p.rotor_speed_rpm, p.pitch_deg
