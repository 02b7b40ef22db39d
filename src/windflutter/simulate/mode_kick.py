"""The kick of ``windflutter simulate --kick MODE``: the whole turbine started in one of method p's
modes at the same operating point, by its name (``"1st edge BW"``).

Method p's mode is a complex shape ``q`` of its multi-blade system (ground coordinates: support,
azimuth, generator; each blade's coordinates in multi-blade form: collective, cosine, sine)
with eigenvalue ``lambda``.  The simulation starts from the real part of ``a e^{i phi} q
e^{lambda t}`` at ``t = 0`` and its time derivative (the phase ``phi`` makes the real part the
largest): the ground coordinates as they are (the same support model and numbering), blade
``b``'s coordinates ``sum_j C_bj eta_j`` (``C`` the Coleman matrix at azimuth 0) expanded to the
blade's nodal displacements and velocities -- whose time derivative also has the turning of the
azimuth, ``Omega C' eta`` -- and taken onto the simulation's blade coordinates.  The size ``a``
makes the largest translation of a blade or support node ``amplitude`` (m).  The lag states
start at their steady values.

Only the initial condition comes from the eigen-solver: it selects which motion is started, the
identification then finds what the simulation's own equations do with it.  The mode's name and
its eigenvalue are those of :func:`windflutter.system.modes.point_modes` on method p's model of
the point (:func:`method_p_model`).
"""

from __future__ import annotations

import numpy as np

from windflutter.config import load_config
from windflutter.errors import InputError
from windflutter.methods import operational_options
from windflutter.system.modes import point_modes
from windflutter.system.multiblade import coleman_matrix
from windflutter.system.operational import OperationalModel, OperationalOptions
from windflutter.units import RPM

__all__ = ["method_p_config", "method_p_model", "named_mode", "mode_state", "mode_kick"]


def method_p_config(wind_speed: float, n_span: int, part: str = "rotor", damping: str = "none"):
    """The analysis config of method p at one wind speed (``n_span`` strips, viscous strips,
    no structural damping or the files')."""

    return load_config(None, {"wind_speeds": [float(wind_speed)], "method": ["p"], "aero": ["viscous"],
                              "model": {"type": "beam", "part": part, "n_aero_sections": int(n_span)},
                              "damping": {"model": damping}}, overrides_source="confirm_onset")


def method_p_model(turbine, wind_speed: float, n_span: int, part: str = "turbine", damping: str = "none"):
    """Method p's operating-point model (:class:`~windflutter.system.operational.OperationalModel`)
    as :func:`windflutter.simulate.onset.confirm_onset` builds it (``n_span`` blade elements and
    strips, no structural damping or the files'); in vacuum (``wind_speed`` 0) without aerodynamics."""

    if float(wind_speed) == 0.0:
        return OperationalModel(turbine, OperationalOptions(part=part, aero=None, damping=damping,
                                                            mesh={"n_span": int(n_span)}))

    cfg = method_p_config(wind_speed, n_span, part, damping)
    return OperationalModel(turbine, operational_options(cfg, "viscous"))


def named_mode(turbine, name: str, rpm: float, wind_speed: float, pitch_deg: float | None, n_span: int,
               damping: str = "none", max_hz: float = 8.0):
    """``(ps, mode)``: method p's point system at the operating point and its mode named ``name``
    (its ``name`` or its structural identity's); unknown: InputError listing the names there."""

    om = method_p_model(turbine, wind_speed, n_span, "turbine", damping)
    pitch = None if pitch_deg is None else np.radians(float(pitch_deg))
    if pitch is None and wind_speed == 0.0:
        pitch = 0.0
    ps = om.at(float(wind_speed), rpm=float(rpm), pitch=pitch)
    modes = point_modes(ps, max_hz=max_hz)
    key = " ".join(str(name).split()).lower()
    for m in modes:
        if m.name.lower() == key:
            return ps, m
    for m in modes:
        if m.identity_name.lower() == key:
            return ps, m
    names = ", ".join(repr(m.name) for m in modes)
    raise InputError("--kick", name, f"one of method p's modes up to {max_hz:g} Hz at this point: {names}")


def mode_state(ps, mode, blade_T, n_nodes: int, labels) -> tuple[np.ndarray, np.ndarray]:
    """``(q, v)`` complex: the mode's ground coordinates (in the order of ``labels``, the
    simulation's) and blades' coordinates on the simulation's blade basis ``blade_T`` (n_dof, nq;
    a selection of nodal freedoms) -- ``q`` the displacements at t = 0, ``v`` their rates (the
    complex mode; the kick takes the real part)."""
    lam = complex(mode.eigenvalue)
    x = np.asarray(mode.shape, complex)
    mb = ps.mbc
    nF, m, N = mb.n_fixed, mb.n_eta, mb.n_blades
    idx = [list(ps.labels).index(lb) if lb in ps.labels else -1 for lb in labels]
    if min(idx) < 0:
        missing = [lb for lb, i in zip(labels, idx) if i < 0]
        raise InputError("drivetrain", missing, "the same ground coordinates in method p's model")
    qF = x[np.array(idx)]
    eta = x[nF:nF + N * m].reshape(N, m)  # the multi-blade coordinates (collective, cos, sin, ...)

    C, dC, _ = coleman_matrix(N, 0.0)
    eb = C @ eta
    eb_dot = lam * eb + ps.omega * (dC @ eta)
    B = ps.blade.struct.T if ps.Phi is None else ps.blade.struct.T @ ps.Phi
    B = B.toarray() if hasattr(B, "toarray") else np.asarray(B)
    nd = 6 * int(n_nodes)
    if B.shape[0] < nd:
        raise InputError("n_span", n_nodes, "the same blade mesh in method p's model and the simulation")
    Ts = blade_T.toarray() if hasattr(blade_T, "toarray") else np.asarray(blade_T)
    u = B[:nd] @ eb.T  # (nd, N) nodal displacements of each blade (method p's first nodes: the blade's)
    ud = B[:nd] @ eb_dot.T
    qb = np.linalg.lstsq(Ts, u, rcond=None)[0]
    vb = np.linalg.lstsq(Ts, ud, rcond=None)[0]
    q = np.concatenate([qF, qb.T.reshape(-1)])
    v = np.concatenate([lam * qF, vb.T.reshape(-1)])
    return q, v


def mode_kick(dyn, turbine, name: str, wind_speed: float, pitch_deg: float | None, n_span: int,
              amplitude: float = 1e-2, damping: str = "none", max_hz: float = 8.0):
    """``(q0, v0, mode)``: the initial displacements and velocities of the turbine model ``dyn``
    (:class:`~windflutter.simulate.turbine.TurbineDynamics`) in method p's mode ``name`` (module
    docstring), and that :class:`~windflutter.system.modes.ModeRecord`."""
    ps, mode = named_mode(turbine, name, dyn.omega / RPM, wind_speed, pitch_deg, n_span, damping, max_hz)
    q, v = mode_state(ps, mode, dyn.T, dyn.b.fe.n_nodes, dyn.g.labels)
    phase = -0.5 * np.angle(np.sum(q * q))  # the real part of e^{i phase} q is the largest
    q, v = q * np.exp(1j * phase), v * np.exp(1j * phase)
    if q.real[np.argmax(np.abs(q.real))] < 0:  # the sign fixed (the largest component positive), not the
        q, v = -q, -v                          # eigen-solver's: a record's start transient adds to either
    size = _largest_translation(dyn, q.real)
    if not size > 0:
        raise InputError("--kick", name, "a mode with a translation of a blade or support node")
    scale = float(amplitude) / size
    return scale * q.real, scale * v.real, mode


def _largest_translation(dyn, q) -> float:
    """The largest translation (m) of a blade node or of the support's hub motion for ``q``."""
    ns = dyn.g.labels.index("azimuth")
    hub = dyn.g.L[:3, :ns] @ q[:ns]
    ub = [dyn.T @ q[dyn.nF + k * dyn.nq: dyn.nF + (k + 1) * dyn.nq] for k in range(dyn.N)]
    tr = [np.abs(np.asarray(u).reshape(-1, 6)[:, :3]).max() for u in ub]
    return float(max([np.abs(hub).max()] + tr))
