"""Design sensitivities of shell blades: the thickness of a region of the layup.

A *region* is one or more layers of the blade's layup (:class:`~windflutter.model.blade.Layer`, by
name: the spar caps ``Spar_Cap_SS`` and ``Spar_Cap_PS``, the trailing-edge reinforcement, a panel's
core, ...).  The parameter ``p`` is relative: every thickness of those layers times ``1 + p`` (the
plies they give every shell element; the blade's outer shape kept).

The layers' plies are not tagged in the FE model (the mesh merges them into laminates), so the
change is made on the turbine's data: the blade is meshed again with the changed layup
(:func:`layered_properties`) and the changed laminates are put on the nominal model's elements --
the undeformed blade's or the point's deflected one (:func:`with_properties`; the same mesh, its
nodes and material axes kept).  The derivative of the shell's assembled mass and stiffness matrices
is a central difference of those assemblies (:func:`matrix_derivatives`), as the beams' element
matrices are differentiated (:mod:`windflutter.sensitivity.point`).

* :func:`standstill_sensitivities`: the clamped blade's own modes at rest,
  ``d omega^2 = x^T (dK - omega^2 dM) x`` (``x`` mass-normalized);
* :func:`layer_derivatives`: the named modes of an operating point, with its steady state held
  (the deflected shape, its stress, inflow and strips): the point reassembled with the changed
  blade on its blade basis at ``p = +-h`` and the central difference of the multi-blade matrices
  contracted with the modes' left and right vectors
  (:func:`~windflutter.sensitivity.eigen.mbc_derivative`).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.sensitivity.eigen import ModeVectors, mbc_derivative
from windflutter.structure.assembly import assemble_matrices
from windflutter.structure.modal import symmetric_eigs
from windflutter.system.blade import RotorBlade
from windflutter.system.operational import OperationalModel

#: the relative step of the layers' thickness (the mesh merges laminates closer than 1e-6 m: a
#: step well above that)
LAYER_STEP = 1e-2


def layer_names(turbine) -> list[str]:
    """The names of the blade's layup layers (the regions a sensitivity can be asked for)."""
    layup = getattr(turbine.blade, "layup", None)
    return [] if layup is None else [lay.name for lay in layup.layers]


def _checked(turbine, layers) -> tuple[str, ...]:
    names = layer_names(turbine)
    if not names:
        raise InputError("blade.layup", None, "a blade with a composite layup (a shell blade's regions)")
    out = (layers,) if isinstance(layers, str) else tuple(layers)
    bad = [n for n in out if n not in names]
    if bad or not out:
        raise InputError("layers", bad[0] if bad else out, f"layer names of the layup: {', '.join(names)}")
    return out


def layer_thickness_check(turbine, layers) -> tuple[str, ...]:
    """The layer names ``layers`` checked against the turbine's layup (InputError naming ``layers``)."""
    return _checked(turbine, layers)


def layer_thickness(turbine, layers, p: float):
    """``turbine`` with the thickness of the layup layers ``layers`` (names) times ``1 + p``."""
    chosen = set(_checked(turbine, layers))
    lay = turbine.blade.layup
    new = tuple(dataclasses.replace(x, thickness=np.asarray(x.thickness, float) * (1.0 + p)) if x.name in chosen
                else x for x in lay.layers)
    blade = dataclasses.replace(turbine.blade, layup=dataclasses.replace(lay, layers=new))
    return dataclasses.replace(turbine, blade=blade)


def layered_properties(om, layers, p: float) -> tuple[np.ndarray, list]:
    """``(shell_prop, shell_properties)`` of the blade of ``om``'s turbine with the layers' thickness
    times ``1 + p``, meshed again (the same mesh settings: the same elements)."""
    fe = OperationalModel(layer_thickness(om.turbine, layers, p), om.options).blade(0.0).fe
    return np.asarray(fe.shell_prop), list(fe.shell_properties)


def with_properties(fe, properties: tuple[np.ndarray, list]):
    """``fe`` (the undeformed or the deflected blade) with the laminates ``properties``
    (:func:`layered_properties`) on its elements."""
    prop, props = properties
    if len(prop) != len(fe.shell_conn):
        raise InputError("shell_prop", len(prop), f"{len(fe.shell_conn)} shell elements (the same mesh)")
    return dataclasses.replace(fe, shell_prop=prop, shell_properties=props)


def matrix_derivatives(fe, om, layers, h: float = LAYER_STEP) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """``(dM/dp, dK/dp)`` (full numbering) of the shell model ``fe`` (the blade of ``om``, undeformed or
    deflected) for the layers' relative thickness: central differences of the assembled matrices."""
    (Mp, Kp), (Mm, Km) = (assemble_matrices(with_properties(fe, layered_properties(om, layers, s))) for s in (h, -h))
    return sp.csr_matrix((Mp - Mm) / (2 * h)), sp.csr_matrix((Kp - Km) / (2 * h))


def standstill_sensitivities(om, layers, n_modes: int = 6, h: float = LAYER_STEP) -> tuple[np.ndarray, np.ndarray]:
    """``(f, df/dp)`` (Hz) of the ``n_modes`` lowest modes of the blade of ``om`` clamped at its root, at
    rest, for the layers' relative thickness (``d omega^2 = x^T (dK - omega^2 dM) x``)."""
    rb = om.blade(0.0)
    T = rb.struct.T
    dM, dK = matrix_derivatives(rb.fe, om, layers, h)
    w2, X = clamped_modes(rb.struct.K, rb.struct.M, T, n_modes)
    dMr, dKr = (T.T @ dM @ T), (T.T @ dK @ T)
    dw2 = np.einsum("im,im->m", X, dKr @ X) - w2 * np.einsum("im,im->m", X, dMr @ X)
    w = np.sqrt(w2)
    return w / (2 * np.pi), dw2 / (2 * w) / (2 * np.pi)


def clamped_modes(K, M, T, n_modes: int) -> tuple[np.ndarray, np.ndarray]:
    """``(omega^2, X)`` of the ``n_modes`` lowest modes of ``K x = omega^2 M x`` on the free DOFs
    ``T`` (shift-invert Lanczos from a fixed start: the shell's drilling rotations have no mass),
    ``X`` mass-normalized."""
    Kr, Mr = sp.csc_matrix(T.T @ K @ T), sp.csc_matrix(T.T @ M @ T)
    w2, X = symmetric_eigs(Kr, Mr, n_modes, shift=0.0, v0=np.ones(Kr.shape[0]))
    X = X / np.sqrt(np.einsum("im,im->m", X, Mr @ X))
    return w2, X


def changed_shell_blade(om, ps, layers, s: float) -> RotorBlade:
    """The point's (deflected) shell blade with the layers' thickness times ``1 + s``: the changed
    laminates on its elements; its stiffness and mass the nominal ones plus the change of the assembled
    elastic stiffness and mass (the initial stress held; the nominal deflected blade's elements are
    its undeformed ones carried with their rotations, the change is that of pyfe3d's elements on the
    deflected nodes: equal to the order of the strains), its structural damping held (the modal damping of the
    point's blade modes, :func:`windflutter.system.damping.shell_modal_damping`)."""
    rb = ps.blade
    fe2 = with_properties(rb.fe, layered_properties(om, layers, s))
    M0, K0 = assemble_matrices(rb.fe)
    M2, K2 = assemble_matrices(fe2)
    st = dataclasses.replace(rb.struct, fe=fe2, M=(rb.struct.M + (M2 - M0)).tocsr(), K=(rb.struct.K + (K2 - K0)).tocsr())
    return RotorBlade(fe2, st, rb.sections, rb.apex, rb.axis, damping=rb.damping)


def changed_point(om, ps, layers, s: float, Phi="nominal"):
    """The point ``ps`` with the layers' thickness times ``1 + s`` (:func:`changed_shell_blade`), the
    steady state held; ``Phi`` the blade basis (default the point's; None: recomputed)."""
    return om.assemble_point(changed_shell_blade(om, ps, layers, s), ps.steady, ps.ksigma, ps.klink, ps.wind_speed,
                             ps.omega, ps.pitch, tip_frame=ps.tip_frame, Phi=ps.Phi if isinstance(Phi, str) else Phi)


def layer_derivatives(om, ps, mvs: list[ModeVectors], regions: dict, h: float = LAYER_STEP) -> dict:
    """``{region: (k,) dlambda/dp}`` of the modes ``mvs`` of the shell point ``ps`` for each region
    ``{name: layer names}`` (relative thickness), the steady state held (module docstring)."""
    if not len(ps.blade.fe.shell_conn):
        raise InputError("model", "beam", "a shell blade (the layup's regions)")
    out = {}
    for name, layers in regions.items():
        plus, minus = (changed_point(om, ps, layers, s).mbc for s in (h, -h))
        out[name] = np.array([mbc_derivative(mv, plus, minus, h) for mv in mvs])
    return out
