"""The mode-identity criteria of issue 32, on a CampbellResult: every blade family an engineer reads
(1st-3rd flap, 1st and 2nd edge, 1st torsion; collective, BW, FW) present at every wind speed; no
named mode's natural frequency jumping by more than 12 % between neighbouring wind speeds (both
damped below 30 %); no ordinal beyond the blade's own count of its family below the plot's limit.
Written for the test suite (the same criteria as the project's shared checker of the JSON)."""

from __future__ import annotations

FAMILIES = [("flap", 1), ("flap", 2), ("flap", 3), ("edge", 1), ("edge", 2), ("torsion", 1)]
WHIRLS = ("BW", "FW", "collective")
JUMP = 0.12
HEAVY = 0.3


def identity_checks(result, blade_counts: dict[str, int], limit_hz: float):
    """``(passed, total, missing, jumps, impossible)``: the checks passed of the presence and jump
    checks (one per family, whirl and wind speed) and the lists of failures."""
    n = ok = 0
    missing, jumps, impossible = [], [], []
    prev: dict = {}
    for p in result.points:
        by = {}
        for m in p.modes:
            if m.identity is None:
                continue
            fam, order = m.identity.family, m.identity.order
            if fam in blade_counts and order > blade_counts[fam] and m.frequency_hz < limit_hz:
                impossible.append(f"{p.wind_speed:g} m/s: {m.name} at {m.frequency_hz:.3f} Hz")
            by[(fam, order, m.identity.whirl)] = m
        for fam, order in FAMILIES:
            for w in WHIRLS:
                n += 1
                key = (fam, order, w)
                m = by.get(key)
                if m is None:
                    missing.append(f"{p.wind_speed:g} m/s: {order} {fam} {w}")
                    continue
                q = prev.get(key)
                if q is not None and max(m.damping_ratio, q.damping_ratio) < HEAVY \
                        and abs(m.frequency_hz / q.frequency_hz - 1) > JUMP:
                    jumps.append(f"{p.wind_speed:g} m/s: {m.name} {q.frequency_hz:.3f} -> {m.frequency_hz:.3f} Hz")
                else:
                    ok += 1
                prev[key] = m
    return ok, n, missing, jumps, impossible


#: a mode in operation may lie this much below the blade's own mode it is (aerodynamic coupling with a
#: neighbour: the IEA 15 MW's 3rd edge FW at 25 m/s, mixed with the 3rd flap, is 9 % below the blade's
#: 4.34 Hz at 3.94 Hz); an ordinal is impossible when the blade has no mode of it within this of the limit
COUPLING_MARGIN = 1.15


def blade_counts_below(reference, limit_hz: float) -> dict[str, int]:
    """The blade's own count of each family below ``COUPLING_MARGIN`` x ``limit_hz`` (its standstill
    modes; the rotor's stiffening only raises them)."""
    out: dict[str, int] = {}
    for fam, order, f in reference.blade:
        if f < COUPLING_MARGIN * limit_hz:
            out[fam] = max(out.get(fam, 0), order)
    return out
