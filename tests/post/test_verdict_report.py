"""The verdict and the terminal headline (stable, unstable in operation, unstable below
overspeed), labels in the field's terms, formatted numbers, and the report that leads with them."""

from __future__ import annotations

import re

import numpy as np
import pytest
from post_fixtures import RATED_RPM, synthetic_run

from windflutter.post import fmt
from windflutter.post.verdict import headline, verdict


def test_headline_of_a_stable_turbine(stable_campbell):
    ds = synthetic_run(flutter_rpm=(20.0, 19.0))
    text = headline(ds, stable_campbell)
    lines = text.splitlines()
    assert lines[0] == "verdict: stable up to overspeed"
    # first instability: the lower of the two onsets, its mode in words, RPM and margins
    # computed here: 19/12.1 - 1 = +57.0 %, 19/14.52 - 1 = +30.9 %
    assert lines[1].startswith("first instability: flutter of flap-edge, blade 2 at 19.00 RPM, 1.050 Hz, "
                               "grown from edge, blade 2 (V = 20 m/s")
    assert "+57.0 % to rated 12.10 RPM" in lines[1] and "+30.9 % to overspeed 14.52 RPM" in lines[1]
    # least damped in operation: the synthetic edge BW at 11 m/s, zeta 0.8 %
    assert lines[2] == "least damped mode in operation: 1st edge BW, ζ = 0.80 % at V = 11 m/s (0.880 Hz, 12.10 RPM)"
    assert "12.100000000000001" not in text


def test_headline_of_a_mode_unstable_in_operation(unstable_campbell):
    ds = synthetic_run(flutter_rpm=(20.0, 19.0))
    v = verdict(ds, unstable_campbell)
    assert v.status == "unstable in operation" and not v.stable
    assert v.first.kind == "negative damping" and v.first.mode == "1st edge BW"
    assert v.first.margin_rated == pytest.approx(0.0)          # at rated speed, 11 m/s
    text = headline(ds, unstable_campbell)
    assert text.splitlines()[0] == "verdict: UNSTABLE IN OPERATION"
    assert "negative damping of 1st edge BW (ζ = -0.40 %) at 12.10 RPM, 0.880 Hz" in text
    assert "least damped mode in operation: 1st edge BW, ζ = -0.40 % at V = 11 m/s" in text


def test_verdict_levels_from_the_overspeed_search_alone():
    below_over = verdict(synthetic_run(flutter_rpm=(13.0, 14.0)))
    assert below_over.status == "instability below overspeed"
    assert below_over.first.margin_rated == pytest.approx(13.0 / RATED_RPM - 1)
    below_rated = verdict(synthetic_run(flutter_rpm=(11.0, 14.0)))
    assert below_rated.status == "instability below rated"
    # an onset at or below the operating rotor speed of its wind speed is in operation
    ds = synthetic_run(flutter_rpm=(11.0, 14.0))
    ds["operating_rpm"] = ("operating", [8.0, 10.5])
    ds = ds.assign_coords(operating_wind_speed=("operating", [5.0, 10.0]))
    assert verdict(ds).status == "instability below rated"     # 11 RPM at 10 m/s, above its 10.5
    ds["operating_rpm"] = ("operating", [8.0, 11.5])
    assert verdict(ds).status == "unstable in operation"       # 11 RPM at 10 m/s, below its 11.5
    none = synthetic_run(flutter_rpm=(float("nan"), float("nan")))
    assert verdict(none).status == "no instability found"
    assert headline(none).splitlines()[1] == "first instability: none found up to 24.00 RPM"
    # a sweep stopped early (no steady state, the structure alone unstable) limits the claim
    r = none["rotor_speed"].values.copy()
    r[1, r[1] > 16.0] = float("nan")
    none["rotor_speed"] = none["rotor_speed"].copy(data=r)
    top = float(np.nanmax(r[1]))
    assert top < 16.0
    # ... and, a sweep having ended below rated (or overspeed), so does the claim's scope: "none found"
    # covers less than the turbine's range there
    assert top < RATED_RPM
    assert headline(none).splitlines()[1] == (f"first instability: none found up to {top:.2f} RPM at every wind "
                                              "speed (24.00 RPM at most; see the points' notes), below rated "
                                              f"{RATED_RPM:.2f} RPM: not searched up to it at every wind speed")


def test_sweeps_ending_within_two_per_cent_searched_one_range():
    """Method p's sweeps end on the tips' Mach 0.5, 1 % lower at 25 m/s than at 4 m/s (the wind adds to the
    tip's speed): "none found up to" the lower end, without sending the reader to notes the points do not
    have; a sweep ending 3 % lower still does (the test above: a stop)."""
    for factor, spread in ((0.99, False), (0.97, True)):
        none = synthetic_run(flutter_rpm=(float("nan"), float("nan")))
        r = none["rotor_speed"].values.copy()
        r[1, np.nanargmax(r[1])] *= factor
        none["rotor_speed"] = none["rotor_speed"].copy(data=r)
        line = headline(none).splitlines()[1]
        assert line.startswith(f"first instability: none found up to {24.0 * factor:.2f} RPM"), line
        assert ("at most; see the points' notes" in line) == spread, line


@pytest.mark.parametrize("label, words", [
    ("flap-edge b3 r/R=1.00", "flap-edge, blade 3"),
    ("torsion b2 r/R=0.60", "torsion, blade 2, peak at r/R 0.60"),
    ("flap-edge b3 r/R=1.00 -> flap b2 r/R=1.00", "flap, blade 2"),
    ("1st edge BW", "1st edge BW"),                     # the field's vocabulary passes unchanged
    ("tower", "tower"),
])
def test_field_label(label, words):
    assert fmt.field_label(label) == words


def test_flutter_label_parts_and_number_formats():
    assert fmt.flutter_label("edge b1 r/R=1.00 -> flap b2 r/R=0.95 (above divergence)") == (
        "flap, blade 2", "edge, blade 1", "above divergence")
    assert fmt.sig(12.100000000000001) == "12.1" and fmt.num(float("nan")) == "—"
    assert fmt.value(True) == "yes" and fmt.value(False) == "no" and fmt.value(0.1 + 0.2) == "0.3"
    assert fmt.qty(12.1, "RPM") == "12.10 RPM" and fmt.pct(0.1744) == "+17.4 %"


def test_report_opens_with_the_verdict_and_assumptions(unstable_campbell):
    from windflutter.post import plots, report

    ds = synthetic_run(flutter_rpm=(20.0, 19.0))
    html = report.build_report(ds, {}, campbell=unstable_campbell)
    order = [html.index(f"data-section='{s}'") for s in ("verdict", "assumptions", "campbell")]
    assert order == sorted(order) and order[0] < html.index("Summary: margins")
    assert "Verdict: unstable in operation" in html and "class='verdict bad'" in html
    assert "unsteady strips" in html and "flexible" in html           # the Campbell's assumptions
    # the margins table names the flutter mode and its frequency
    row = re.search(r"<tr><td class='l'>potential, pk</td>.*?</tr>", html).group(0)
    assert "flap-edge, blade 2" in row and "<td>1.050</td>" in row
    # least damped per wind speed: one row per wind speed, negative damping in red
    camp = html[html.index("data-section='campbell'"):]
    camp = camp[:camp.index("</section>")]
    assert camp.count("<tr><td>") == 3 and "<span class='warn'>-0.40</span>" in camp
    # formatted numbers and flags: no float noise (the config's own text aside), no 1/0 for booleans
    assert "12.100000000000001" not in re.sub(r"<pre>.*?</pre>", "", html, flags=re.S)
    assert "<th class='l'>solver.geometric_stiffness</th><td class='l'>yes</td>" in html
    assert "rated rotor speed</th><td class='l'>12.1 RPM" in html
    # the operating Campbell figure goes into its section, not among the run's figures
    figs = {"operating_campbell": plots.all_figures(ds.isel(point=[]), unstable_campbell)["operating_campbell"]}
    html = report.build_report(ds, figs, dpi=30, campbell=unstable_campbell)
    assert html.count("data-figure='operating_campbell'") == 1
    assert html.index("data-figure='operating_campbell'") > html.index("data-section='campbell'")


def test_an_onset_whose_point_kept_a_validity_note_is_said_so():
    # the lowest onset (19 RPM at 20 m/s) comes from a point whose sweep left the BEM's range:
    # the headline names it with the caution; without the note it reads as before
    from windflutter.post import verdict as vd

    ds = synthetic_run(flutter_rpm=(20.0, 19.0))
    plain = vd.headline(ds)
    assert "caution" not in plain
    ds["reason"] = ds["reason"].copy(data=["", "at V = 20.0 m/s the BEM induction leaves momentum theory ..."])
    v = vd.verdict(ds)
    assert v.first.wind_speed == 20.0 and v.first.caveat == vd.CAVEAT
    assert f"caution: {vd.CAVEAT}" in vd.headline(ds)
    ds["reason"] = ds["reason"].copy(data=["at V = 10.0 m/s ...", ""])  # a note on the other point only
    assert "caution" not in vd.headline(ds)
    # a note that starts above the onset (19 RPM) does not concern it; one that starts below does
    ds["reason"] = ds["reason"].copy(data=["", "at V = 20.0 m/s ... [from 25.00 RPM]"])
    assert "caution" not in vd.headline(ds)
    ds["reason"] = ds["reason"].copy(data=["", "at V = 20.0 m/s ... [from 18.50 RPM]"])
    assert f"caution: {vd.CAVEAT}" in vd.headline(ds)


def test_sweep_instability_in_operation_and_a_damped_campbell_do_not_contradict(stable_campbell):
    """Issue 34: "UNSTABLE IN OPERATION" (a sweep onset at or below the operating rotor speed of its
    wind speed) above "least damped mode in operation: ζ = +0.80 %" read as a contradiction; the
    Campbell line now says which operating points it covered and whose the instability is."""
    ds = synthetic_run(flutter_rpm=(11.0, 14.0))
    ds["operating_rpm"] = ("operating", [8.0, 11.5])
    ds = ds.assign_coords(operating_wind_speed=("operating", [5.0, 10.0]))
    lines = headline(ds, stable_campbell).splitlines()
    assert lines[0] == "verdict: UNSTABLE IN OPERATION"
    assert lines[2].startswith("least damped mode in operation: 1st edge BW, ζ = 0.80 %")
    assert "every mode damped at the Campbell's operating points (V = " in lines[2]
    assert "the instability above is the rotor-speed sweep's at V = 10 m/s" in lines[2]
    # a stable verdict keeps the plain line
    assert "every mode damped" not in headline(synthetic_run(flutter_rpm=(20.0, 19.0)), stable_campbell)


def test_a_run_whose_points_all_failed_has_no_result_whatever_its_campbell(stable_campbell):
    """Every map point failed (the IEA 15 MW shell: each wind speed refused, its blade structure
    unstable on its own): the damped Campbell does not make it "no instability found"; one point done
    is a result again, and the Campbell alone (no map) still is."""
    ds = synthetic_run(flutter_rpm=(float("nan"), float("nan")))
    ds["status"] = ("point", ["failed", "failed"])
    v = verdict(ds, stable_campbell)
    assert v.status == "no result" and v.least_damped is not None
    ds["status"] = ("point", ["failed", "ok"])
    assert verdict(ds, stable_campbell).status == "no instability found"
    assert verdict(None, stable_campbell).status == "no instability found"
