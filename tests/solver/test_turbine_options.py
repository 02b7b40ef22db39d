"""Turbine solver options reach the model: skin distribution, reduction, bad combinations.

The physics of each option is verified where it is implemented (aero/skin.py:
tests/solver/test_skin_aero.py; reduction: tests/perf/); here: the wiring.
"""

import numpy as np
import pytest

from windflutter.errors import InputError
from windflutter.frozen.turbine import TurbineOptions, TurbineStability


def test_bad_combinations_name_the_field():
    with pytest.raises(InputError, match="aero_distribution"):
        TurbineOptions(model="beam", aero_distribution="skin")
    with pytest.raises(InputError, match="reduction"):
        TurbineOptions(reduction="guyan")
    with pytest.raises(InputError, match="damping"):
        TurbineOptions(damping="modal", reduction="none")
    assert TurbineOptions(basis_modes=None).reduction == "none"  # basis_modes=None: full order


def test_skin_distribution_builds_the_seed_sub_strips():
    from windflutter.solve.skin_model import SkinAeroelasticModel, skin_aeroelastic_model
    from windflutter.model import load_turbine

    mesh = {"part": "rotor", "n_chord": 8, "n_span": 4}
    t = load_turbine("nrel5mw")
    spline = TurbineStability(t, TurbineOptions(model="shell", basis_modes=6, mesh=mesh, reduction="modal"))
    skin = TurbineStability(t, TurbineOptions(model="shell", basis_modes=6, mesh=mesh, aero_distribution="skin",
                                              reduction="modal"))
    fe, sec, am = spline.model(0.0)
    fe2, sub, am2 = skin.model(0.0)
    assert isinstance(am2, SkinAeroelasticModel)
    # 2x2 Gauss points on every skin quad: 4 sub-strips per quad, more than the strips
    assert sub.n_sections > 4 * sec.n_sections
    # the same model as built by hand with skin_aeroelastic_model (docs/aero_distribution.md)
    # from the skin model's structure and the spline model's strips (same mesh, same geometry)
    ref = skin_aeroelastic_model(fe2, sec, None, structure=am2.structure, rotor=am2.rotor,
                                 rotor_geometry=am2.rotor_geometry, aero=am2.aero, air_density=am2.air_density,
                                 n_modes=am2.n_modes, omega_ref=am2.omega_ref, pitch=am2.pitch)
    # the bases are the same subspace but not the same vectors (three blades: repeated modes,
    # any rotation within them), so compare basis-invariant quantities: the coupled eigenvalues
    from windflutter.solve.qep import solve_qep_dense

    lam = [np.sort_complex(solve_qep_dense(*m.at(10.0, 1.5).matrices(3.0)).values) for m in (am2, ref)]
    assert np.allclose(lam[0], lam[1], rtol=1e-8)


def test_stability_cli_rejects_skin_on_beams(capsys):
    from windflutter.cli import main

    assert main(["stability", "nrel5mw", "--aero-distribution", "skin"]) == 2
    err = capsys.readouterr().err
    assert "aero_distribution" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_config_reaches_the_turbine_options():
    # every solver / rotor-speed setting of a run config arrives in TurbineOptions
    # (through build.with_span_count: a beam config's null model.n_aero_sections means 30 elements)
    from windflutter.config import config_from_dict
    from windflutter.methods import with_span_count
    from windflutter.frozen.turbine import options_from_config as _from_config

    def options_from_config(c, aero, method):
        return _from_config(with_span_count(c), aero, method)

    c = config_from_dict({"rotor_speed": {"full_sweep": True},
                          "solver": {"correction_tol": 1e-6, "basis_modes": 12, "n_eig": 8, "reduction": "modal",
                                     "mean_loads": False}})
    o = options_from_config(c, "viscous", "pk")
    assert o.mesh["n_span"] == 30
    assert (o.full_sweep, o.correction_tol, o.basis_modes, o.n_eig, o.reduction, o.aero, o.mean_loads) == (
        True, 1e-6, 12, 8, "modal", "viscous", False)
    d = options_from_config(config_from_dict({}), "potential", "pk")
    # the config's defaults: the mean-load terms and the induction on, the files' damping
    assert (d.full_sweep, d.correction_tol, d.mean_loads, d.induction, d.damping) == (False, 1e-8, True, True, "file")
    with pytest.raises(InputError, match="correction_tol"):
        TurbineOptions(correction_tol=0.0)


def test_steady_loads_reach_the_strips_and_need_polars():
    # the option arrives in the model's strips (mean coefficients at the strips' angles of
    # attack); without polars it is a clear error naming the field
    from windflutter.aero.sections import AeroSections
    from windflutter.aero.strip import AeroOptions, OperatingPoint, StripAero
    from windflutter.model import load_turbine
    import scipy.sparse as sp

    ts = TurbineStability(load_turbine("nrel5mw"), TurbineOptions(mean_loads=True, mesh={"n_span": 6}))
    _, _, am = ts.model(0.0)
    st = am.strip(10.0, 1.2)
    assert am.aero.steady_loads and st.steady is not None and np.all(np.isfinite(st.steady))
    assert np.any(st.steady[0] > 0.5) and np.all(st.steady[1] > 0)  # lifting tip, positive drag
    bare = AeroSections(blade=np.array([0]), radius=np.array([1.0]), width=np.array([1.0]), chord=np.array([1.0]),
                        elastic_axis=np.array([0.0]), origin=np.zeros((1, 3)), e_chord=np.array([[1.0, 0, 0]]),
                        e_span=np.array([[0, 1.0, 0]]), airfoil=np.array([0]), polars=[], twist=np.zeros(1),
                        motion_map=sp.identity(6, format="csr"))
    with pytest.raises(InputError, match="polars"):
        StripAero(bare, OperatingPoint(10.0), AeroOptions(steady_loads=True))
