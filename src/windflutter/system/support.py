"""The ground-fixed part of a turbine for the multi-blade system: support structure, hub mass,
drivetrain.

* Support: tower, nacelle and yaw bearing with a massless hub node tied to the tower top
  (``MeshSettings(part="support")``), in its constrained coordinates (beam towers) or on a basis of
  its modes with the rotor mass lumped at the hub plus the six static responses to hub loads
  (shell towers).  ``None`` for a rotor on a fixed nacelle (HAWCStab2's / OpenFAST's rotor-only
  analyses).
* Hub: a rigid body at the apex moving with the hub motion the rotor sees, ``h_R = L x_F``; its
  rotation about the shaft includes the rotor azimuth ``phi``.
* Drivetrain (docs/campbell.md, "The model", hub and drivetrain): ``phi`` (rotor azimuth
  relative to the nacelle) and the generator rotation ``theta_g`` relative to the nacelle seen on
  the low-speed side, a shaft spring ``k`` and damper ``c`` between them and the generator inertia
  ``n^2 J_gen`` (absolute rotation ``n . theta_nacelle + theta_g``); ``rigid``: one azimuth
  coordinate carries the generator too; ``locked``: no azimuth freedom (the rotor locked to the
  nacelle, as the seed's model).  With a free generator (no controller) the drivetrain has one
  rigid-body mode (lambda = 0).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.errors import InputError
from windflutter.system.multiblade import FixedFrame


@dataclass(frozen=True)
class Drivetrain:
    """Shaft torsion and generator inertia, low-speed side (SI).

    stiffness : N m/rad (``inf``: rigid shaft).  damping : N m s/rad.
    generator_inertia : kg m^2 on the LOW-speed side (``gear_ratio^2 J_gen``).
    mode : ``"flexible"``, ``"rigid"`` or ``"locked"``.
    """

    stiffness: float = float("inf")
    damping: float = 0.0
    generator_inertia: float = 0.0
    mode: str = "flexible"

    def __post_init__(self):
        if self.mode not in ("flexible", "rigid", "locked"):
            raise InputError("drivetrain", self.mode, "'flexible', 'rigid' or 'locked'")
        for name in ("damping", "generator_inertia"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v >= 0):
                raise InputError(f"drivetrain.{name}", v, "a finite non-negative value")
        if not (self.stiffness > 0):
            raise InputError("drivetrain.stiffness", self.stiffness, "a positive stiffness (N m/rad) or inf")

    @property
    def effective_mode(self) -> str:
        """``flexible`` becomes ``rigid`` for an infinite shaft stiffness or no generator inertia."""
        if self.mode == "flexible" and (not np.isfinite(self.stiffness) or self.generator_inertia <= 0):
            return "rigid"
        return self.mode

    @staticmethod
    def from_turbine(turbine, mode: str = "flexible") -> "Drivetrain":
        nac = turbine.nacelle
        n = float(nac.gear_ratio)
        return Drivetrain(stiffness=float(nac.drivetrain_torsional_stiffness),
                          damping=float(getattr(nac, "drivetrain_torsional_damping", 0.0) or 0.0),
                          generator_inertia=n * n * float(nac.generator_inertia), mode=mode)


def rigid_body_mass(mass: float, inertia: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """(6, 6) mass matrix of a rigid body at a reference point: ``[[m I, -m [c]], [m [c], I_c - m [c]^2]]``
    for the motion ``(translation, rotation)`` of the point, CG at ``offset`` (m), ``inertia``
    about the CG (kg m^2)."""
    c = np.asarray(offset, float)
    S = np.array([[0.0, -c[2], c[1]], [c[2], 0.0, -c[0]], [-c[1], c[0], 0.0]])
    Mr = np.zeros((6, 6))
    Mr[:3, :3] = mass * np.eye(3)
    Mr[:3, 3:] = -mass * S
    Mr[3:, :3] = mass * S
    Mr[3:, 3:] = np.asarray(inertia, float) - mass * S @ S
    return Mr


@dataclass
class SupportModel:
    """Support matrices in their coordinates and the map to the hub node's 6 DOFs.

    M, K, D : (ns, ns) dense; H : (6, ns) hub motion; expand : (n_dof, ns) to the FE numbering;
    fe, struct : the support model.
    """

    M: np.ndarray
    K: np.ndarray
    D: np.ndarray
    H: np.ndarray
    expand: object
    fe: object = None
    struct: object = None


def support_model(fe, struct, damping=None, basis: np.ndarray | None = None) -> SupportModel:
    """The support in its constrained coordinates, or projected on ``basis`` (nq, k)."""
    hub = int(fe.node_groups["hub"][0])
    T = struct.T
    E = T if basis is None else T @ basis
    H = E[6 * hub: 6 * hub + 6]
    H = H.toarray() if hasattr(H, "toarray") else np.asarray(H)

    def proj(A):
        out = E.T @ (A @ E)
        return out.toarray() if hasattr(out, "toarray") else np.asarray(out)

    D = proj(damping) if damping is not None else np.zeros((E.shape[1], E.shape[1]))
    return SupportModel(M=proj(struct.M), K=proj(struct.K), D=D, H=H, expand=E, fe=fe, struct=struct)


def fixed_frame(support: SupportModel | None, hub_mass: np.ndarray, axis, drivetrain: Drivetrain) -> FixedFrame:
    """The :class:`FixedFrame` of support + hub rigid body (6x6 ``hub_mass`` at the apex) + drivetrain."""
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    ns = 0 if support is None else support.M.shape[0]
    mode = drivetrain.effective_mode
    nd = {"locked": 0, "rigid": 1, "flexible": 2}[mode]
    nF = ns + nd
    M = np.zeros((nF, nF))
    C = np.zeros((nF, nF))
    K = np.zeros((nF, nF))
    L = np.zeros((6, nF))
    labels = [f"support:{i}" for i in range(ns)]
    if support is not None:
        M[:ns, :ns] = support.M
        K[:ns, :ns] = support.K
        C[:ns, :ns] = support.D
        L[:, :ns] = support.H
    if nd:
        L[3:, ns] = n  # rotor azimuth about the shaft
        labels.append("azimuth")
    M += L.T @ hub_mass @ L
    if nd:
        g = np.zeros(nF)  # absolute generator rotation
        g[:ns] = n @ L[3:, :ns]
        g[ns + nd - 1] = 1.0
        M += drivetrain.generator_inertia * np.outer(g, g)
    if nd == 2:
        labels.append("generator")
        d = np.zeros(nF)
        d[ns], d[ns + 1] = 1.0, -1.0
        K += drivetrain.stiffness * np.outer(d, d)
        C += drivetrain.damping * np.outer(d, d)
    return FixedFrame(M=M, C=C, K=K, L=L, labels=labels)
