"""Shell vs thin-walled beam of the same layup (seed 5 MW): the overspeed flutter and divergence onsets.

Run:  OPENBLAS_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/shell_vs_beam_onsets.py [--quick]
(the full study is about 45 minutes on one core; --quick runs the 30-element meshes only, about 5
minutes).  Results: docs/verification.md section 11 item 4 and docs/mesh.md.

The case: 10 m/s, the rotor with its hub clamped, p-k, potential flow, no induction or mean loads
(``windflutter stability seed5mw --part rotor --aero potential --method pk --no-induction
--no-mean-loads``), one aerodynamic strip per blade element.  Each row changes one thing:

* the beam at 30 / 60 / 90 elements (its sections' shear and torsion stiffness at their shear centre);
* the shell (40 elements around each section) at 30 / 60 / 90 / 120 elements along the span, its
  tips closed by the rib (the default), the skin on the outer mould line (the default, the seed's);
* the same shell with its skin on the laminate midsurface (the beam's wall midline), at 30 and 90;
* the shell with the open tip of the seed's mesh (``model.tip_closure: open``) at 30.
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import io
import json
import time
import warnings

import windflutter.mesh.parts as parts
from windflutter.cli import main
from windflutter.mesh.blade_shell import blade_shell_mesh


def onset(model: str, n_span: int, surface: str = "outer", tip: str | None = None) -> dict:
    """Flutter / divergence onsets (RPM) and the flutter frequency (Hz) of one case."""
    original = parts.blade_shell_mesh
    parts.blade_shell_mesh = functools.partial(blade_shell_mesh, reference_surface=surface)
    args = ["stability", "seed5mw", "--model", model, "--part", "rotor", "--aero", "potential",
            "--n-span", str(n_span), "--method", "pk", "--no-induction", "--no-mean-loads", "--json"]
    buf = io.StringIO()
    if tip is not None:
        args += ["--tip-closure", tip]
    try:
        with contextlib.redirect_stdout(buf), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            main(args)
    finally:
        parts.blade_shell_mesh = original
    p = json.loads(buf.getvalue())["points"][0]
    return {k: p[k] for k in ("flutter_rpm", "flutter_frequency_hz", "divergence_rpm")}


def run(quick: bool) -> None:
    spans = (30,) if quick else (30, 60, 90)
    cases = [("beam", n, "outer", None) for n in spans]
    cases += [("shell", n, "outer", None) for n in ((30,) if quick else (30, 60, 90, 120))]
    cases += [("shell", n, "midsurface", None) for n in ((30,) if quick else (30, 90))]
    cases += [("shell", 30, "outer", "open")]
    for model, n, surface, tip in cases:
        t = time.time()
        r = onset(model, n, surface, tip)
        print(f"{model:5s} 40x{n:<3d} {surface:10s} tip {tip or 'default':7s}  flutter {r['flutter_rpm']:.2f} RPM "
              f"({r['flutter_frequency_hz']:.2f} Hz), divergence {r['divergence_rpm']:.2f} RPM   [{time.time() - t:.0f} s]",
              flush=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the 30-element meshes only")
    run(ap.parse_args().quick)
