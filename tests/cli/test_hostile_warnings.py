"""Warnings of a command (issue 34): one line per kind listing the wind speeds, no warning about a
point the command did not analyse, range warnings that say inside the operating range or only at
overspeed, an air-density plausibility warning."""

from __future__ import annotations

import io
import math
import warnings

import pytest

from windflutter.cli.warn import grouped_line, one_line_warnings, operating_rotor_speed
from windflutter.errors import InputWarning, ValidityWarning

KIND = "the BEM induction leaves momentum theory at high rotor speed"


def _brake(v, rpm):
    warnings.warn(ValidityWarning(f"at V = {v:.1f} m/s {KIND}", rotor_speed_rpm=rpm, wind_speed=v, kind=KIND))


def test_one_line_per_kind_listing_the_wind_speeds():
    buf = io.StringIO()
    with one_line_warnings("windflutter x", stream=buf):
        warnings.simplefilter("always")
        for v, rpm in ((4.0, 14.0), (4.0, 12.0), (6.0, 20.0), (12.0, 9.0), (25.0, 30.0)):
            _brake(v, rpm)
        warnings.warn("something else", InputWarning)
        warnings.warn("something else", InputWarning)
        operating_rotor_speed(lambda v: {4.0: 7.1, 6.0: 7.6, 12.0: 12.1}.get(v, math.nan))
    lines = buf.getvalue().splitlines()
    assert len(lines) == 2, lines
    assert lines[0] == "windflutter x: warning: something else"
    line = lines[1]
    assert line.startswith(f"windflutter x: warning: {KIND} -- ")
    # 12 m/s from 9 RPM is below its operating 12.1 RPM: inside; 4 and 6 only above theirs; 25 m/s
    # has no operating speed (outside the curve): listed plainly; 4 m/s with its lowest speed
    assert "at V = 25 m/s from 30.0 RPM" in line
    assert "inside the operating range at V = 12 m/s from 9.0 RPM (operating 12.1 RPM)" in line
    assert ("only at overspeed at V = 4 m/s from 12.0 RPM (operating 7.1 RPM), 6 m/s from 20.0 RPM "
            "(operating 7.6 RPM)") in line


def test_grouped_line_without_a_curve():
    assert grouped_line("k", {10.0: math.inf, 4.0: 3.0}) == "k -- at V = 4 m/s from 3.0 RPM, 10 m/s"


def test_nothing_grouped_nothing_printed():
    buf = io.StringIO()
    with one_line_warnings("windflutter x", stream=buf):
        pass
    assert buf.getvalue() == ""


@pytest.mark.parametrize("rho, warned", [(1e-30, True), (0.5, True), (1.225, False), (0.8, False), (1.9, True)])
def test_air_density_plausibility(rho, warned):
    from windflutter.config import load_config

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        load_config(None, {"air_density": rho})
    hits = [str(w.message) for w in caught if "air_density" in str(w.message)]
    assert len(hits) == int(warned), hits
    if warned:
        assert f"air_density = {rho:g}" in hits[0] and "0.7-1.5" in hits[0]


def test_bem_warning_from_the_cache_and_not_from_the_basis(run_cli):
    """``stability --wind-speeds 10`` on the NREL 5 MW (p-k, 2 and 14 RPM, 10 strips, 8 basis
    modes): the reduction basis's own points (4 and 25 m/s at 0 and 14 RPM, where 4 m/s is in the
    propeller-brake state) give no warning (before issue 34: "at V = 4.0 m/s ..."); ``--wind-speeds
    4`` gives one line, only at overspeed (operating 7.1 RPM), although its BEM state at 14 RPM was
    first computed (quietly) for the basis and then taken from the cache."""
    argv = ["stability", "nrel5mw", "--method", "pk", "--rpm", "2", "14", "12", "--n-span", "10", "--basis-modes", "8",
            "--wind-speeds"]
    rc, out, err = run_cli(argv + ["10"])
    assert rc == 0 and "momentum" not in err, err
    rc, out, err = run_cli(argv + ["4"])
    lines = [ln for ln in err.splitlines() if "momentum" in ln]
    assert rc == 0 and len(lines) == 1, err
    assert "only at overspeed at V = 4 m/s from 14.0 RPM (operating 7." in lines[0]


def test_points_notes_gathered_into_one_line():
    """A run's worker processes print no range warning: the command gathers the points' notes
    (their ``reason``, where the full text stays) into one line per kind."""
    from windflutter.cli.warn import gather_notes

    reasons = [f"at V = 4.0 m/s {KIND} [from 12.00 RPM]", "",
               f"at V = 6.0 m/s {KIND} [from 17.50 RPM]; the steady state did not converge",
               f"at V = 12.0 m/s {KIND} [from 9.00 RPM]"]
    buf = io.StringIO()
    with one_line_warnings("windflutter run", stream=buf):
        warnings.simplefilter("always")
        _brake(4.0, 13.0)  # also seen in this process (one worker): the same line
        gather_notes(reasons)
        operating_rotor_speed(lambda v: {4.0: 7.1, 6.0: 7.6, 12.0: 12.1}[v])
    lines = buf.getvalue().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].endswith("inside the operating range at V = 12 m/s from 9.0 RPM (operating 12.1 RPM); only at "
                             "overspeed at V = 4 m/s from 12.0 RPM (operating 7.1 RPM), 6 m/s from 17.5 RPM "
                             "(operating 7.6 RPM)"), lines[0]


def test_worker_processes_print_no_gathered_warning():
    """The workers' warning display (windflutter.parallel) drops a gathered warning, shows others."""
    import windflutter.parallel as par

    seen = []
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = lambda message, *a, **k: seen.append(str(message))  # a fresh worker's display
        saved = warnings.formatwarning
        try:
            par.worker_warning_display()
            _brake(4.0, 12.0)
            warnings.warn("plain", InputWarning)
        finally:
            warnings.formatwarning = saved
    assert seen == ["plain"]
