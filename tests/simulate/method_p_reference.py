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
