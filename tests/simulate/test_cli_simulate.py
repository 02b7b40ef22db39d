"""`windflutter simulate`: bad input is one line naming the flag; a short run prints the modes."""

from __future__ import annotations

import json

import pytest

from windflutter.cli import main


@pytest.mark.parametrize("argv, words", [
    (["simulate", "nrel5mw"], ["--rpm"]),
    (["simulate", "nrel5mw", "--rpm", "-3"], ["--rpm", "[0, 200]"]),
    (["simulate", "nrel5mw", "--rpm", "10", "--duration", "0"], ["--duration"]),
    (["simulate", "nrel5mw", "--rpm", "10", "--n-span", "1"], ["--n-span"]),
    (["simulate", "nrel5mw", "--rpm", "10", "--circulation", "wagner"], ["--circulation"]),
    (["simulate", "nrel5mw", "--confirm-onset"], ["--wind-speed", "--confirm-onset"]),
    (["simulate", "nrel5mw", "--rpm", "10", "--part", "tower"], ["--part"]),
    (["simulate", "nrel5mw", "--rpm", "10", "--part", "blade", "--kick", "1st edge BW"], ["--kick", "--part blade"]),
    (["simulate", "nrel5mw", "--wind-speed", "8", "--confirm-onset", "--bracket", "0.7"], ["--bracket"]),
    (["simulate", "nrel5mw", "--rpm", "10", "--dynamic-stall"], ["dynamic_stall", "wind speed"]),
    (["simulate", "nrel5mw", "--wind-speed", "8", "--confirm-onset", "--dynamic-stall"], ["--dynamic-stall"]),
])
def test_bad_input_is_one_line(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and all(w in err for w in words), err


def test_short_run_json_and_csv(tmp_path, capsys):
    """A blade in vacuum at 12.1 RPM, 6 elements, 2.5 s: the 1st flap and edge are found; the
    response is written."""
    out = tmp_path / "r.csv"
    rc = main(["simulate", "nrel5mw", "--part", "blade", "--rpm", "12.1", "--n-span", "6", "--duration", "2.5",
               "--f-max", "5", "--json", "--output", str(out)])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    f = sorted(m["frequency_hz"] for m in d["modes"] if m["share"] > 0.01)
    assert 0.6 < f[0] < 0.8 and any(1.0 < x < 1.15 for x in f)
    # modes above --f-max are in the response but under-resolved: the fit residual says so (~0.08)
    assert not d["interrupted"] and d["residual"] < 0.2
    assert out.read_text().startswith("t,node")


def test_dynamic_stall_run_says_so(capsys):
    """One blade in the wind with --dynamic-stall (4 elements, 0.3 s): it runs and its line of what
    is included names dynamic stall (the model itself: test_dynamic_stall_time_domain.py)."""
    rc = main(["simulate", "nrel5mw", "--part", "blade", "--rpm", "12.1", "--wind-speed", "20", "--n-span", "4",
               "--duration", "0.3", "--f-max", "5", "--json", "--dynamic-stall"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert "dynamic stall" in d["included"] and not d["interrupted"]


def test_onset_plot(tmp_path):
    """The --confirm-onset figure from a synthetic check (the check itself: test_onset.py, slow)."""
    import numpy as np

    from windflutter.errors import InputError
    from windflutter.post.simulate_plot import plot_onset_check
    from windflutter.simulate.onset import OnsetCheck, SpeedCheck

    t = np.linspace(0.0, 10.0, 200)
    checks = tuple(SpeedCheck(f, 15 * f, s, 1e-3, 1.04, s, 1e-3, 1.04, 1e-4, 1e-5, False, t=t,
                              tip=np.stack([np.exp(s * t) * np.cos(6.5 * t)] * 3, axis=1) * 1e-4)
                   for f, s in ((0.97, -0.01), (1.03, 0.01)))
    res = OnsetCheck(10.0, 15.0, "1st edge FW", 0.0, checks)
    assert res.confirmed and "t" not in checks[0].summary()
    out = plot_onset_check(res, tmp_path / "o.png")
    assert out.stat().st_size > 1000
    with pytest.raises(InputError):
        plot_onset_check(res, tmp_path / "o.gif")


def test_unknown_kick_mode_lists_the_names(capsys):
    """``--kick`` with a name method p does not have at the point: one line listing those it has."""
    assert main(["simulate", "nrel5mw", "--rpm", "12.1", "--n-span", "4", "--kick", "2nd wobble"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--kick" in err and "'2nd wobble'" in err
    assert "'1st edge BW'" in err and "'1st tower side-side'" in err


def test_kick_starts_the_named_mode(capsys):
    """``--kick "1st edge FW"`` (whole turbine in vacuum, 12.1 RPM, 4 elements, 4 s): the run starts
    in method p's mode, so the identified mode nearest its eigenvalue carries more than 90 % of the
    response (measured 0.971; the default kick spreads it over tower, flap and edge modes) at its
    frequency within 0.5 % (measured 1.1887 Hz against 1.1892 Hz).  A wrong map of the multi-blade
    coordinates would start the BW mode (0.83 Hz) or a mixture instead."""
    rc = main(["simulate", "nrel5mw", "--rpm", "12.1", "--n-span", "4", "--duration", "4", "--f-max", "2.5",
               "--kick", "1st edge FW", "--json"])
    assert rc == 0
    k = json.loads(capsys.readouterr().out)["kicked"]
    assert k["name"] == "1st edge FW" and 1.1 < k["frequency_hz"] < 1.3
    assert k["identified_share"] > 0.9
    assert k["identified_frequency_hz"] == pytest.approx(k["frequency_hz"], rel=5e-3)


def test_confirm_onset_table_json_and_plot(tmp_path, capsys, monkeypatch):
    """``--confirm-onset`` passes the bracket, the operating speed and the kick to the check and
    prints one row per speed (the check itself, real runs: test_turbine_time_domain.py, slow); the
    figure has a panel per speed."""
    import numpy as np

    from windflutter import api
    from windflutter.simulate.onset import OnsetCheck, SpeedCheck

    seen = {}

    def fake(turbine, wind_speed, **kw):
        seen.update(kw)
        t = np.linspace(0.0, 5.0, 100)
        tip = np.zeros((100, 3))
        checks = tuple(SpeedCheck(f, 14.0 * f, s, -s, 0.8, s, -s, 0.8, 1e-4, 1e-3, False, t=t, tip=tip)
                       for f, s in ((0.64, -0.02), (0.9, -0.01), (1.1, 0.01)))
        return OnsetCheck(wind_speed, 14.0, "1st edge BW", 0.0, checks, part="turbine")

    monkeypatch.setattr(api, "confirm_onset", fake)
    out = tmp_path / "o.png"
    assert main(["simulate", "nrel5mw", "--wind-speed", "8", "--confirm-onset", "--bracket", "0.1", "--kick", "onset",
                 "--plot", str(out), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert seen["factors"] == pytest.approx((0.9, 1.1)) and seen["kick"] == "onset"
    assert "CONFIRMED" in text and len([ln for ln in text.splitlines() if ln.strip().startswith(("0.", "1."))]) == 3
    assert out.stat().st_size > 1000


@pytest.mark.slow
def test_confirm_onset_cli_real(tmp_path, capsys):
    """The real ``--confirm-onset --kick onset`` of the whole NREL 5 MW at 8 m/s (10 elements,
    30 s, no structural damping): the operating speed (8.97 RPM) and 0.97 / 1.03 x the 1st edge
    BW onset (14.20 RPM), each run started in the unstable mode: decay, decay, growth, as the
    eigenvalues; damping within 10 % or 0.2 points, frequency 0.5 %; the figure has the three
    tip responses.  Measured (f-max 3): zeta 0.649 / 0.112 / -0.109 % against 0.717 / 0.120 /
    -0.118 %, frequencies within 0.03 %, fit residual 6e-5."""
    out = tmp_path / "o.png"
    assert main(["simulate", "nrel5mw", "--wind-speed", "8", "--confirm-onset", "--kick", "onset", "--n-span", "10",
                 "--duration", "30", "--f-max", "3", "--plot", str(out), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["mode"] == "1st edge BW" and d["confirmed"]
    checks = d["checks"]
    assert [c["factor"] for c in checks][1:] == pytest.approx([0.97, 1.03]) and checks[0]["factor"] < 0.7
    assert checks[0]["sigma_sim"] < 0 and checks[1]["sigma_sim"] < 0 < checks[2]["sigma_sim"]
    for c in checks:
        assert abs(c["zeta_sim"] - c["zeta_eig"]) <= max(0.1 * abs(c["zeta_eig"]), 2e-3), c
        assert c["frequency_sim_hz"] == pytest.approx(c["frequency_eig_hz"], rel=5e-3), c
    assert out.stat().st_size > 1000


def test_the_included_line_names_the_damping_it_runs_with():
    from windflutter.simulate.run import included

    assert included("turbine").endswith("no gravity, dynamic inflow or structural damping")
    assert included("turbine", "file").endswith("no gravity or dynamic inflow; with the turbine files' structural damping")
    assert included("blade").endswith("no tower, drivetrain, other blades, gravity, dynamic inflow or structural damping")
