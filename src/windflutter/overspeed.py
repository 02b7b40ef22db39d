"""Flutter and divergence of the whole turbine in multi-blade coordinates (method ``p``).

At a wind speed the blade pitch is the operating curve's and the rotor speed is raised from the
operating rotor speed of that wind speed (the steady operating point; lower speeds are not reached
in steady operation) to ``max_rpm``.  At each rotor speed the turbine is linearized about its
steady state (:class:`~windflutter.system.operational.OperationalModel`) and the eigenvalues of
the first-order system with aerodynamic states are its damped modes -- valid at any damping, so
no frequency matching is needed (the p-method; the seed's p-k and 8-k searches remain as methods
``pk`` and ``thesis`` on the seed's frozen-azimuth model, :mod:`windflutter.frozen.turbine`).

* Modes are named by their structural identity (:mod:`windflutter.system.identity`), each sweep
  point continuing the previous one's (a step where a named mode's frequency jumps is refined once
  through its middle, as along the Campbell), and followed along the rotor speed by their identities
  (the Campbell arrays) and by the MAC of their physical signatures (the root searches).
* Flutter: the first rotor speed where a followed mode's damping ratio turns negative (the
  drivetrain's rigid-body root excluded), located on that mode by :func:`smooth_root`.
* Divergence: the blades' static stiffness in the rotating frame with the aerodynamic stiffness at
  zero frequency (the lag states at their static values) losing positive definiteness: the
  smallest eigenvalue of ``(K + F (-A)^-1 ... )`` changing sign, located by :func:`smooth_root`.

Each trial of a root search is a full operating point (steady state, linearization, blade basis,
eigen-solve: 2.5-3.5 s on the NREL 5 MW shell): :func:`smooth_root` models the smooth function by a
parabola through the bracket and the nearest known sample (the sweep point before the bracket first)
and typically needs two trials where Brent's method took three or more.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
from scipy.optimize import brentq

from windflutter.aero.compressibility import SPEED_OF_SOUND
from windflutter.errors import InputError, ModelError
from windflutter.linalg_tools import mac_matrix
from windflutter.results import Onset, PointSummary
from windflutter.system.blade_aero import static_state_stiffness
from windflutter.system.campbell import CampbellPoint, ambiguous, track_modes
from windflutter.system.modes import point_modes, rotating_frequency, state_eig
from windflutter.system.operational import OperationalModel, lowest_elastic, structural_margin

RPM = math.pi / 30.0
#: root searches: at most this many trial points (each a full operating point)
MAX_TRIALS = 20
#: the flutter search takes the followed mode's damping at the sweep point before its bracket as a
#: sample for its first trial where that point has a mode of at least this MAC with it
KNOWN_MAC = 0.9
#: a mode's frequency in the rotating frame does not change by this factor or more across one sweep
#: step: two modes so far apart are not one mode's two ends, whatever their signatures' MAC (the IEA
#: 22 MW shell's 4.72 Hz edge collective and the 0.009 Hz rotor-speed root, both mostly drivetrain
#: motion: MAC 0.72).  In the rotating frame, so that a backward whirl whose ground-fixed frequency
#: passes near zero (its rotating one near the rotor speed) stays one mode
SAME_MODE_RATIO = 2.0
#: operating points (models and modes) kept by OperationalStability: the bracket of a root search
#: and its last trial points
POINT_CACHE = 6


@dataclass(frozen=True)
class SearchSettings:
    """Rotor-speed sweep of method p: up to ``max_rpm`` (RPM) in steps of ``rpm_step`` from the
    operating rotor speed; onsets to ``tolerance_rpm``; modes up to ``max_hz`` (Hz; None: the
    model's default, :meth:`windflutter.system.reference.StructuralReference.default_max_hz`);
    ``full_sweep`` False stops past both onsets; ``max_tip_mach`` (None: no bound) ends the sweep
    where the tip's speed relative to the wind reaches this Mach number (:func:`tip_mach_rpm`)."""

    max_rpm: float = 40.0
    rpm_step: float = 2.0
    tolerance_rpm: float = 0.01
    max_hz: float | None = None
    full_sweep: bool = False
    max_tip_mach: float | None = None


#: the sweep's first and last steps are at least this fraction of a grid step: a grid point closer
#: above the operating rotor speed is left out, one closer below the sweep's end (:meth:`top_rpm`) is
#: replaced by the end
MIN_STEP = 0.5


def tip_mach_rpm(mach: float, tip_radius: float, wind_speed: float) -> float:
    """The rotor speed (RPM) at which the blade tip's speed relative to the wind,
    ``sqrt((Omega R)^2 + V^2)``, is ``mach`` times the speed of sound (the strips' own relative speeds
    are a few per cent lower there: the fastest strip's centre lies inside ``R``, the tangential
    induction is negative at overspeed).  0 where the wind alone is that fast."""
    w = mach * SPEED_OF_SOUND
    return math.sqrt(max(w * w - wind_speed * wind_speed, 0.0)) / tip_radius / RPM


def blade_static_margin(ps) -> float:
    """Smallest eigenvalue (1/s^2) of the blade's static stiffness over its mass, with the
    aerodynamic states at their static values (``z = -A^-1 (Bq y)``), hub clamped: negative beyond
    static divergence.  ``ps`` is a :class:`~windflutter.system.operational.PointSystem`."""
    bs = ps.blade_system
    return lowest_elastic(bs.K + static_state_stiffness(bs), bs.M)


def blade_structural_margin(ps) -> float:
    """:func:`~windflutter.system.operational.structural_margin` of the point ``ps``: negative, the
    blade's FE structure under its steady stress is statically unstable on its own (a local
    buckling), which is not aeroelastic divergence (the sweep's check; tests replace it here)."""
    return structural_margin(ps)


def _structural_mode_motion(ps) -> np.ndarray | None:
    """(n_nodes,) translation amplitude of the mode of :func:`blade_structural_margin` at the blade's
    nodes; None without a finite eigenvalue, and where the basis's lowest mode is stable but the
    full-order stiffness is not (``ps.blade_negative``: the unstable mode is outside the basis, its
    shape not computed)."""
    M, K = ps.blade_structure
    e = slice(6, None)
    w, V = sla.eig(K[e, e], M[e, e])
    ok = np.flatnonzero(np.isfinite(w))
    if not ok.size:
        return None
    i = ok[np.argmin(w[ok].real)]
    if w[i].real > 0 and getattr(ps, "blade_negative", None):
        return None
    v = np.asarray(ps.blade.basis_full(ps.Phi) @ np.concatenate([np.zeros(6), V[:, i].real])).reshape(-1, 6)
    return np.linalg.norm(v[:, :3], axis=1)


def structural_mode_site(ps) -> str:
    """Where the mode of :func:`blade_structural_margin` lives, in words: ``"largest at r/R = 0.88"``
    and, on a shell blade, the laminate of the shell element that moves most (``", where the shell is
    a 2.2 mm laminate: glass_triax 1.2 mm, Gelcoat 1.0 mm"``): a thin single skin there is a panel
    that buckles under little compression (the layup's, not the solver's)."""
    amp = _structural_mode_motion(ps)
    if amp is None:
        return "(its shape not computed: outside the blade basis's modes)"
    fe = ps.blade.fe
    r = np.linalg.norm(np.asarray(fe.nodes, float) - ps.blade.apex, axis=1)
    text = f"largest at r/R = {r[np.argmax(amp)] / r.max():.2f}"
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    if len(conn):
        p = fe.shell_properties[int(np.asarray(fe.shell_prop)[np.argmax(amp[conn].mean(axis=1))])]
        plies = ", ".join(f"{getattr(x.material, 'name', '') or 'ply'} {1e3 * x.thickness:.1f} mm" for x in p.plies)
        text += f", where the shell is a {1e3 * p.thickness:.1f} mm laminate: {plies}"
    return text


def _unstable_at_operating(ps, wind_speed: float, rpm: float) -> ModelError:
    """The error of a blade structure statically unstable on its own at the operating point: where
    (:func:`structural_mode_site`) and, for a shell blade, what to do."""
    shell = len(ps.blade.fe.shell_conn) > 0
    return ModelError(f"at V = {wind_speed:g} m/s the blade's FE structure under its steady stress is statically "
                      f"unstable at the operating point ({rpm:.2f} RPM) without aerodynamics: a mode "
                      f"{structural_mode_site(ps)} -- a local buckling " +
                      ("(a thin skin panel under compression, or the mesh) is likely; the shell blade cannot be "
                       "linearized about this state (the beam model, --model beam, has no local modes)" if shell
                       else "is likely"))


def _static_image(mode, omega: float, rel: float = 0.05) -> bool:
    """The mode's rotating-frame frequency is (about) zero."""
    return rotating_frequency(mode, omega) < rel * max(omega, 1e-9)


def _model_root(pts: dict, lo: float, hi: float, near: float) -> float:
    """The root in ``[lo, hi]`` of the parabola through ``lo``, ``hi`` and the known point nearest to
    ``near`` (``pts``: x -> f(x)); the secant of ``lo`` and ``hi`` where there is no third point or
    the parabola has no root in the bracket."""
    flo, fhi = pts[lo], pts[hi]
    sec = lo - flo * (hi - lo) / (fhi - flo)
    others = sorted((x for x in pts if x != lo and x != hi), key=lambda x: abs(x - near))
    if not others:
        return sec
    x = np.array([lo, hi, others[0]])
    y = np.array([pts[v] for v in x])
    if not np.all(np.isfinite(y)):
        return sec
    c = np.polyfit(x, y, 2)
    r = np.roots(c) if abs(c[0]) > 1e-300 else np.roots(c[1:])
    r = r[np.isreal(r)].real
    r = r[(r >= lo) & (r <= hi)]
    return float(r[np.argmin(np.abs(r - sec))]) if r.size else sec


def smooth_root(f, lo: tuple, hi: tuple, tol: float, known=()) -> float:
    """A root of ``f`` (smooth: a followed mode's damping ratio, the static margin) between the sweep
    points ``lo = (a, f(a))`` and ``hi = (b, f(b))`` of opposite signs, to ``tol``: each trial is the
    root of the parabola through the bracket and the known point nearest to the last trial (``known``:
    more ``(x, f(x))`` samples, e.g. the sweep point before ``a``; the first trial is the model's
    root), the bracket kept.  It stops at a trial ``x`` when the next model root is within ``tol / 2``
    of it, or when the bracket is narrower than ``tol``, and returns an evaluated point, as Brent's
    method does.  Typically two trials where Brent's method takes three or more (each a full
    operating point: 3 s on the NREL 5 MW shell); :func:`scipy.optimize.brentq` is the reference in
    the tests."""
    (a, fa), (b, fb) = lo, hi
    if fa == 0 or fb == 0:
        return float(a if fa == 0 else b)
    pts = {float(x): float(v) for x, v in known if np.isfinite(v)}
    pts.update({float(a): float(fa), float(b): float(fb)})
    a, b = float(a), float(b)
    last, step, widths = None, None, [b - a]
    for _ in range(MAX_TRIALS):
        s = _model_root(pts, a, b, 0.5 * (a + b) if last is None else last)
        if last is not None:
            if abs(s - last) <= 0.5 * tol:
                return last
            # bisect where the model's steps stop shrinking or the bracket did not halve in three trials
            slow = (step is not None and abs(s - last) > 0.5 * step) or \
                (len(widths) >= 4 and widths[-1] > 0.5 * widths[-4])
            step = None if slow else abs(s - last)
            s = 0.5 * (a + b) if slow else s
        if b - a <= tol:
            return a if abs(pts[a]) < abs(pts[b]) else b
        s = min(max(s, a + 0.25 * tol), b - 0.25 * tol) if np.isfinite(s) else 0.5 * (a + b)
        fs = float(f(s))
        pts[s] = fs
        if fs == 0:
            return s
        if (fs > 0) == (pts[a] > 0):
            a = s
        else:
            b = s
        last = s
        widths.append(b - a)
    return last


def flutter_label(sweep, rpm: float, mode) -> str:
    """The flutter mode's name: the identity it had in operation (the first sweep point, the
    operating rotor speed) and ``" -> "`` the one it has at the onset where the two differ
    (``post.fmt.flutter_label`` reads both).  A mode whose identity at the onset is present at the
    operating rotor speed had it in operation (the sweep points continue their identities); else it is
    followed back from the onset by the MAC of its signature."""
    onset = mode.name  # with its second participation where it is mixed
    first = sweep[0][1] if sweep else []
    if mode.identity is not None and any(m.identity == mode.identity for m in first):
        return onset
    ref, here = mode.signature, mode
    for r, modes in reversed([(r, m) for r, m in sweep if r <= rpm]):
        if not modes:
            continue
        mac = mac_matrix(ref[:, None], np.stack([x.signature for x in modes], 1))[0]
        here = modes[int(np.argmax(mac))]
        ref = here.signature
    start = here.identity_name
    return onset if start == mode.identity_name else f"{start} -> {onset}"


class OperationalStability:
    """Method p on a turbine: :meth:`analyse_operating_point` per wind speed (models cached)."""

    #: the onsets' root searches: ``"smooth"`` (:func:`smooth_root`) or ``"brent"``
    #: (:func:`scipy.optimize.brentq`, the reference of the tests and ``benchmarks/bench_shell_map.py``)
    root_search = "smooth"

    def __init__(self, turbine, options=None, search: SearchSettings | None = None):

        self.turbine = turbine
        self.model = OperationalModel(turbine, options)
        self.search = search or SearchSettings()
        self._max_hz = None
        self._points: OrderedDict = OrderedDict()
        #: keep each wind speed's operating point (:meth:`analyse_operating_point`'s first) as
        #: :attr:`operating`, ``(PointSystem, state_eig)``: the run's Campbell has the same points
        self.keep_operating = False
        self.operating = None

    def max_hz(self, pitch: float) -> float:
        if self.search.max_hz is not None:
            return float(self.search.max_hz)
        if self._max_hz is None:
            self._max_hz = self.model.reference().default_max_hz()
        return self._max_hz

    def pitch_at(self, wind_speed: float) -> float:
        return self.model.operating_point(wind_speed)[1]

    def top_rpm(self, wind_speed: float) -> float:
        """The sweep's end (RPM): ``max_rpm``, or below it where the tip reaches ``max_tip_mach``."""
        s = self.search
        if s.max_tip_mach is None:
            return float(s.max_rpm)
        return min(float(s.max_rpm), tip_mach_rpm(s.max_tip_mach, float(self.turbine.tip_radius), wind_speed))

    def grid(self, wind_speed: float, rpm_grid=None) -> np.ndarray:
        """Rotor speeds (RPM): the operating one, then the multiples of the step above it up to
        :meth:`top_rpm`, which ends it; the first and last steps at least :data:`MIN_STEP` of a step."""
        om_op = self.model.operating_point(wind_speed)[0] / RPM
        if rpm_grid is not None:
            g = np.asarray(rpm_grid, float)
            return np.concatenate([[om_op], g[g > om_op + 1e-9]])
        s, top = self.search, self.top_rpm(wind_speed)
        g = np.arange(s.rpm_step * math.floor(om_op / s.rpm_step + 1), top, s.rpm_step)
        g = g[(g >= om_op + MIN_STEP * s.rpm_step) & (g < top - MIN_STEP * s.rpm_step)]
        return np.concatenate([[om_op], g, [top]]) if top > om_op + 1e-9 else np.array([om_op])

    def _modes(self, wind_speed: float, rpm: float, pitch: float, previous=None, eig=None):
        """``(PointSystem, modes)`` at a rotor speed, the last :data:`POINT_CACHE` kept: the root
        searches start from the two sweep points that bracket a crossing, and the flutter search ends
        on a point it evaluated (a shell point costs 3-5 s).  ``previous``: the modes of the previous
        sweep point, whose identities these continue (:func:`~windflutter.system.modes.point_modes`);
        ``eig``: the point's eigen-solution when already solved."""
        ps, entry = self._point(wind_speed, rpm, pitch)
        if entry[1] is None:
            entry[1] = self._named(ps, pitch, previous, eig)
        return ps, entry[1]

    def _first(self, wind_speed: float, rpm: float, pitch: float):
        """``(PointSystem, modes)`` of a sweep's first point, the operating point; with
        :attr:`keep_operating` its system and eigen-solution are kept as :attr:`operating`
        (``(PointSystem, state_eig)``) for the run's Campbell, which has the same point."""
        if not self.keep_operating:
            return self._modes(wind_speed, rpm, pitch)
        ps = self._point(wind_speed, rpm, pitch)[0]
        self.operating = (ps, state_eig(ps.mbc))
        return self._modes(wind_speed, rpm, pitch, eig=self.operating[1])

    def _named(self, ps, pitch: float, previous=None, eig=None) -> list:
        """The named modes of ``ps`` but the rigid rotation, continuing ``previous``'s names."""
        return [m for m in point_modes(ps, max_hz=self.max_hz(pitch), previous=previous, eig=eig) if not m.rigid]

    def _continued(self, wind_speed: float, pitch: float, before: tuple, rpm: float):
        """``(PointSystem, modes)`` at ``rpm``, continuing the names of the sweep point ``before``
        (``(rpm, modes)``); where a named mode's frequency jumps across the step
        (:func:`~windflutter.system.campbell.ambiguous`) the step is refined once, as along the
        Campbell: the names are carried through its middle (not a sweep point)."""
        ps, entry = self._point(wind_speed, rpm, pitch)
        modes = self._modes(wind_speed, rpm, pitch, previous=before[1])[1]
        if ambiguous(before[1], modes):
            mid = self._named(self.model.at(wind_speed, rpm=0.5 * (before[0] + rpm), pitch=pitch), pitch, before[1])
            modes = entry[1] = self._named(ps, pitch, mid)
        return ps, modes

    def _point(self, wind_speed: float, rpm: float, pitch: float):
        """``(PointSystem, cache entry)`` at a rotor speed; the entry's modes are read on demand (the
        divergence search needs none)."""
        key = (float(wind_speed), float(rpm), float(pitch))
        if key in self._points:
            self._points.move_to_end(key)
        else:
            self._points[key] = [self.model.at(wind_speed, rpm=rpm, pitch=pitch), None]
            while len(self._points) > POINT_CACHE:
                self._points.popitem(last=False)
        entry = self._points[key]
        return entry[0], entry

    def analyse_operating_point(self, wind_speed: float, rpm_grid=None, progress=None) -> PointSummary:
        """Onsets of flutter and divergence above the operating point at ``wind_speed`` (m/s)."""
        if not (np.isfinite(wind_speed) and wind_speed > 0):
            raise InputError("wind_speed", wind_speed, "a positive wind speed (m/s) on the operating curve")
        pitch = self.pitch_at(wind_speed)
        grid = self.grid(wind_speed, rpm_grid)
        self.model.restart_modes()  # the result depends on this wind speed's points only
        self.operating = None
        sweep, margins, structural = [], [], []
        on = Onset(method="p")
        flutter = None
        for i, rpm in enumerate(grid):
            try:
                ps, modes = self._continued(wind_speed, pitch, sweep[-1], rpm) if sweep else \
                    self._first(wind_speed, rpm, pitch)
            except ModelError as exc:  # no steady state (e.g. it diverges at this overspeed)
                if not sweep:
                    raise
                on.reason = f"{exc} [from {rpm:.2f} RPM]"  # onsets below it are not concerned
                break
            struct_margin = blade_structural_margin(ps)
            if i == 0 and struct_margin <= 0:
                raise _unstable_at_operating(ps, wind_speed, rpm)
            if i > 0 and self._structure_lost(ps, (grid[i - 1], structural[-1]), (rpm, struct_margin), on):
                break
            structural.append(struct_margin)
            sweep.append((float(rpm), modes))
            margins.append(blade_static_margin(ps))
            if on.divergence is None and i > 0 and margins[-2] > 0 >= margins[-1]:
                on.divergence = self._locate(lambda r: blade_static_margin(self._point(wind_speed, r, pitch)[0]),
                                             (grid[i - 1], margins[-2]), (rpm, margins[-1]),
                                             [(grid[i - 2], margins[-3])] if i > 1 else [])
            if flutter is None and i > 0:
                flutter = self._flutter(wind_speed, pitch, sweep[-2], sweep[-1], sweep[-3] if i > 1 else None)
            if flutter is not None and on.divergence is not None and not self.search.full_sweep:
                break
            if progress is not None:
                progress((i + 1) / len(grid), f"{rpm:.1f} RPM")
        return self._summary(wind_speed, pitch, sweep, flutter, on)

    # -- pieces ------------------------------------------------------------------------------
    def _structure_lost(self, ps, a: tuple, b: tuple, on: Onset) -> bool:
        """The blade's structure alone turned statically unstable between the sweep points ``a``
        and ``b`` (``(RPM, structural margin)``): the sweep stops there with the reason in ``on``
        (not reported as divergence, which is the aerodynamic stiffness overcoming a stable
        structure).  The rotor speed is interpolated, the margin taken linear in the square of the
        rotor speed (the centrifugal stress's scaling), not searched: a full model per trial
        point cost half of a shell point (NREL 5 MW, 41 of 81 s), for a note."""
        (ra, ma), (rb, mb) = a, b
        if mb > 0:
            return False
        if not np.isfinite(mb):  # a negative eigenvalue outside the basis: where it crossed zero is not known
            on.reason = (f"the blade's FE structure under its steady stress is not positive definite at {rb:.2f} RPM "
                         f"(it was at {ra:.2f}): a mode far above the blade's lowest modes has a negative stiffness "
                         "(a local buckling of the mesh, e.g. a skin panel under compression, is likely): the sweep "
                         f"stops there; this is not aeroelastic divergence [from {ra:.2f} RPM]")
            return True
        where = structural_mode_site(ps)
        r0 = float(np.sqrt(ra**2 + (rb**2 - ra**2) * ma / (ma - mb))) if ma > 0 else float(ra)
        on.reason = (f"the blade's FE structure under its steady stress loses static stability on its own at about "
                     f"{r0:.2f} RPM (between {ra:.2f} and {rb:.2f}; a mode without aerodynamics, {where}; a local "
                     f"buckling of a skin panel or the mesh is likely): the sweep stops there; this is not "
                     f"aeroelastic divergence [from {r0:.2f} RPM]")
        return True

    def _locate(self, f, lo: tuple, hi: tuple, known=()) -> float:
        """The sign change of ``f`` between the sweep points ``lo`` and ``hi`` (``(RPM, f)``), to the
        search's tolerance: :func:`smooth_root` (``known``: earlier samples for its first trial), or
        with :attr:`root_search` ``"brent"`` Brent's method on the bracket (the reference)."""
        tol = self.search.tolerance_rpm
        if self.root_search != "brent":
            return smooth_root(f, lo, hi, tol, known)
        try:
            return float(brentq(f, lo[0], hi[0], xtol=tol))
        except ValueError:
            return float(hi[0])

    def _flutter(self, V: float, pitch: float, prev, cur, earlier=None):
        """``(rpm, mode)`` of the lowest damping sign change between two sweep points, or None;
        ``earlier``: the sweep point before ``prev``, a sample for the root search's first trial.

        A root whose rotating-frame frequency is about zero (a cyclic mode at the rotor speed in the
        ground-fixed frame, a collective one at zero) is the blades' static divergence seen from
        the ground, not flutter: left to the divergence search.  Two modes paired by their
        signatures whose rotating-frame frequencies differ by :data:`SAME_MODE_RATIO` or more are not one
        mode.
        """
        (ra, ma), (rb, mb) = prev, cur
        if not ma or not mb:
            return None
        mac = mac_matrix(np.stack([m.signature for m in ma], 1), np.stack([m.signature for m in mb], 1))
        best = None
        for j, m in enumerate(mb):
            i = int(np.argmax(mac[:, j]))
            if not (m.damping_ratio < 0 <= ma[i].damping_ratio) or _static_image(m, rb * RPM):
                continue
            ratio = rotating_frequency(m, rb * RPM) / max(rotating_frequency(ma[i], ra * RPM), 1e-300)
            if not 1 / SAME_MODE_RATIO < ratio < SAME_MODE_RATIO:  # not the same mode: no crossing of one
                continue
            ref = m.signature

            def follow(r, ref=ref):
                _, mods = self._modes(V, r, pitch)
                k = int(np.argmax(mac_matrix(ref[:, None], np.stack([x.signature for x in mods], 1))[0]))
                return mods[k]

            known = []
            if earlier is not None and earlier[1]:
                me = earlier[1]
                mac_e = mac_matrix(ref[:, None], np.stack([x.signature for x in me], 1))[0]
                if mac_e.max() >= KNOWN_MAC:
                    known = [(earlier[0], me[int(np.argmax(mac_e))].damping_ratio)]
            r0 = self._locate(lambda r: follow(r).damping_ratio, (ra, ma[i].damping_ratio), (rb, m.damping_ratio),
                              known)
            if best is None or r0 < best[0]:
                best = (r0, follow(r0))
        return best

    def _summary(self, V, pitch, sweep, flutter, on: Onset) -> PointSummary:
        """Campbell arrays over the sweep (modes followed by signature MAC) and the onsets."""

        pts = [CampbellPoint(wind_speed=V, rotor_speed_rpm=r, pitch_deg=math.degrees(pitch), modes=m)
               for r, m in sweep]
        tracks = track_modes(pts)
        rpm = np.array([r for r, _ in sweep])
        lam = np.full((len(sweep), len(tracks)), np.nan + 0j)
        for t, tr in enumerate(tracks):
            for i, k in enumerate(tr.index):
                if k >= 0:
                    lam[i, t] = pts[i].modes[k].eigenvalue
        on.params, on.eigenvalues = rpm, lam
        if flutter is not None:
            on.flutter, on.flutter_frequency = flutter[0], float(flutter[1].eigenvalue.imag)
        with np.errstate(invalid="ignore", divide="ignore"):
            zeta = -lam.real / np.abs(lam)
        return PointSummary(wind_speed=float(V), pitch_deg=float(np.degrees(pitch)),
                            flutter_rpm=None if flutter is None else float(flutter[0]),
                            flutter_frequency_hz=None if flutter is None else flutter[1].frequency_hz,
                            flutter_mode=None if flutter is None else flutter_label(sweep, *flutter),
                            divergence_rpm=on.divergence, sweep_rpm=rpm, damped_frequency_hz=np.abs(lam.imag) / (2 * np.pi),
                            damping_ratio=zeta, mode_labels=[t.name for t in tracks], onset=on)
