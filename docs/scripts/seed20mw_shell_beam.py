"""The seed 20 MW's shell beside the beam of its layup (issue 33): the numbers of
docs/notes/seed_comparison.md section 5 that trace the two models' differences at 10 m/s.

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/seed20mw_shell_beam.py [props] [modes] [onsets]

* props: the shell blade's section properties (``mesh/shell_beam.py``, the default shell mesh)
  against the thin-walled beam's of the same layup (``model/section.py``) at 20 stations: mass,
  EA, flap and edge EI (about the tension centre), GJ (about the shear centre), the chordwise
  tension, shear and mass centres.
* modes: the rotor's structural modes (hub clamped, 10 m/s: pitch 0) of the shell, the
  thin-walled beam and the beam on the shell's own properties (``with_shell_blade_properties``,
  40 stations) at 0, 5 and 8 RPM: frequencies and method p's names, in the p-k model's basis.
* onsets: the p-k onsets at 10 m/s of the beam on the shell's properties (the shell and the
  thin-walled beam: section 5's table, ``windflutter stability seed20mw --model shell|beam --part
  rotor --aero potential --method pk --no-induction --no-mean-loads``), undamped and with 0.5 %
  modal damping (``--damping modal --damping-ratio 0.005``).
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings

import numpy as np

from windflutter.cli import stability as cli_stability
from windflutter.frozen.tracking import mode_names
from windflutter.model.section import layup_beam_sections
from windflutter.mesh.shell_beam import shell_beam_table, with_shell_blade_properties
from windflutter.methods import stability_analysis
from windflutter.model import load_turbine
from windflutter.structure.modal import symmetric_eigs
from windflutter.units import RPM

SEED_FLAGS = ["--part", "rotor", "--aero", "potential", "--method", "pk", "--no-induction", "--no-mean-loads"]


def solver(turbine, model: str, extra=()):
    """The ``windflutter stability seed20mw`` solver of ``model`` for the turbine object ``turbine``."""
    p = argparse.ArgumentParser()
    cli_stability.add_parser(p.add_subparsers())
    args = p.parse_args(["stability", "seed20mw", "--model", model, *SEED_FLAGS, *extra])
    config, _ = cli_stability.options_from_args(args)
    return stability_analysis(turbine, config, config.aero[0], config.method[0])


def section_numbers(K, M):
    """(mass, EA, EI flap, EI edge, GJ, tension-centre z, shear-centre z, mass-centre z) of a 6x6 pair
    (BeamSection order N, V_y, V_z, T, M_y, M_z; y flapwise, z chordwise to the TE)."""
    C = np.linalg.inv(K)
    Kb = np.linalg.inv(C[4:, 4:])
    zt = K[0, 4] / K[0, 0]  # K04 = int E z
    Kv = np.linalg.inv(C[np.ix_([1, 2, 3], [1, 2, 3])])  # shear-torsion about the reference
    zs = -Kv[0, 2] / Kv[0, 0]  # K13 = -GA_y z_s
    zm = M[0, 4] / M[0, 0] if abs(M[0, 4]) > 0 else -M[0, 5] / M[0, 0]
    return M[0, 0], K[0, 0], Kb[1, 1], Kb[0, 0], 1.0 / C[3, 3], zt, zs, zm


def props(t):
    tab = shell_beam_table(t, n_stations=20)
    tw = layup_beam_sections(t, tab.s)
    print("s, chord | shell / thin-walled: mass, EA, EI flap, EI edge, GJ (ratio) | centres z/c: tension, shear, mass")
    for i, s in enumerate(tab.s):
        a = section_numbers(tab.beam.stiffness[i], tab.beam.mass[i])
        b = section_numbers(tw.stiffness[i], tw.mass[i])
        c = float(np.interp(s, t.blade.s, t.blade.chord))
        ratios = " ".join(f"{x / y:5.2f}" for x, y in zip(a[:5], b[:5]))
        zt = tab.tension_centre[i, 1] / c
        zs = tab.shear_centre[i, 1] / c
        zm = tab.mass_centre[i, 1] / c
        print(f"{s:5.3f} {c:5.2f} | {ratios} | shell {zt:+.3f} {zs:+.3f} {zm:+.3f}  beam {b[5] / c:+.3f} "
              f"{b[6] / c:+.3f} {b[7] / c:+.3f}{'  (clipped)' if tab.clipped[i] else ''}", flush=True)


#: the needle tip of the seed 20 MW blade: chord 3.0 m at 88 % span, 0.52 m at 93 %, 0.12 m from 95 %
TIP_SPAN = 0.88


def tip_share(fe, M, shapes, turbine):
    """(m,) share of each mode's kinetic energy (translations) in the blades' outer part, beyond
    :data:`TIP_SPAN` of the blade's span from the root."""
    x = np.asarray(fe.nodes, float)
    outer = np.zeros(fe.n_nodes, bool)
    k = 0
    while f"blade{k}" in fe.node_groups:
        ids = fe.node_groups[f"blade{k}"]
        r = np.linalg.norm(x[ids] - np.asarray(turbine.rotor_apex, float), axis=1)
        outer[ids[r >= r.min() + TIP_SPAN * (r.max() - r.min())]] = True
        k += 1
    md = np.asarray(M.diagonal()).reshape(-1, 6)[:, :3].ravel()
    e = md[:, None] * np.abs(np.asarray(shapes).reshape(-1, 6, shapes.shape[1])[:, :3].reshape(-1, shapes.shape[1])) ** 2
    w = np.repeat(outer, 3)
    return e[w].sum(axis=0) / np.maximum(e.sum(axis=0), 1e-300)


def modes(rows, rpms=(0.0, 5.0, 8.0), n=24):
    for label, tb, model in rows:
        t0 = time.time()
        ts = solver(tb, model)
        fe, sections, am = ts.model(0.0)
        ref = ts.reference()
        for rpm in rpms:
            K = am.structural_stiffness(rpm * RPM)
            K, M = (np.asarray(A.toarray() if hasattr(A, "toarray") else A) for A in (K, am.Mr))
            w2, V = symmetric_eigs(0.5 * (K + K.T), 0.5 * (M + M.T))
            f = np.sqrt(np.maximum(w2[:n], 0.0)) / (2 * np.pi)
            shapes = np.asarray(am.TPhi @ V[:, :n]) if am.TPhi is not None else np.asarray(am.structure.T @ V[:, :n])
            names = mode_names(fe, am.structure.M, shapes, f, sections, reference=ref)
            tip = tip_share(fe, am.structure.M, shapes, tb)
            print(f"{label}, {rpm:g} RPM: " + "; ".join(f"{x:.3f} {nm} ({100 * e:.0f} %)"
                                                      for x, nm, e in list(zip(f, names, tip))[::3]), flush=True)
        print(f"  [{time.time() - t0:.0f} s]", flush=True)


def onsets(ts_rows):
    for label, tb, model, extra in ts_rows:
        t0 = time.time()
        p = solver(tb, model, extra).analyse_operating_point(10.0)
        print(f"{label}: flutter {p.flutter_rpm} RPM ({p.flutter_frequency_hz} Hz, {p.flutter_mode}); "
              f"divergence {p.divergence_rpm} RPM  [{time.time() - t0:.0f} s]", flush=True)


def hybrid(t, inner=0.30, outer=0.86):
    """``t`` whose beam takes the shell's section properties (40 stations, the usable ones) between
    ``inner`` and ``outer`` of the span and the thin-walled ones elsewhere: the root transition
    (a 9 m cylinder to a 40 % airfoil within 5 m, where a chord-long extraction window straddles
    the change) and the needle tip (chord 0.12-0.5 m), where the shell's extraction fails or is cut
    off; the same BeamProperties convention for both."""
    import dataclasses

    from windflutter.mesh.section_props import thin_walled_properties
    from windflutter.mesh.shell_beam import usable_stations
    from windflutter.model.turbine import BeamProperties

    tab = shell_beam_table(t, n_stations=40)
    sh = usable_stations(tab) & (tab.s >= inner) & (tab.s <= outer)
    tw = thin_walled_properties(t)
    out = (tw.s < inner) | (tw.s > outer)
    order = np.argsort(np.r_[tab.s[sh], tw.s[out]])
    cat = lambda a, b: np.concatenate([a[sh], b[out]])[order]  # noqa: E731
    bp = BeamProperties(s=cat(tab.s, tw.s), stiffness=cat(tab.beam.stiffness, tw.stiffness),
                        mass=cat(tab.beam.mass, tw.mass), twist=cat(tab.beam.twist, tw.twist), length=tw.length,
                        source=f"shell {inner}-{outer} of the span, thin-walled elsewhere")
    return dataclasses.replace(t, blade=dataclasses.replace(t.blade, beam=bp))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the seed files give no damping (known, warned)
        t = load_turbine("seed20mw")
        if not argv or "props" in argv:
            props(t)
        ts = with_shell_blade_properties(t, 40) if (not argv or {"modes", "onsets"} & set(argv)) else None
        if not argv or "modes" in argv:
            modes((("beam (thin-walled)", t, "beam"), ("beam (shell's properties)", ts, "beam"), ("shell", t, "shell")))
        if "hybrid" in argv:  # not in the default set: one extraction more
            th = hybrid(t)
            modes((("beam (shell's properties 0.30-0.86)", th, "beam"),))
            onsets((("beam (shell's properties 0.30-0.86)", th, "beam", []),))
        if not argv or "onsets" in argv:
            damped = ["--damping", "modal", "--damping-ratio", "0.005"]
            onsets((("beam (shell's properties)", ts, "beam", []), ("beam (thin-walled), 0.5 %", t, "beam", damped),
                    ("beam (shell's properties), 0.5 %", ts, "beam", damped)))


if __name__ == "__main__":
    main()
