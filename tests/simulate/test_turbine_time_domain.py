"""The whole turbine in the time domain (blades in frames turning with the hub, tower, drivetrain)
against method p's operating-point model.

References, independent of the simulation: method p's eigenvalues of the multi-blade system
(``system.operational``: fixed-interface blades coupled to the support and drivetrain in
multi-blade coordinates, linearized), which shares with the simulation only the model data and
the element and strip definitions; and, for the mass coupling, the blades' mass integrated from
the section data.  The simulation forms no linearized matrix of the turbine: co-rotational beam
blades with their inertial loads at the current configuration, a mass turning with the rotor,
identification by the matrix pencil on the hub's motion and the blades' in multi-blade
coordinates.

Tolerances: frequencies 0.5 % (issue 30's for the rotating blade; the mass models differ at
O(h^2): consistent linear interpolation here, the element's interpolation there); growth rates
by sign at 0.97 and 1.03 x the onset (the issue's bracket) and the damping ratio within 10 %
relative or 0.2 points.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from windflutter.api import load_turbine
from windflutter.simulate.integrator import AlphaScheme, fd_jacobian
from method_p_reference import assert_checks_agree, assert_identified_like, method_p_in_wind
from windflutter.simulate.turbine_run import simulate_turbine, turbine_dynamics


@pytest.fixture(scope="module")
def nrel5mw():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return load_turbine("nrel5mw")


def method_p_structural(turbine, rpm, n_span, max_hz=2.0):
    """Method p's structural modes (no aerodynamics, no damping, full-order blades) at ``rpm``."""
    from windflutter.system.modes import point_modes
    from windflutter.system.operational import OperationalModel, OperationalOptions

    om = OperationalModel(turbine, OperationalOptions(aero=None, damping="none", basis_modes=None,
                                                      mesh={"n_span": n_span}))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return point_modes(om.at(0.0, rpm=rpm, pitch=0.0), max_hz=max_hz)


def test_rotor_mass_on_the_hub(nrel5mw):
    """The hub's rigid motion carries the N blades: the rotor's rigid-body mass at the apex in
    ground axes (the blades' mass turned to each azimuth) has the blades' mass integrated from the
    section data (m(s) ds over the elements) on every translation, at any azimuth, and no
    translation-rotation coupling along the shaft."""
    dyn = turbine_dynamics(nrel5mw, 12.1, 0.0, n_span=6)
    fe = dyn.b.fe
    L = np.diff(np.asarray(dyn.b.base.x)[np.asarray(fe.beam_conn)], axis=1)[:, 0]  # the spinning lengths
    m_el = np.array([np.asarray(fe.beam_sections[k].mass)[0, 0] for k in fe.beam_section])
    blade = float(np.sum(m_el * np.linalg.norm(L, axis=1)))
    assert 15e3 < blade < 20e3  # NREL 5 MW: 17.7 t
    for t in (0.0, 0.4, 1.7):
        Mr = sum(np.kron(np.eye(2), A) @ dyn.MGG @ np.kron(np.eye(2), A.T) for A in dyn.turns(t))
        assert np.allclose(Mr[:3, :3], 3 * blade * np.eye(3), rtol=0, atol=1e-6 * blade)
        assert abs(dyn.n @ Mr[:3, 3:] @ dyn.n) < 1e-6 * blade


def test_files_damping_as_method_p_defines_it(nrel5mw):
    """``damping="file"``: the tower's modal damping on the turbine's tower modes (the rotor lumped
    at the hub: here from the simulation's own blade mass turned to the three azimuths) equals
    method p's support damping; the blades get the files' stiffness-proportional damping."""
    from windflutter.system.operational import OperationalModel, OperationalOptions

    dyn = turbine_dynamics(nrel5mw, 12.1, 0.0, n_span=6, damping="file")
    D = OperationalModel(nrel5mw, OperationalOptions(mesh={"n_span": 6})).support().D
    ns = dyn.g.labels.index("azimuth")
    assert np.abs(dyn.g.C[:ns, :ns] - D).max() < 1e-9 * np.abs(D).max()
    assert dyn.b.damping is not None and dyn.b.damping.nnz > 0
    assert turbine_dynamics(nrel5mw, 12.1, 0.0, n_span=6).b.damping is None


def test_structured_solve_and_rest(nrel5mw):
    """In the wind at its steady state the turbine stays put (the forces vanish at every azimuth);
    the structured solve of a step's iteration matrix equals the dense solve with central
    differences of the whole model's forces."""
    dyn = turbine_dynamics(nrel5mw, 12.0, 10.0, n_span=2)
    q = np.zeros(dyn.nF + dyn.N * dyn.nq)
    z = np.tile(dyn.steady_lags(), dyn.N)
    for t in (0.0, 0.9):
        f, g = dyn.forces(t, q, q, z)
        assert np.abs(f).max() < 1e-6 * np.abs(dyn.preload).max() and np.abs(g).max() < 1e-9
    s, h, t = AlphaScheme(0.9), 1 / 200, 0.9
    Jq, Jv, Jz = fd_jacobian(dyn, t, q, q, z, 1e-7)
    n, m = q.size, z.size
    ca, cz = s.beta * h * h, s.gamma * h
    A = np.zeros((n + m, n + m))
    A[:n, :n] = (1 - s.am) * dyn.mass_at(t) + (1 - s.af) * (ca * Jq[:n] + cz * Jv[:n])
    A[:n, n:] = (1 - s.af) * cz * Jz[:n]
    A[n:, :n] = -(1 - s.af) * (ca * Jq[n:] + cz * Jv[n:])
    A[n:, n:] = (1 - s.am) * np.eye(m) - (1 - s.af) * cz * Jz[n:]
    r = np.random.default_rng(1).normal(size=n + m)
    x = np.linalg.solve(A, r)
    assert np.abs(dyn.iteration_solver(t, s, h)(r) - x).max() < 1e-6 * np.abs(x).max()


def _compare_vacuum(turbine, rpm, n_span, duration, max_hz, f_max_hz=4.0):
    """Every method p structural mode up to ``max_hz`` found in the simulation within 0.5 %."""
    ref = [(m.name, m.frequency_hz) for m in method_p_structural(turbine, rpm, n_span) if m.frequency_hz <= max_hz]
    run = simulate_turbine(turbine, rpm, 0.0, duration=duration, n_span=n_span, f_max_hz=f_max_hz)
    found = np.array([m.frequency_hz for m in run.modes])
    for name, f in ref:
        got = found[np.argmin(np.abs(found - f))]
        assert got == pytest.approx(f, rel=5e-3), (name, got, f)
    return run


def test_short_run(nrel5mw):
    """A short real run (3 elements, 1 s): the hub and blade channels recorded, the Newton
    iteration converging in a few iterations with the structured solve, the multi-blade channels
    (hub 6, collective, cosine and sine of each blade channel) scaled to unit peak."""
    from windflutter.simulate.turbine_run import scaled_channels

    run = simulate_turbine(nrel5mw, 12.1, 0.0, duration=1.0, n_span=3, f_max_hz=3.0,
                           kick_loads=(0, 1, 0, 0, 0, 0), tower_kick=0.0)
    tr = run.trajectory
    assert tr.y.shape[1] == 6 + 3 * 6 * len(run.nodes) and not tr.interrupted
    assert tr.iterations.max() <= 4
    dyn = turbine_dynamics(nrel5mw, 12.1, 0.0, n_span=3)
    ch = scaled_channels(dyn, tr.t, tr.y)
    assert ch.shape[1] <= 6 + 3 * 6 * len(run.nodes) and np.allclose(np.abs(ch).max(axis=0), 1.0)



def test_whole_turbine_edge_damping_short_record(nrel5mw):
    """The reduced operating-damping check of the default suite: NREL 5 MW at 8 m/s (8.97 RPM), 6
    elements, the whole turbine started in method p's 1st edge BW (``kick_mode``), a 6 s record
    (5 periods): the identified mode carries > 0.9 of the response, its growth rate is the same on
    both halves of the record (spread < 1 % of it), its damping ratio within 10 % or 0.2 points of
    method p's and its frequency within 0.5 % (issue 30's band).  Measured: 0.645 % against 0.720 %
    (the 30 s, 10-element runs: 0.650 % against 0.717 %, so the short record costs nothing here),
    0.8800 against 0.8812 Hz, share 0.99, spread 2e-3 of sigma.  4 elements and 4 s are not
    enough (0.31 % against 0.44 %, fit residual 0.09)."""
    ref, rpm, pitch = method_p_in_wind(nrel5mw, 8.0, 6)
    run = simulate_turbine(nrel5mw, rpm, 8.0, pitch_deg=pitch, duration=6.0, n_span=6, f_max_hz=2.5,
                           kick_mode="1st edge BW")
    lam = ref["1st edge BW"]
    m = min(run.modes, key=lambda x: abs(x.lam - lam))
    assert m.share > 0.9 and m.sigma_spread < 1e-2 * abs(m.sigma)
    assert_identified_like(run, ref, ("1st edge BW",))

@pytest.mark.slow
@pytest.mark.parametrize("rpm", [0.0, 12.1])
def test_turbine_frequencies_in_vacuum_fine(nrel5mw, rpm):
    """30 elements, 60 s, at standstill and at the rated 12.1 RPM: every mode up to 1.3 Hz within
    0.5 % -- the 1st tower fore-aft and side-side (0.316 / 0.323 Hz, 2 % apart), the 1st flap
    and edge modes (BW / collective / FW when spinning; the tilt and yaw pairs at standstill)."""
    _compare_vacuum(nrel5mw, rpm, 30, 60.0, 1.3)


@pytest.mark.slow
def test_whole_turbine_onset_bracketed(nrel5mw):
    """NREL 5 MW at 8 m/s, 10 blade elements, no structural damping: method p's first
    instability of the whole turbine (1st edge BW, 14.20 RPM; 16.37 RPM with the files' damping)
    decays at 0.97 x and grows at 1.03 x its rotor speed in the time domain (30 s each).
    Measured: sigma -0.00583 / +0.00554 1/s against -0.00621 / +0.00602 (eigenvalues)."""
    from windflutter.simulate.onset import confirm_onset

    res = confirm_onset(nrel5mw, 8.0, n_span=10, duration=30.0, f_max_hz=6.0, part="turbine", operating=False)
    assert res.mode == "1st edge BW" and 13.5 < res.onset_rpm < 15.0
    assert res.confirmed
    assert_checks_agree(res)


@pytest.mark.slow
@pytest.mark.parametrize("wind", [8.0, 18.0])
def test_whole_turbine_operating_damping(nrel5mw, wind):
    """NREL 5 MW at the operating point (8 m/s: 8.97 RPM; 18 m/s: 12.1 RPM, pitched), 10 blade
    elements, no structural damping, 30 s: the identified damping of the 1st tower fore-aft and
    side-side, the 1st edge BW and FW, the 1st edge collective (with the drivetrain) and the 2nd
    edge BW and FW within 10 % (relative) or 0.2 points of method p's eigenvalues, frequencies
    within 0.5 %.  Measured at 18 m/s: 2nd edge BW zeta 1.224 % against 1.228 %, FW 0.990 %
    against 0.969 %, frequencies 3.4763 / 3.8544 Hz against 3.4755 / 3.8523 Hz."""
    ref, rpm, pitch = method_p_in_wind(nrel5mw, wind, 10)
    run = simulate_turbine(nrel5mw, rpm, wind, pitch_deg=pitch, duration=30.0, n_span=10, f_max_hz=6.0)
    assert run.identification.residual < 1e-2
    names = ["1st tower fore-aft", "1st tower side-side", "1st edge BW", "1st edge FW",
             "1st edge collective + drivetrain", "2nd edge BW", "2nd edge FW"]
    assert_identified_like(run, ref, names)


@pytest.mark.slow
def test_whole_turbine_onset_with_the_files_damping_bracketed(nrel5mw):
    """The onset the analysis reports (``make run``: 1st edge BW at 16.37 RPM with 30 elements and
    the files' structural damping; 16.67 RPM with 10) decays at 0.97 x and grows at 1.03 x in the
    time domain with the same damping (blades: stiffness-proportional on the deflected elements;
    tower: the same modal damping matrix).  Measured (10 elements): sigma -0.00630 / +0.00287 1/s
    against -0.00540 / +0.00477; 30 elements (16.374 RPM): -0.00621 / +0.00436 against
    -0.00583 / +0.00515."""
    from windflutter.simulate.onset import confirm_onset

    res = confirm_onset(nrel5mw, 8.0, n_span=10, duration=30.0, f_max_hz=6.0, part="turbine", damping="file",
                        operating=False)
    assert res.mode == "1st edge BW" and 16.0 < res.onset_rpm < 17.2
    assert res.confirmed
    assert_checks_agree(res)
