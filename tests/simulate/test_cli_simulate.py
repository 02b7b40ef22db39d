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
