"""Convergence of the shell blade's frequencies with the mesh, and the default target element length.

The quantity: the blade's natural frequencies clamped at the root, spinning at the rated rotor speed
(centrifugal stiffening and spin softening: the structural frequencies of the Campbell diagram), the
lowest eight (up to the 1st torsion and past it: the default Campbell range is 1.25 x the 1st torsion).
The reference: the converged value extrapolated from three meshes along the span (Richardson, the
order observed from the three), with 60 elements around a section.  The default mesh
(``MeshSettings()``: the blade length / 80 along the span, 40 around) must be within 3 % of it for
every one of the eight.  Measured (4 Dec 2026, midsurface skin): the slowest is the 1st torsion,
observed order 1.3-1.5 along the span; the frequencies at the default are given in docs/mesh.md.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from windflutter.mesh import MeshSettings, turbine_modes
from windflutter.model import load_turbine

RATED_RPM = {"nrel5mw": 12.1, "iea22mw": 7.06}
N_MODES = 8


def _freqs(tb, rpm, n_modes: int = N_MODES, **kw) -> np.ndarray:
    r = turbine_modes(tb, MeshSettings(model="shell", part="blade", **kw), n_modes=n_modes, rpm=rpm)
    return np.asarray(r.frequencies_hz)


def richardson(f1, f2, f3, r12: float, r23: float):
    """Limit and order of f(n) = f_inf + C n^-p from three meshes with ratios n2/n1 = r12, n3/n2 = r23
    (order by bisection on the ratio of the differences; per mode)."""
    d1, d2 = f1 - f2, f2 - f3
    p = np.empty(len(f1))
    for i in range(len(f1)):
        q = d1[i] / d2[i] if d2[i] != 0 else np.inf
        g = lambda pp: (1 - r12 ** -pp) / (r12 ** -pp * (1 - r23 ** -pp)) - q  # noqa: E731
        lo, hi = 0.2, 6.0
        if not (np.isfinite(q) and q > 0 and g(lo) * g(hi) < 0):
            p[i] = 2.0  # monotone convergence not seen: the quadratic rate (small correction)
            continue
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if g(lo) * g(mid) > 0 else (lo, mid)
        p[i] = 0.5 * (lo + hi)
    return f3 - d2 / (r23 ** p - 1), p


def study(name: str, spans=(80, 120, 160), n_chord: int = 60, **kw):
    """(default-mesh frequencies, extrapolated limit, observed order, the meshes' frequencies)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tb = load_turbine(name)
    rpm = RATED_RPM[name]
    f = [_freqs(tb, rpm, n_span=n, n_chord=n_chord, **kw) for n in spans]
    lim, p = richardson(*f, spans[1] / spans[0], spans[2] / spans[1])
    f0 = _freqs(tb, rpm, **kw)
    return f0, lim, p, f


@pytest.mark.slow
@pytest.mark.parametrize("name", ["nrel5mw", "iea22mw"])
def test_default_shell_mesh_within_3_percent_of_converged(name):
    """Both blades (61.5 m and 138 m): the default mesh within 3 % of the extrapolated limit."""
    f0, lim, p, f = study(name)
    err = f0 / lim - 1
    print(name, "default", np.round(f0, 4), "limit", np.round(lim, 4), "order", np.round(p, 2),
          "error %", np.round(100 * err, 2), "meshes", [np.round(x, 4) for x in f])
    assert np.all(np.abs(err) < 0.03), err


# ------------------------------------------------------------------------------------------------
# the element-length rule and its checks
# ------------------------------------------------------------------------------------------------
def test_counts_follow_the_blade_size_and_given_counts_win(nrel5mw):
    """The default: blade length / SHELL_SPAN_ELEMENTS (100) along the span, 40 around; an element length h gives
    ceil(L / h) along and max(40, even ceil(4 P_max / h)) around; given counts are kept; beams 30."""
    from windflutter.config.declarations import SHELL_SPAN_ELEMENTS
    from windflutter.mesh.settings import max_perimeter

    L = nrel5mw.blade.length
    st = MeshSettings(model="shell").resolved(nrel5mw)
    assert (st.n_span, st.n_chord) == (SHELL_SPAN_ELEMENTS, 40)
    st = MeshSettings(model="shell", element_length=2.0).resolved(nrel5mw)
    assert st.n_span == int(np.ceil(L / 2.0)) == 31 and st.n_chord == 40
    P = max_perimeter(nrel5mw.blade, nrel5mw.airfoils)
    assert 10.0 < P < 12.5  # the 3.5 m root circle (11.0 m) and the 4.65 m chord at 25 % thick (11.3 m, lofted)
    st = MeshSettings(model="shell", element_length=0.5).resolved(nrel5mw)
    assert st.n_span == 123 and st.n_chord == 2 * int(np.ceil(4 * P / 0.5 / 2)) > 40
    st = MeshSettings(model="shell", element_length=0.5, n_span=7, n_chord=12).resolved(nrel5mw)
    assert (st.n_span, st.n_chord) == (7, 12)
    assert MeshSettings(model="beam").resolved(nrel5mw).n_span == 30


@pytest.mark.parametrize("kw, field", [({"element_length": 0.0}, "mesh.element_length"),
                                       ({"element_length": -1.0}, "mesh.element_length"),
                                       ({"element_length": float("nan")}, "mesh.element_length"),
                                       ({"element_length": "1"}, "mesh.element_length"),
                                       ({"reference_surface": "inner"}, "mesh.reference_surface"),
                                       ({"n_span": 1}, "mesh.n_span")])
def test_bad_mesh_settings_are_input_errors(kw, field):
    from windflutter.errors import InputError

    with pytest.raises(InputError) as exc:
        MeshSettings(model="shell", **kw)
    assert exc.value.field == field


def test_element_length_bounds_checked_before_the_mesh(nrel5mw, monkeypatch):
    """Too fine or too coarse a length is refused with the range of lengths that would do, before
    any loft is made (the mesher is not called)."""
    from windflutter.errors import InputError
    from windflutter.mesh import blade_shell, build_model

    monkeypatch.setattr(blade_shell, "_lofted_stations", lambda *a, **k: pytest.fail("meshed"))
    for h in (0.01, 40.0):
        with pytest.raises(InputError) as exc:
            build_model(nrel5mw, MeshSettings(model="shell", part="blade", element_length=h))
        assert exc.value.field == "mesh.element_length" and "0.154 to 15.4 m" in str(exc.value)


def test_config_element_length_and_reference_surface():
    """The config: shells take their span count from the element length (null: L / 100 at density 1),
    beams 30; element_length with a beam model is refused; the reference surface reaches the mesh."""
    from windflutter.config import load_config
    from windflutter.errors import InputError
    from windflutter.methods import mesh_settings

    assert mesh_settings(load_config(None))["n_span"] == 30
    m = mesh_settings(load_config(None, {"model": {"type": "shell"}}))
    assert "n_span" not in m and m["reference_surface"] == "midsurface"
    m = mesh_settings(load_config(None, {"model": {"type": "shell", "element_length": 1.5, "mesh_density": 2.0,
                                                   "reference_surface": "outer"}}))
    assert m["element_length"] == 0.75 and "n_chord" not in m and m["reference_surface"] == "outer"
    assert mesh_settings(load_config(None, {"model": {"type": "shell", "mesh_density": 0.5}}))["n_span"] == 50
    assert mesh_settings(load_config(None, {"model": {"type": "shell", "n_aero_sections": 12}}))["n_span"] == 12
    with pytest.raises(InputError) as exc:
        load_config(None, {"model": {"element_length": 1.0}})
    assert exc.value.field == "model.element_length"


def test_default_shell_mesh_reduced_convergence_check(nrel5mw):
    """The default suite's version of the study: the NREL 5 MW blade at rated, the default mesh
    (100 x 40) against 1.5 times as many elements along the span (150 x 40); the span-converged limit
    by Richardson with order 1, ``f150 + (f150 - f100) / 0.5`` (conservative: the slow study observes 0.9-2.6 for the lowest eight,
    1.4 for the 1st torsion; a lower order extrapolates further).  The six lowest modes (up to the 1st
    torsion, the default Campbell range's top) within 3 % of that limit."""
    rpm = RATED_RPM["nrel5mw"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        f0 = _freqs(nrel5mw, rpm, n_modes=6)
        f2 = _freqs(nrel5mw, rpm, n_modes=6, n_span=150)
    lim = f2 + (f2 - f0) / 0.5
    err = f0 / lim - 1
    print("default", np.round(f0, 4), "150", np.round(f2, 4), "error %", np.round(100 * err, 2))
    assert np.all(np.abs(err) < 0.03), err
