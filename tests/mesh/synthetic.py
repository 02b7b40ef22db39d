"""Synthetic turbines built in code (no files): analytic shapes for independent checks."""

from __future__ import annotations

import numpy as np

from windflutter.aero.sections import Polar
from windflutter.model.turbine import (
    Airfoil, BeamProperties, Blade, Hub, IsotropicMaterial, Layer, Layup, Nacelle, Tower, TowerLayer, Turbine, Web,
)

AL = IsotropicMaterial(E=70e9, nu=0.3, rho=2700.0, name="alu")
STEEL = IsotropicMaterial(E=210e9, nu=0.3, rho=7850.0, name="steel")


def ellipse(a_over_c: float, n: int = 181) -> tuple[np.ndarray, np.ndarray]:
    """Unit-chord ellipse (thickness ratio a_over_c), listed TE -> upper -> LE -> lower."""
    th = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return 0.5 + 0.5 * np.cos(th), 0.5 * a_over_c * np.sin(th)


def polar() -> Polar:
    al = np.radians(np.linspace(-180, 180, 73))
    return Polar(al, 2 * np.pi * np.sin(al), 0.01 + np.sin(al) ** 2, np.zeros_like(al), name="flat")


def tube_blade(length=40.0, chord=2.0, thick=1.0, t=0.01, webs=False, beam=None) -> Blade:
    """Straight untwisted blade of constant elliptical (thick=1: circular) section, one isotropic layer."""
    s = np.array([0.0, 1.0])
    layers = [Layer("wall", "alu", s, np.full(2, t), np.zeros(2), np.zeros(2), np.ones(2))]
    wl = []
    if webs:
        wl = [Web("web", s, np.full(2, 0.25), np.full(2, 0.75))]
        layers.append(Layer("web_wall", "alu", s, np.full(2, t), np.zeros(2), np.zeros(2), np.ones(2), web="web"))
    return Blade(
        s=s, ref_axis=np.array([[0.0, 0.0, 0.0], [0.0, 0.0, length]]), arc_length=np.array([0.0, length]),
        chord=np.full(2, chord), twist=np.zeros(2), pitch_axis=np.full(2, 0.5), section_offset_y=np.full(2, 0.5 * chord),
        relative_thickness=np.full(2, thick), airfoil_positions=np.array([0.0, 1.0]), airfoil_names=("ell", "ell"),
        layup=Layup(webs=tuple(wl), layers=tuple(layers)), beam=beam,
    )


def tube_beam_props(length, chord, thick, t, E=70e9, nu=0.3, rho=2700.0, midline=False) -> BeamProperties:
    """Thin-walled elliptical tube (numerical contour integration; Bredt-Batho torsion constant
    ``J = 4 A_enc^2 t / perimeter``), section y = flap, z = edge.  The wall lies on the ellipse
    of the blade's outer surface (as the shell mesh), or with ``midline`` on the ellipse whose
    semi-axes are shorter by ``t/2`` (the wall midline of a wall whose outside is the airfoil; an
    ellipse to O(t^2))."""
    x, y = ellipse(thick, 2001)
    X, Y = (x - 0.5) * chord, y * chord  # X edgewise (to TE), Y flapwise
    if midline:
        ax, ay = 0.5 * chord, 0.5 * thick * chord
        X, Y = X * (ax - 0.5 * t) / ax, Y * (ay - 0.5 * t) / ay
    dl = np.hypot(np.diff(np.append(X, X[0])), np.diff(np.append(Y, Y[0])))
    Xm = 0.5 * (X + np.roll(X, -1))
    Ym = 0.5 * (Y + np.roll(Y, -1))
    A = np.sum(dl) * t
    Iflap = np.sum(Ym**2 * dl) * t  # bending about the edgewise axis (flap motion)
    Iedge = np.sum(Xm**2 * dl) * t
    G = E / (2 * (1 + nu))
    Aenc = 0.5 * abs(np.sum(Xm * np.diff(np.append(Y, Y[0])) - Ym * np.diff(np.append(X, X[0]))))
    J = 4 * Aenc**2 * t / np.sum(dl)
    # section frame (x span, y flap, z edge): bending about y moves the section edgewise and
    # uses the second moment of the edgewise coordinate (Iedge), bending about z uses Iflap.
    K = np.diag([E * A, 0.5 * G * A, 0.5 * G * A, G * J, E * Iedge, E * Iflap])
    M = np.diag([rho * A] * 3 + [rho * (Iflap + Iedge), rho * Iedge, rho * Iflap])
    n = 2
    return BeamProperties(s=np.array([0.0, 1.0]), stiffness=np.repeat(K[None], n, 0), mass=np.repeat(M[None], n, 0),
                          twist=np.zeros(n), length=length, source="synthetic tube")


def synthetic_turbine(blade: Blade | None = None, n_blades: int = 3) -> Turbine:
    blade = blade or tube_blade()
    x, y = ellipse(float(blade.relative_thickness[0]))
    tower = Tower(s=np.array([0.0, 1.0]), z=np.array([0.0, 80.0]), outer_diameter=np.array([6.0, 4.0]),
                  layers=(TowerLayer("wall", "steel", np.array([0.03, 0.02])),))
    hub = Hub(mass=50e3, inertia=np.diag([1e5, 5e4, 5e4]), diameter=3.0, precone=np.radians(2.5))
    nac = Nacelle(mass=240e3, inertia=np.diag([1e6, 1e6, 2.6e6]), cg=np.array([1.9, 0.0, 1.75]), overhang=-5.0,
                  shaft_tilt=np.radians(5.0), tower_to_shaft=2.0)
    ell = Airfoil("ell", x, y, 1.0, polars=(polar(),))
    return Turbine(name="synthetic", n_blades=n_blades, hub_height=82.0, rotor_diameter=2 * 41.5, rated_power=1e6,
                   rated_rotor_speed=1.0, blade=blade, tower=tower, hub=hub, nacelle=nac, airfoils={"ell": ell},
                   materials={"alu": AL, "steel": STEEL})
