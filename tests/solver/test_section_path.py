"""A single section on springs through the full FE/strip-aero/p-k path equals the independent
typical-section solver (windflutter.section, written separately from strip.py)."""

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.aero.sections import AeroSections, Polar
from windflutter.aero.strip import AeroOptions
from windflutter.solve.aeroelastic import AeroelasticModel, StructuralMatrices
from windflutter.frozen.search import pk_search
from windflutter.section import TypicalSection, analyse

# Hodges & Pierce (2011) ch. 5 example section: a = -1/5, x_alpha = 0.1, mu = 20, r^2 = 6/25,
# omega_h / omega_alpha = 2/5
B, A, XTH, MU, R2, SIG, RHO = 1.0, -0.2, 0.1, 20.0, 6 / 25, 0.4, 1.0


def _section_model(chord_dir, span_dir, lift_slope=None, model="potential"):
    m = MU * np.pi * RHO * B**2
    Ia = m * R2 * B**2
    e1 = np.cross(chord_dir, span_dir)  # suction-side normal = lift direction for alpha = 0
    # structural DOFs: global translations/rotations of one node; plunge along e1, pitch about
    # e2 = e1 x e3 (nose-up) with e3 = chord direction (flow along the chord)
    e2 = np.cross(e1, chord_dir)
    P = np.zeros((2, 6))
    P[0, :3] = e1
    P[1, 3:] = e2
    Mq = np.array([[m, -m * XTH * B], [-m * XTH * B, Ia]])
    Kq = np.diag([m * SIG**2, Ia])
    # embed in 6 DOFs with unit springs/masses on the other 4 directions (constrained out)
    Q, _ = np.linalg.qr(np.column_stack([P.T, np.eye(6)]))
    T = sp.csr_matrix(P.T)
    M6 = P.T @ Mq @ P
    K6 = P.T @ Kq @ P
    sec = AeroSections(blade=np.array([0]), radius=np.array([1.0]), width=np.array([1.0]),
                       chord=np.array([2 * B]), elastic_axis=np.array([A]), origin=np.zeros((1, 3)),
                       e_chord=np.array([chord_dir], float), e_span=np.array([span_dir], float),
                       airfoil=np.array([0]), polars=[Polar(np.radians([-4.0, 0, 4]), np.array([-0.4, 0, 0.4]),
                                                            np.zeros(3), np.zeros(3))],
                       twist=np.zeros(1), motion_map=sp.identity(6, format="csr"))
    aero = AeroOptions(model=model, lift_slope=lift_slope)
    return AeroelasticModel(StructuralMatrices(sp.csr_matrix(M6), sp.csr_matrix(K6), T), sec, aero=aero,
                            air_density=RHO, n_modes=None), m, Ia


@pytest.mark.parametrize("chord_dir,span_dir", [((1.0, 0, 0), (0, 1.0, 0)),
                                                ((0, 0.6, 0.8), (1.0, 0, 0))])
def test_fe_path_equals_typical_section(chord_dir, span_dir):
    model, m, Ia = _section_model(np.array(chord_dir), np.array(span_dir))
    # flow along the chord: a fixed-wing operating point with the wind along e_chord
    from windflutter.aero.sections import RotorGeometry
    model.rotor_geometry = RotorGeometry(np.zeros(3), np.array([0, 0, 1.0]), np.array(chord_dir, float))
    on = pk_search(lambda U: model.at(U, 0.0), np.arange(0.1, 4.0, 0.1), n_track=2, xtol=1e-8)
    ts = TypicalSection(semi_chord=B, elastic_axis=A, mass=m, static_moment=m * XTH * B, inertia=Ia,
                        plunge_stiffness=m * SIG**2, pitch_stiffness=Ia, air_density=RHO)
    ref = analyse(ts, "pk")
    # both are converged p-k roots of the same equations: agreement to the root-finding tolerance
    assert on.flutter == pytest.approx(ref.flutter_speed, rel=1e-6)
    assert on.flutter_frequency == pytest.approx(ref.flutter_frequency, rel=1e-6)
    # divergence: closed form U_D = sqrt(K_alpha / (2 pi rho b^2 (1/2 + a)))
    assert on.divergence == pytest.approx(np.sqrt(Ia / (2 * np.pi * RHO * B**2 * (0.5 + A))), rel=1e-6)
