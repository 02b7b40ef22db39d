"""The run's sweep figures (Campbell and V-g of the overspeed search) and the section V-g plot:
names in the field's terms without overprinting, the damping axis scaled to the lightly damped
modes, the flutter mode highlighted, the section's damping with the turbine's sign."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from post_fixtures import synthetic_run
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Annotation, Text

from windflutter.post import plots


def _label_boxes(fig):
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    r = canvas.get_renderer()
    texts = [t for ax in fig.axes for t in ax.texts if isinstance(t, Annotation) and not t.get_text().endswith("P")]
    return texts, [Text.get_window_extent(t, r) for t in texts]


def test_sweep_figures_name_modes_in_words_and_scale_the_damping_axis():
    labels = ("flap b1 r/R=1.00", "edge b1 r/R=1.00")
    ds = synthetic_run(labels=labels)
    fig = plots.damping_plot(ds, 1)
    for f in (plots.campbell(ds, 1), fig):
        texts, boxes = _label_boxes(f)
        assert {t.get_text() for t in texts} == {"flap, blade 1", "edge, blade 1"}
        for a, b in itertools.combinations(boxes, 2):
            assert not (a.overlaps(b) and a.y0 < b.y1 - 0.5 and b.y0 < a.y1 - 0.5)
    axh, axl = fig.axes[:2]
    # the edge mode (2 % .. -1 %) fills the main panel; the 30 % flap mode sits above the break
    assert axl.get_ylim()[1] == pytest.approx(1.15 * 0.02) and axl.get_ylim()[0] < -0.01
    assert axh.get_ylim()[1] > 0.3
    # the flutter mode (the one crossing zero: column 1) is drawn bold and black
    bold = [ln for ln in axl.lines if ln.get_linewidth() > 2]
    assert len(bold) == 1 and np.allclose(bold[0].get_ydata(), ds["damping_ratio"].values[1][:, 1])


def test_section_vg_plot_has_the_turbine_sign():
    from types import SimpleNamespace

    from windflutter.post.vg_plots import vg_figure

    speed = np.linspace(1, 50, 5)
    zeta = np.array([[0.05, 0.04, 0.02, 0.0, -0.02], [0.1, 0.1, 0.1, 0.1, 0.1]])
    for kind, damping, expect in (("zeta", zeta, zeta), ("g", -2 * zeta, zeta)):
        c = SimpleNamespace(speed=speed, frequency=np.ones((2, 5)), damping=damping, damping_kind=kind)
        res = SimpleNamespace(curves=c, flutter_speed=37.5, divergence_speed=None, max_speed=50.0, method="p-k")
        fig = vg_figure(res)
        lines = [ln for ln in fig.axes[0].lines if len(ln.get_xdata()) == 5]
        np.testing.assert_allclose([ln.get_ydata() for ln in lines], expect)   # positive = damped
        import matplotlib.pyplot as plt

        plt.close(fig)
