"""Mode animation as a VTK time series (.pvd + frames), read back with meshio."""

from __future__ import annotations

import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from _models import mixed_model  # noqa: E402

from windflutter.errors import InputError  # noqa: E402
from windflutter.post.animation import model_size, peak_translation, write_mode_animation  # noqa: E402


def _frames(pvd: Path):
    root = ET.parse(pvd).getroot()
    assert root.get("type") == "Collection"
    sets = root.find("Collection").findall("DataSet")
    return [float(d.get("timestep")) for d in sets], [meshio.read(pvd.parent / d.get("file")) for d in sets]


def test_real_mode_frames_and_scale(tmp_path):
    fe = mixed_model()
    rng = np.random.default_rng(3)
    mode = rng.standard_normal(fe.n_dof)
    pvd = write_mode_animation(fe, mode, tmp_path / "anim", n_frames=16, fraction=0.1, frequency_hz=2.0)
    assert pvd == tmp_path / "anim" / "mode.pvd"
    times, frames = _frames(pvd)
    assert len(frames) == 16 and len(list((tmp_path / "anim").glob("mode_*.vtu"))) == 16
    # one period of 0.5 s, end point excluded (the loop closes on frame 0)
    np.testing.assert_allclose(times, np.arange(16) * 0.5 / 16, rtol=0, atol=1e-15)
    L = model_size(fe)
    # model size by hand: bounding box from (0,0,0) to (2.7, 0.6, 0.018)
    assert L == pytest.approx(np.sqrt(2.7**2 + 0.6**2 + 0.018**2), rel=1e-14)
    # a real mode peaks at theta = 0: frame 0's largest translation is exactly 10 % of L
    d0 = frames[0].point_data["displacement"]
    assert np.linalg.norm(d0, axis=1).max() == pytest.approx(0.1 * L, rel=1e-12)
    # frame 8 is half a period later: the exact opposite deflection
    np.testing.assert_allclose(frames[8].point_data["displacement"], -d0, atol=1e-15 * L)
    # points are the deformed positions; cells carry the regions
    np.testing.assert_allclose(frames[3].points, fe.nodes + frames[3].point_data["displacement"], atol=1e-15)
    region = np.concatenate([np.asarray(a).ravel() for a in frames[5].cell_data["region_id"]])
    np.testing.assert_array_equal(region[:6], fe.element_regions["shell"])


def test_complex_mode_is_re_phi_exp_iwt(tmp_path):
    fe = mixed_model()
    rng = np.random.default_rng(4)
    phi = rng.standard_normal(fe.n_dof) + 1j * rng.standard_normal(fe.n_dof)
    n = 20
    pvd = write_mode_animation(fe, phi, tmp_path / "f.pvd", n_frames=n, fraction=0.05, align_phase=False)
    times, frames = _frames(pvd)
    assert len(frames) == n and times[-1] == pytest.approx((n - 1) / n)
    s = 0.05 * model_size(fe) / peak_translation(fe, phi).max()
    # quarter period: Re(phi e^{i pi/2}) = -Im(phi)
    np.testing.assert_allclose(frames[n // 4].point_data["displacement"],
                               -s * phi.imag.reshape(-1, 6)[:, :3], rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(frames[n // 4].point_data["rotation"], -s * phi.imag.reshape(-1, 6)[:, 3:],
                               rtol=1e-12, atol=1e-14)
    # sampled maximum lies within [sqrt(cos(2 pi / n)), 1] x the exact cycle maximum (5 % of L)
    top = max(np.linalg.norm(f.point_data["displacement"], axis=1).max() for f in frames)
    assert np.sqrt(np.cos(2 * np.pi / n)) * 0.05 * model_size(fe) <= top <= 0.05 * model_size(fe) * (1 + 1e-12)


def test_peak_translation_matches_dense_sampling():
    """Closed-form cycle maximum vs brute-force sampling of 20001 phases (independent check)."""
    fe = mixed_model()
    rng = np.random.default_rng(5)
    phi = rng.standard_normal(fe.n_dof) + 1j * rng.standard_normal(fe.n_dof)
    th = np.linspace(0, 2 * np.pi, 20001)
    u = phi.reshape(-1, 6)[:, :3]
    brute = np.linalg.norm((u[None] * np.exp(1j * th)[:, None, None]).real, axis=2).max(axis=0)
    # sampling step 3e-4 rad: brute force is below the true maximum by at most ~1e-7 relative
    np.testing.assert_allclose(peak_translation(fe, phi), brute, rtol=1e-7)
    assert np.all(peak_translation(fe, phi) >= brute * (1 - 1e-14))


def test_bad_inputs(tmp_path):
    fe = mixed_model()
    with pytest.raises(InputError, match="mode"):
        write_mode_animation(fe, np.ones(5), tmp_path)
    with pytest.raises(InputError, match="n_frames"):
        write_mode_animation(fe, np.ones(fe.n_dof), tmp_path, n_frames=2)
    with pytest.raises(InputError, match="zero translations"):
        z = np.zeros(fe.n_dof)
        z[3::6] = 1.0  # rotations only
        write_mode_animation(fe, z, tmp_path)
    with pytest.raises(InputError, match="fraction"):
        write_mode_animation(fe, np.ones(fe.n_dof), tmp_path, fraction=-1)


def test_pvd_timesteps_are_plain_numbers_with_numpy_frequency(tmp_path):
    """Frequencies come out of the eigen-solvers as np.float64; the .pvd must still carry plain
    numbers (``timestep="0.125"``, which ParaView parses) and not ``np.float64(0.125)``; every frame
    it lists reads back with meshio."""
    fe = mixed_model()
    mode = np.random.default_rng(5).standard_normal(fe.n_dof)
    pvd = write_mode_animation(fe, mode, tmp_path / "a.pvd", n_frames=8, frequency_hz=np.float64(1.0))
    raw = [d.get("timestep") for d in ET.parse(pvd).getroot().iter("DataSet")]
    assert raw == [repr(k / 8) for k in range(8)]
    assert "np." not in pvd.read_text()
    times, frames = _frames(pvd)
    assert times == [k / 8 for k in range(8)]
    assert all(f.points.shape == (fe.n_nodes, 3) for f in frames)
    with pytest.raises(InputError):
        write_mode_animation(fe, mode, tmp_path / "b.pvd", frequency_hz="fast")
