"""The reference point and the tolerance of the sensitivity tests (tests/sensitivity/test_sensitivity_point.py)."""

from __future__ import annotations

import numpy as np

from windflutter.sensitivity.eigen import frequency_damping

WIND, MAX_HZ = 15.0, 2.0
#: the blade elements of the spanwise segment changed (r/R ~ 0.3-0.5 of the 30-element blade)
SEGMENT = np.arange(8, 14)


def mismatches(res, derivs: dict, reference: dict, label: str) -> list[str]:
    """The modes whose frequency or damping derivative misses the reference (module tolerance)."""
    bad = []
    for i, m in enumerate(res.modes):
        ref = reference[m.identity_name]
        assert np.isfinite(ref), f"{label}: {m.identity_name} not found after the change"
        lam = complex(m.eigenvalue)
        (df, dz), (df0, dz0) = frequency_damping(lam, derivs[i]), frequency_damping(lam, ref)
        if abs(df - df0) > max(0.01 * abs(df0), 1e-4 * m.frequency_hz):
            bad.append(f"{label} {m.identity_name}: dfreq {df:.6g} against {df0:.6g} Hz")
        if abs(dz - dz0) > max(0.01 * abs(dz0), 1e-4):
            bad.append(f"{label} {m.identity_name}: dzeta {dz:.6g} against {dz0:.6g}")
    return bad
