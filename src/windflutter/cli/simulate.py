"""`windflutter simulate TURBINE --rpm R [--wind-speed V] [--duration T] [--part turbine|blade] ...`: a
nonlinear time-domain run of the whole turbine (or one blade on a rigid hub;
:mod:`windflutter.simulate.run`: what is and is not included),
a second implementation beside the eigen-solvers, and the frequency and damping of its modes
identified from the response (matrix pencil, with its residual and half-record spread).
Progress goes to stderr; Ctrl-C keeps the record so far and identifies from it.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

from windflutter.cli.options import Flag, add_flags, command_values
from windflutter.schema import Spec

FLAGS = (
    Flag("--rpm", spec=Spec("float", lower=0.0, upper=200.0, unit="RPM", doc="rotor speed"), metavar="RPM"),
    Flag("--wind-speed", spec=Spec("float", lower=0.0, upper=80.0, unit="m/s", doc="wind speed; 0 = in vacuum"),
         default=0.0, metavar="V"),
    Flag("--pitch", spec=Spec("float", lower=-30.0, upper=90.0, unit="deg", nullable=True,
                              doc="blade pitch (default: the operating curve's at the wind speed)"), metavar="DEG"),
    Flag("--duration", spec=Spec("float", lower=0.0, lower_open=True, upper=3600.0, unit="s",
                                 doc="simulated time"), default=20.0, metavar="T"),
    Flag("--n-span", spec=Spec("int", lower=2, upper=200, doc="blade elements"), default=30, metavar="N"),
    Flag("--f-max", spec=Spec("float", lower=0.0, lower_open=True, upper=200.0, unit="Hz",
                              doc="highest frequency retained (sets the time step: 30 steps per period)"),
         default=8.0, metavar="HZ"),
    Flag("--circulation", spec=Spec("choice", choices=("jones", "rfa"), doc="lag states of C(k)"), default="jones"),
    Flag("--damping", spec=Spec("choice", choices=("none", "file"),
                                doc="structural damping of blades and tower: none, or the turbine files' "
                                    "(--part turbine)"),
         default="none"),
    Flag("--bracket", spec=Spec("float", lower=0.0, lower_open=True, upper=0.5,
                                doc="--confirm-onset: simulate at (1 -+ F) x the onset's rotor speed"),
         default=0.03, metavar="F"),
    Flag("--part", spec=Spec("choice", choices=("turbine", "blade"),
                             doc="the whole turbine (blades, tower, drivetrain) or one blade on a rigid hub"),
         default="turbine"),
)


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simulate", help="nonlinear time-domain run of the turbine; identified damping",
                       description="A nonlinear time-domain run of the whole turbine (co-rotational beam blades "
                                   "on the hub, tower and nacelle, drivetrain; strip aerodynamics with lag states, "
                                   "frozen BEM induction) -- or of one blade on a rigid hub (--part blade) -- a "
                                   "second implementation beside the eigen-solvers; the frequency and damping of "
                                   "its modes up to --f-max identified from the response (ground-fixed: the hub "
                                   "and the blades in multi-blade coordinates). Progress on stderr; Ctrl-C keeps "
                                   "the record so far.")
    p.add_argument("turbine", help="turbine file or bundled name (e.g. nrel5mw)")
    add_flags(p, FLAGS)
    p.add_argument("--kick", metavar="MODE",
                   help="start the whole turbine in method p's mode of this name at the point (e.g. \"1st edge "
                        "BW\"; a small multiple of its shape, its largest translation 1 cm); with --confirm-onset "
                        "'onset' names the unstable mode. Default: unit loads at blade 1's recorded nodes and "
                        "the tower top")
    p.add_argument("--confirm-onset", action="store_true",
                   help="method p's first flutter onset (--damping; --part turbine: the whole "
                        "turbine, --part blade: the rotor on a clamped hub against one blade) at --wind-speed, "
                        "simulated at the operating speed and at 0.97x and 1.03x its rotor speed (--bracket): "
                        "decay/growth beside the eigenvalue's (--rpm not used)")
    p.add_argument("--dynamic-stall", action="store_true",
                   help="Oye's dynamic stall: a separation-point state per strip on the Kirchhoff decomposition "
                        "of its polar (the nonlinear form of method p's solver.dynamic_stall)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--output", metavar="FILE.csv", help="write the recorded response (time, node displacements)")
    p.add_argument("--plot", metavar="FILE.png", help="with --confirm-onset: the tip response at each rotor speed")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    p.set_defaults(func=run)


def _progress(quiet: bool):
    t0 = time.monotonic()

    def show(step, n_steps, t):
        if not quiet:
            print(f"  t = {t:.2f} s ({100 * step / n_steps:.0f} %), {time.monotonic() - t0:.0f} s elapsed",
                  file=sys.stderr, flush=True)

    return show


def run(args: argparse.Namespace) -> int:
    from windflutter.api import load_turbine, simulate  # noqa: PLC0415
    from windflutter.errors import InputError  # noqa: PLC0415
    from windflutter.simulate.run import included  # noqa: PLC0415

    v = command_values(args, FLAGS)
    if args.confirm_onset:
        if args.dynamic_stall:
            raise InputError("--dynamic-stall", True, "not with --confirm-onset (its reference, method p, runs "
                             "without dynamic stall)")
        return _confirm(args, v)
    if v["rpm"] is None:
        raise InputError("--rpm", None, "a rotor speed (RPM)")
    if args.kick is not None and v["part"] != "turbine":
        raise InputError("--kick", args.kick, "no mode kick with --part blade (one blade on a rigid hub)")
    turbine = load_turbine(args.turbine)
    res = simulate(turbine, v["rpm"], v["wind_speed"], duration=v["duration"], pitch_deg=v["pitch"],
                   n_span=v["n_span"], f_max_hz=v["f_max"], circulation=v["circulation"], part=v["part"],
                   damping=v["damping"], kick=args.kick, progress=None if args.json else _progress(args.quiet),
                   dynamic_stall=args.dynamic_stall)
    tr = res.trajectory
    if args.output:
        _write_csv(args.output, res, v["part"])
    modes = [{"frequency_hz": m.frequency_hz, "damping_ratio": m.zeta, "share": m.share,
              "sigma_spread": m.sigma_spread} for m in res.modes if m.frequency_hz <= v["f_max"]]
    if args.json:
        print(json.dumps({"included": included(v["part"], v["damping"], args.dynamic_stall), "part": v["part"], "rpm": v["rpm"],
                          "wind_speed": v["wind_speed"],
                          "simulated_s": float(tr.t[-1]), "interrupted": tr.interrupted,
                          "residual": res.identification.residual, "modes": modes,
                          "kicked": _kicked(res)}))
        return 0
    print(f"{turbine.name}: {v['rpm']:g} rpm, {v['wind_speed']:g} m/s; {included(v['part'], v['damping'], args.dynamic_stall)}")
    print(f"simulated {tr.t[-1]:.2f} s in {tr.wall_time:.0f} s, step {tr.info['dt'] * 1e3:.2f} ms"
          + (" (INTERRUPTED: identified from the partial record)" if tr.interrupted else ""))
    print(f"identification residual {res.identification.residual:.2e} (matrix pencil; spread = growth-rate "
          "difference between the record's halves)")
    kicked = _kicked(res)
    if kicked:
        print(f"started in method p's {kicked['name']} ({kicked['frequency_hz']:.4f} Hz, damping "
              f"{100 * kicked['damping_ratio']:.3f} %); identified nearest: "
              f"{kicked['identified_frequency_hz']:.4f} Hz, "
              f"{100 * kicked['identified_damping_ratio']:.3f} %, share {kicked['identified_share']:.3f}")
    if res.identification.residual > 0.05:
        print("the fit leaves more than 5 % of the response: the modes are not resolved -- simulate longer "
              "(--duration; close pairs such as the tower's fore-aft and side-side need about 60 s)")
    print(f"{'freq (Hz)':>10}  {'damping %':>9}  {'share':>7}  {'spread 1/s':>10}")
    for m in modes:
        if m["share"] >= 1e-3:
            print(f"{m['frequency_hz']:>10.4f}  {100 * m['damping_ratio']:>9.3f}  {m['share']:>7.3f}  "
                  f"{m['sigma_spread']:>10.2e}")
    return 0


def _confirm(args, v) -> int:
    from windflutter.api import load_turbine  # noqa: PLC0415
    from windflutter.errors import InputError  # noqa: PLC0415
    from windflutter.api import confirm_onset  # noqa: PLC0415

    if not v["wind_speed"]:
        raise InputError("--wind-speed", v["wind_speed"], "a positive wind speed with --confirm-onset")
    if args.kick is not None and v["part"] != "turbine":
        raise InputError("--kick", args.kick, "no mode kick with --part blade (one blade on a rigid hub)")
    if args.plot:
        from windflutter.post.simulate_plot import check_png  # noqa: PLC0415

        check_png(args.plot)
    turbine = load_turbine(args.turbine)
    res = confirm_onset(turbine, v["wind_speed"], factors=(1 - v["bracket"], 1 + v["bracket"]), n_span=v["n_span"],
                        duration=v["duration"], f_max_hz=v["f_max"],
                        part="turbine" if v["part"] == "turbine" else "rotor", damping=v["damping"], kick=args.kick,
                        progress=None if args.json else _progress(args.quiet))
    if args.plot:
        from windflutter.post.simulate_plot import plot_onset_check  # noqa: PLC0415

        plot_onset_check(res, args.plot)
    if args.json:
        print(json.dumps({"part": res.part, "wind_speed": res.wind_speed, "onset_rpm": res.onset_rpm, "mode": res.mode,
                          "confirmed": res.confirmed,
                          "checks": [c.summary() for c in res.checks]}))
        return 0
    what = "the whole turbine" if res.part == "turbine" else "rotor on a clamped hub"
    damp = "no structural damping" if v["damping"] == "none" else "the files' structural damping"
    print(f"{turbine.name}, {res.wind_speed:g} m/s, {what}, {damp}: method p's first "
          f"instability {res.mode} at {res.onset_rpm:.2f} RPM (pitch {res.pitch_deg:.2f} deg)")
    fcol = "f (Hz)" if res.part == "turbine" else "f rot (Hz)"
    print(f"{'x onset':>7}  {'RPM':>7}  {fcol:>10}  {'sigma eig':>10}  {'sigma sim':>10}  {'spread':>8}  "
          f"{'zeta eig %':>10}  {'zeta sim %':>10}")
    for c in res.checks:
        print(f"{c.factor:>7.3f}  {c.rpm:>7.3f}  {c.frequency_sim_hz:>10.4f}  {c.sigma_eig:>10.4f}  {c.sigma_sim:>10.4f}  "
              f"{c.sigma_spread:>8.1e}  {100 * c.zeta_eig:>10.3f}  {100 * c.zeta_sim:>10.3f}"
              + ("  (interrupted)" if c.interrupted else ""))
    print("CONFIRMED: decay below, growth above, as the eigenvalues" if res.confirmed
          else "NOT CONFIRMED: the simulation's growth rate has another sign than the eigenvalue's at some speed")
    return 0


def _kicked(res) -> dict | None:
    """The mode the run started in (``--kick``) and the identified mode nearest its eigenvalue."""
    mode = getattr(res, "kicked", None)
    if mode is None:
        return None
    import numpy as np  # noqa: PLC0415

    lam = complex(mode.eigenvalue)
    m = res.nearest(lam)
    return {"name": mode.name, "frequency_hz": abs(lam.imag) / (2 * np.pi), "damping_ratio": -lam.real / abs(lam),
            "identified_frequency_hz": m.frequency_hz, "identified_damping_ratio": m.zeta,
            "identified_share": m.share}


def _write_csv(path: str, res, part: str) -> None:
    from windflutter.errors import InputError  # noqa: PLC0415

    import numpy as np  # noqa: PLC0415

    dofs = ("ux", "uy", "uz", "rx", "ry", "rz")
    names = [f"node{n}_{c}" for n in res.nodes for c in dofs]
    if part == "turbine":  # the hub (ground axes), then each blade's nodes in its own frame
        n_blades = (res.trajectory.y.shape[1] - 6) // len(names)
        names = [f"hub_{c}" for c in dofs] + [f"blade{b + 1}_{x}" for b in range(n_blades) for x in names]
    data = np.column_stack([res.trajectory.t, res.trajectory.y])
    try:
        np.savetxt(path, data, delimiter=",", header="t," + ",".join(names), comments="")
    except OSError as exc:
        raise InputError("--output", path, f"a writable file ({exc.strerror})") from None
