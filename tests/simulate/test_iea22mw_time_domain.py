"""The IEA 22 MW whole turbine in the time domain against method p (issue 30), no structural
damping unless said, f_max 3 Hz.  Long runs (4-13 minutes each on the shared 2-core machine): slow.

The tower modes and the 1st edge damping agree at 10 elements.  The 1st edge FREQUENCY had been
about 1 % above method p's at 10 m/s and the 1st edge BW onset was not bracketed: traced to the
time domain's load transfer (the strip loads moved to the nodes with the steady configuration's
lever arms, a first-order, non-conservative nodal moment; docs/notes/iea22mw_edge_gap.md), fixed.
What is left between the two at 10 elements is method p's lever-arm load stiffness (the steady
strip loads are dead nodal loads there), a discretization term: the 1st edge -1.0 % at 10
elements, -0.05 % at 30.  The onset is therefore checked at 30 elements, where it is bracketed.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from windflutter.api import load_turbine
from method_p_reference import assert_checks_agree, assert_identified_like, method_p_in_wind
from windflutter.simulate.turbine_run import simulate_turbine


@pytest.fixture(scope="module")
def iea22mw():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return load_turbine("iea22mw")


@pytest.mark.slow
def test_iea22mw_operating_damping_10ms(iea22mw):
    """10 m/s (6.155 RPM, pitch 0.73 deg), 80 s: the identified damping of the 1st tower side-side
    and fore-aft, the 1st edge BW and FW and the 2nd edge BW and FW within 10 % or 0.2 points of
    method p's; frequencies within 0.5 % (tower, 2nd edge) and 2 % (1st edge: the lever-arm
    discretization term at 10 elements, module docstring).  Measured (4 Dec 2026, after the load-transfer fix): side-side
    0.120 % against 0.173 %, fore-aft 7.746 % against 7.836 %, 1st edge BW 3.634 % against 3.777 %
    (0.4023 against 0.4074 Hz, -1.27 %), FW 3.207 % against 3.244 % (-0.90 %), 2nd edge FW 0.647 %
    against 0.625 %, 2nd edge BW 1.3445 Hz / 1.325 % against 1.3460 / 1.418 % (41 % of its energy in
    the support: started in it, ``kick_mode="2nd edge BW"``, 20 s, the same numbers with 0.87 of
    the response)."""
    ref, rpm, pitch = method_p_in_wind(iea22mw, 10.0, 10)
    run = simulate_turbine(iea22mw, rpm, 10.0, pitch_deg=pitch, duration=80.0, n_span=10, f_max_hz=3.0)
    assert run.identification.residual < 1e-2
    for name, rel_f in (("1st tower side-side", 5e-3), ("1st tower fore-aft", 5e-3), ("1st edge BW", 2e-2),
                        ("1st edge FW", 2e-2), ("2nd edge BW", 5e-3), ("2nd edge FW", 5e-3)):
        lam = ref[name]
        f_ref, z_ref = abs(lam.imag) / (2 * np.pi), -lam.real / abs(lam)
        m = min(run.modes, key=lambda x: abs(x.lam - lam))
        assert m.frequency_hz == pytest.approx(f_ref, rel=rel_f), (name, m.frequency_hz, f_ref)
        assert abs(m.zeta - z_ref) <= max(0.1 * abs(z_ref), 2e-3), (name, m.zeta, z_ref)


@pytest.mark.slow
def test_iea22mw_operating_damping_20ms(iea22mw):
    """20 m/s (7.061 RPM, pitch 16.70 deg), 80 s: the 1st tower side-side and fore-aft, the 1st
    edge BW, FW and collective, the 2nd edge BW (with the 2nd tower fore-aft; negative without
    structural damping) and FW within 10 % or 0.2 points of method p's damping, frequencies within
    0.5 %.  Measured: side-side 0.618 % against 0.632 %, fore-aft 9.512 % against 9.471 %, 1st
    edge BW 2.505 % against 2.448 %, FW 1.548 % against 1.519 %, collective 1.385 % against
    1.387 %, 2nd edge BW -0.179 % against -0.118 %, FW 1.289 % against 1.344 %; frequencies
    within 0.07 % (measured before the load-transfer fix, not rerun: pitched and lightly loaded, the
    fix moves the linearized 1st edge here by 0.05 %, docs/notes/iea22mw_edge_gap.md)."""
    ref, rpm, pitch = method_p_in_wind(iea22mw, 20.0, 10)
    run = simulate_turbine(iea22mw, rpm, 20.0, pitch_deg=pitch, duration=80.0, n_span=10, f_max_hz=3.0)
    assert run.identification.residual < 1e-2
    assert_identified_like(run, ref, ("1st tower side-side", "1st tower fore-aft", "1st edge BW", "1st edge FW",
                                      "1st edge collective + 2nd flap collective", "2nd edge BW + 2nd tower fore-aft",
                                      "2nd edge FW + 2nd flap FW"))


@pytest.mark.slow
def test_iea22mw_onset_with_the_files_damping_bracketed(iea22mw):
    """Issue 30: the IEA 22 MW 1st edge BW onset at 10 m/s with the files' damping (method p,
    30 elements: 8.480 RPM, 1.20 x rated) decays at 0.97 x and grows at 1.03 x in the time domain
    (started in method p's mode, 30 s), damping within 10 % or 0.2 points of the eigenvalue's,
    frequency within 0.5 %.  Measured (4 Dec 2026): sigma -0.00666 / +0.01001 1/s against
    -0.00879 / +0.00792, zeta 0.281 % / -0.429 % against 0.370 % / -0.340 %, frequency 0.3776 /
    0.3708 Hz against 0.3780 / 0.3712 (-0.10 %).  At 10 elements the two onsets differ (the
    simulation grows already at 0.97 x: +0.0044 against -0.0081 1/s; docs/simulate.md)."""
    from windflutter.simulate.onset import confirm_onset

    res = confirm_onset(iea22mw, 10.0, n_span=30, duration=30.0, f_max_hz=3.0, damping="file", operating=False,
                        kick="onset")
    assert res.mode == "1st edge BW" and 8.0 < res.onset_rpm < 9.0
    assert res.confirmed
    assert_checks_agree(res)
