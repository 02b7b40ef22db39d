"""The report in a real browser: headless Chromium renders ``report.html`` (a synthetic run with
an unstable edge mode in operation), its page script reports what the browser decoded, and a
screenshot is taken.  Checked: the verdict, the assumptions and the Campbell section are in the
rendered document, in that order; every figure is an image the browser decoded (natural width > 0);
the screenshot is a page with content, not a blank or an error page.  (What it looks like was
judged by eye: docs/verification.md.)  Skipped where no Chromium is installed, unless
``WINDFLUTTER_REQUIRE_BROWSER=1`` (``.ci/run`` installs Debian's chromium)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess

import numpy as np
import pytest

from post_fixtures import synthetic_run

BROWSER = next((b for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)
if BROWSER is None and os.environ.get("WINDFLUTTER_REQUIRE_BROWSER") != "1":
    pytest.skip("no Chromium on this machine (WINDFLUTTER_REQUIRE_BROWSER=1 makes this an error)",
                allow_module_level=True)

#: appended to a copy of the report: the browser's own count of decoded figures, in the DOM
PROBE = ("<script>window.addEventListener('load', () => {const imgs = [...document.images];"
         "document.body.dataset.decoded = imgs.filter(i => i.complete && i.naturalWidth > 0).length;"
         "document.body.dataset.images = imgs.length;});</script>")


def _chromium(*args, timeout=120):
    assert BROWSER is not None, "WINDFLUTTER_REQUIRE_BROWSER=1 but no Chromium found"
    cmd = [BROWSER, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           "--virtual-time-budget=10000", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=True)


def test_report_renders_in_a_browser(unstable_campbell, tmp_path):
    from matplotlib.image import imread

    from windflutter.post import plots, report

    ds = synthetic_run(flutter_rpm=(20.0, 19.0))
    figs = plots.all_figures(ds, unstable_campbell)
    html = report.build_report(ds, figs, dpi=40, campbell=unstable_campbell)
    page = tmp_path / "report.html"
    page.write_text(html.replace("</body>", PROBE + "</body>"), encoding="utf-8")

    dom = _chromium("--dump-dom", page.as_uri()).stdout
    order = [dom.index(f'data-section="{s}"') for s in ("verdict", "assumptions", "campbell")]
    assert order == sorted(order)
    assert "Verdict: unstable in operation" in dom
    n_img = int(re.search(r'data-images="(\d+)"', dom).group(1))
    decoded = int(re.search(r'data-decoded="(\d+)"', dom).group(1))
    assert n_img == len(figs) and decoded == n_img  # every figure decoded by the browser
    for name in figs:
        assert f'data-figure="{name}"' in dom

    shot = tmp_path / "report.png"
    _chromium(f"--screenshot={shot}", "--window-size=1280,3000", page.as_uri())
    img = imread(shot)
    assert img.shape[0] == 3000 and img.shape[1] == 1280
    rgb = img[..., :3]
    ink = np.mean(np.any(rgb < 0.9, axis=-1))  # share of pixels that are not (near) white
    colours = np.unique((rgb[::7, ::7] * 15).round().reshape(-1, 3), axis=0).shape[0]
    assert 0.02 < ink < 0.9 and colours > 30, (ink, colours)  # text, tables and coloured figures
