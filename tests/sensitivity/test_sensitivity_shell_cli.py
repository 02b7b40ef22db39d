"""``windflutter sensitivity --model shell``: the layup regions' ply-thickness derivatives through the
command line and the API (windflutter.sensitivity.shell_results), on the IEA 15 MW shell rotor with a
coarse mesh (6 x 20 skin elements, 12 strips) at 10 m/s, with pyfe3d's one-point transverse shear.  That
coarse blade is not positive definite under its steady stress at 10 m/s with either shear (nor at 12 x
20, 12 x 40 or 20 x 20 elements); the sensitivities' formulas do not depend on it, but their central
differences need well-separated roots: with MITC4's shear two roots are named "blade structure unstable
4" (one derivative not defined), at 12 x 20 elements the rotor-speed root is nearly real and the
differences of a flap root miss by 2 % with either shear.

Reference: central differences (+-1 % of the spar caps' thickness) of the eigenvalues re-solved and
re-named (point_modes) of the point reassembled with the changed layup -- the steady state and the
blade basis held, as the derivative holds them; it shares none of the perturbation formula, the left
vectors or the dataset's conversion to frequency and damping.  Tolerance (issue 31): the frequency
derivative within 1 % or 1e-4 x the frequency, the damping ratio's within 1 % or 1e-4 per unit.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from windflutter.cli import main
from windflutter.errors import InputError

COARSE = ["--n-span", "12", "--mesh-density", "0.5", "--part", "rotor", "--shell-shear", "one-point"]


def _run(argv, capsys):
    rc = main(argv)
    out, err = capsys.readouterr()
    return rc, out, err


def test_default_regions_of_the_iea15mw_layup():
    """The layup's layers grouped by name: spar caps both sides, the TE reinforcement both sides, the
    panels' fillers, the webs; the UV coating is in no region; a wrong region name is refused."""
    from windflutter.api import load_turbine
    from windflutter.sensitivity.shell_results import chosen_regions, default_regions

    t = load_turbine("iea15mw")
    reg = default_regions(t)
    assert reg["spar caps"] == ("Spar_Cap_SS", "Spar_Cap_PS")
    assert reg["TE reinforcement"] == ("TE_reinforcement_SS", "TE_reinforcement_PS")
    assert set(reg["shell panels"]) == {"TE_SS_filler", "LE_SS_filler", "LE_PS_filler", "TE_PS_filler"}
    assert len(reg["webs"]) == 6 and not any("UV" in n for v in reg.values() for n in v)
    assert chosen_regions(t, ["spar caps"]) == {"spar caps": reg["spar caps"]}
    with pytest.raises(InputError) as exc:
        chosen_regions(t, ["spar cap"])
    assert "regions" in str(exc.value) and "spar caps" in str(exc.value)
    with pytest.raises(InputError):
        chosen_regions(t, {"caps": ("Spar_Cap_XX",)})


@pytest.mark.parametrize("extra, flag", [(["--total"], "--total"), (["--onset"], "--onset"),
                                         (["--plot", "x.png"], "--plot")])
def test_shell_refuses_what_it_does_not_give(extra, flag, capsys):
    """One line naming the flag, before any analysis."""
    rc, out, err = _run(["sensitivity", "iea15mw", "--model", "shell", "--wind-speeds", "10"] + extra, capsys)
    assert rc == 2 and len(err.strip().splitlines()) == 1 and flag in err, err


def test_regions_need_a_shell_model(capsys):
    rc, out, err = _run(["sensitivity", "nrel5mw", "--wind-speeds", "10", "--regions", "spar caps"], capsys)
    assert rc == 2 and "--regions" in err and "--model shell" in err, err


def test_spar_caps_table_dataset_and_reference(tmp_path, capsys):
    """The command's table and NetCDF dataset (dimensions, units, the region's layers), its sentence
    the dataset's value for +1 %, and the dataset against the re-solved eigenvalues (module
    docstring)."""
    import xarray as xr

    from sensitivity_checks import mismatches
    from windflutter.api import analysis_config, load_turbine
    from windflutter.operating import campbell_model
    from windflutter.sensitivity import shell
    from windflutter.system.modes import point_modes

    nc = tmp_path / "s.nc"
    rc, out, err = _run(["sensitivity", "iea15mw", "--model", "shell", "--wind-speeds", "10", "--max-hz", "1.2",
                         "--regions", "spar caps", "--out", str(nc), "--top", "20"] + COARSE, capsys)
    assert rc == 0, err
    lines = [ln.strip() for ln in out.splitlines()[1:]]
    assert lines and all(ln.startswith("+1 % ply thickness of the spar caps (Spar_Cap_SS, Spar_Cap_PS)")
                         for ln in lines)
    ds = xr.open_dataset(nc)
    assert dict(ds["ddamping_region"].sizes) == {"mode": len(ds["mode"]), "wind_speed": 1, "region": 1}
    assert ds["ddamping_region"].attrs["units"] == "1" and ds["dfrequency_region"].attrs["units"] == "Hz"
    assert str(ds["region_layers"].values[0]) == "Spar_Cap_SS, Spar_Cap_PS"
    assert ds["wind_speed"].attrs["units"] == "m/s" and bool(ds["defined"].values.all())
    least = str(ds["mode"].values[int(np.nanargmin(ds["damping_ratio"].values[:, 0]))])
    line = next(ln for ln in lines if f"the {least} damping" in ln)
    text = line.split(" by ")[1].split(" points")[0]
    value, decimals = float(text), len(text.split(".")[1]) if "." in text else 0
    # the printed number is the dataset's, rounded to the printed digits (half a unit of the last one)
    assert abs(value - abs(float(ds["ddamping_region"].sel(mode=least).values[0, 0]))) <= 0.5 * 10**-decimals + 1e-12

    cfg = analysis_config(model={"type": "shell", "n_aero_sections": 12, "mesh_density": 0.5, "part": "rotor",
                                 "shell_shear": "one-point"})
    om = campbell_model(load_turbine("iea15mw"), cfg)
    ps = om.at(10.0)
    modes = point_modes(ps, 1.2)
    assert [m.identity_name for m in modes] == [str(n) for n in ds["mode"].values]
    h = shell.LAYER_STEP
    ev = [{m.identity_name: m.eigenvalue for m in point_modes(shell.changed_point(om, ps, ("Spar_Cap_SS",
                                                                                           "Spar_Cap_PS"), s), 1.2)}
          for s in (h, -h)]
    ref = {n: (ev[0][n] - ev[1][n]) / (2 * h) for n in ev[0] if n in ev[1]}
    # the dataset's dzeta and dfreq turned back into dlambda: compare in the tolerance's own terms
    res = SimpleNamespace(modes=modes)
    got = []
    for m in modes:
        lam = complex(m.eigenvalue)
        df = float(ds["dfrequency_region"].sel(mode=m.identity_name).values[0, 0])
        dz = float(ds["ddamping_region"].sel(mode=m.identity_name).values[0, 0])
        a, z = abs(lam), -lam.real / abs(lam)  # lambda = a (-z + i sqrt(1 - z^2))
        da = 2 * np.pi * df
        got.append(da * (-z + 1j * np.sqrt(1 - z * z)) + a * dz * (-1 - 1j * z / np.sqrt(1 - z * z)))
    assert mismatches(res, got, ref, "spar caps (dataset)") == []
