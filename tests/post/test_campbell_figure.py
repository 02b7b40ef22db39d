"""The operating-point Campbell figure: it builds, names every line without overprinting, scales
the damping axis to the lightly damped modes, marks the least damped and unstable modes and keeps
the legends off the data."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from matplotlib.text import Annotation, Text

from windflutter.post.campbell_data import campbell_dataset, least_damped
from windflutter.post.campbell_plots import campbell_figure


def _labels(fig):
    return [t for ax in fig.axes for t in ax.texts if isinstance(t, Annotation) and not t.get_text().endswith("P")]


def _overlaps(boxes):
    return [(i, j) for (i, a), (j, b) in itertools.combinations(enumerate(boxes), 2)
            if a.x0 < b.x1 - 0.5 and b.x0 < a.x1 - 0.5 and a.y0 < b.y1 - 0.5 and b.y0 < a.y1 - 0.5]


def test_campbell_figure_of_the_nrel5mw_names_every_line_without_overprinting(nrel_campbell_ds, tmp_path):
    ds = nrel_campbell_ds
    fig = campbell_figure(ds)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()                                         # text extents are final
    r = canvas.get_renderer()
    texts = _labels(fig)
    boxes = [Text.get_window_extent(t, r) for t in texts]     # the text itself, not its leader line
    assert not _overlaps(boxes), [texts[i].get_text() + " / " + texts[j].get_text() for i, j in _overlaps(boxes)]
    axf, axh, axl = fig.axes[:3]
    # every drawn track is named at its end on the frequency panel (rigid-body root not drawn)
    elastic = [t for t in range(ds.sizes["track"]) if not np.all(ds["rigid_body"].values[:, t][np.isfinite(
        ds["frequency"].values[:, t])] == 1)]
    names_f = sorted(t.get_text() for t in axf.texts if isinstance(t, Annotation) and not t.get_text().endswith("P"))
    assert names_f == sorted(str(ds["track_name"].values[t]) for t in elastic)
    assert "drivetrain rigid-body" not in names_f
    # the 1P/3P/6P/9P lines are drawn and named
    assert {t.get_text() for t in axf.texts if t.get_text().endswith("P")} <= {"1P", "3P", "6P", "9P"}
    assert "1P" in {t.get_text() for t in axf.texts}
    # damping axis: main panel scaled to the lightly damped modes (edge, tower: < 10 %), the flap
    # modes (up to 62 % here) on the panel above the break, both in %
    lo, cut = axl.get_ylim()
    assert lo < 0 < cut <= 10.0 + 1e-9
    z = np.where(ds["rigid_body"].values == 1, np.nan, 100 * ds["damping_ratio"].values)
    assert axh.get_ylim()[0] == pytest.approx(cut) and axh.get_ylim()[1] > np.nanmax(z)
    # the least damped mode starred on both panels at its own coordinates
    ld = least_damped(ds)
    stars = [(ax, ln) for ax in (axf, axl) for ln in ax.lines if ln.get_marker() == "*"]
    assert len(stars) == 2
    assert stars[0][1].get_xydata()[0] == pytest.approx([ld["wind_speed"], ld["frequency_hz"]])
    assert stars[1][1].get_xydata()[0] == pytest.approx([ld["wind_speed"], 100 * ld["damping_ratio"]])
    assert ld["name"] in axh.get_title()
    # legends below the axes, covering no data
    data_area = [ax.get_window_extent(r) for ax in fig.axes]
    for leg in fig.legends:
        lb = leg.get_window_extent(r)
        assert all(not (lb.x0 < a.x1 and a.x0 < lb.x1 and lb.y0 < a.y1 and a.y0 < lb.y1) for a in data_area)


def test_unstable_mode_is_crossed_and_announced(unstable_campbell):
    fig = campbell_figure(unstable_campbell)
    axl = fig.axes[-1]
    crosses = [ln for ln in axl.lines if ln.get_marker() == "x"]
    assert len(crosses) == 1 and crosses[0].get_xydata().tolist() == [[11.0, pytest.approx(-0.4)]]
    assert fig.axes[1].get_title().startswith("UNSTABLE: 1st edge BW")
    assert axl.get_ylim()[0] < -0.4                   # the negative value is inside the axis


def test_campbell_dataset_and_result_draw_the_same(stable_campbell):
    a = campbell_figure(stable_campbell)
    b = campbell_figure(campbell_dataset(stable_campbell))
    da = [ln.get_xydata().tolist() for ax in a.axes for ln in ax.lines]
    db = [ln.get_xydata().tolist() for ax in b.axes for ln in ax.lines]
    np.testing.assert_equal(da, db)


def test_save_campbell_plot_writes_the_file_or_names_the_option(stable_campbell, tmp_path):
    from windflutter.errors import InputError
    from windflutter.post.campbell_plots import save_campbell_plot

    p = save_campbell_plot(stable_campbell, tmp_path / "sub" / "c.png", dpi=30)
    assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for bad in (tmp_path / "c.txt", tmp_path):
        with pytest.raises(InputError, match="--plot"):
            save_campbell_plot(stable_campbell, bad)
