"""The coupled aeroelastic system on a (modally) reduced basis.

``Mt = Ms - Ma``, ``Dt = Ds + G - Da``, ``Kt = Ks - Kr + Ksigma - Ka`` (docs/stability.md, "Pipeline
(modules)", coupled system), first
reduced by the constraint map ``u = T q`` and then, by default, projected on a basis of
structural modes (Galerkin, exact for the terms that live in that subspace): the union of the
modes at rotor speed 0 and at the top of the analysed range, M-orthonormalized.  The projection
keeps every p-k solve a small dense problem; ``n_modes=None`` keeps the full constrained
system (sparse shift-invert Arnoldi for large models).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from windflutter.aero.compressibility import warn_compressible
from windflutter.aero.induction import sections_induction, warn_outside_momentum_theory
from windflutter.aero.sections import AeroSections, RotorGeometry
from windflutter.aero.strip import AeroOptions, OperatingPoint, StripAero, lift_drag_slopes
from windflutter.errors import InputError, ModelError
from windflutter.rotor.rotating import RotorTerms
from windflutter.solve.qep import qep_pencil
from windflutter.solve.reduction import structural_modes as lanczos_modes
from windflutter.structure.modal import m_orthonormalize, symmetric_eigs


@dataclass
class StructuralMatrices:
    """Structural matrices in the unconstrained numbering (n_dof) and the constraint map.

    M, K, D : (n_dof, n_dof) sparse (kg, N/m, N s/m); D may be None.
    T : (n_dof, n_red) sparse, ``u = T q``.
    """

    M: sp.csr_matrix
    K: sp.csr_matrix
    T: sp.csr_matrix
    D: sp.csr_matrix | None = None

    @staticmethod
    def from_structural(struct) -> "StructuralMatrices":
        """Adapter for the structural engineer's ``Structural`` (attributes M, K, T, optional D)."""
        D = getattr(struct, "D", None)
        return StructuralMatrices(M=sp.csr_matrix(struct.M), K=sp.csr_matrix(struct.K), T=sp.csr_matrix(struct.T),
                                  D=None if D is None else sp.csr_matrix(D))

    def reduce(self, A):
        return (self.T.T @ A @ self.T).tocsr() if sp.issparse(A) else self.T.T @ A @ self.T


def structural_modes(K, M, n: int, shift: float = -1.0):
    """Lowest ``n`` eigenpairs ``(w^2, V)`` of the symmetric pencil (K, M); dense for small problems.

    Large problems: shift-invert Lanczos of :func:`windflutter.solve.reduction.structural_modes`
    (the project's sparse LU, a fixed start vector; ``w^2`` clipped at 0 there).  NREL 5 MW
    shell (26k DOF), 30 modes at 2 rotor speeds: 37 s against 83 s with SciPy's default
    ``splu`` inside ``eigsh``.
    """
    nn = K.shape[0]
    if nn <= 800 or n >= nn - 1:
        Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M)
        w, V = symmetric_eigs(Kd, Md)
        return w[:n], V[:, :n]

    b = lanczos_modes(M, K, n, shift=shift, dense_below=0)
    return b.omega**2, b.Phi


@dataclass
class AeroelasticModel:
    """Everything needed to form the coupled matrices at (V, Omega, omega).

    Parameters
    ----------
    structure : structural matrices and constraint map.
    sections : aerodynamic strips (``motion_map`` in the unconstrained numbering).
    rotor : rotating-frame terms per unit speed (None for a fixed wing).
    rotor_geometry : hub centre, shaft axis, wind direction (None for a fixed wing).
    aero : aerodynamic options.
    air_density : kg/m^3.
    n_modes : modes per reference speed in the projection basis, None = no projection.
    omega_ref : rotor speeds (rad/s) whose structural modes build the basis.
    pitch : blade pitch reported with the operating point (rad).
    induction : steady BEM axial and tangential induction in the inflow
        (:mod:`windflutter.aero.induction`): :meth:`at` solves it at each (V, Omega) (cached) and
        the strips see ``U = sqrt((V (1 - a))^2 + (Omega r (1 + a'))^2)``; frozen in the linear
        problem (quasi-steady, no dynamic inflow).  False (default): the thesis's
        ``U = sqrt(V^2 + (Omega r)^2)``.
    high_thrust : the BEM's thrust--induction relation (:mod:`windflutter.aero.momentum`).
    n_blades : blades of the rotor for the BEM (None: the blades present in ``sections``).
    """

    structure: StructuralMatrices
    sections: AeroSections
    rotor: RotorTerms | None = None
    rotor_geometry: RotorGeometry | None = None
    aero: AeroOptions = field(default_factory=AeroOptions)
    air_density: float = 1.225
    n_modes: int | None = 30
    omega_ref: tuple[float, ...] = (0.0,)
    pitch: float = 0.0
    induction: bool = False
    high_thrust: str = "buhl"
    n_blades: int | None = None

    def __post_init__(self):
        self._induction_cache: dict = {}
        if not isinstance(self.induction, (bool, np.bool_)):
            raise InputError("induction", self.induction, "true or false")
        if self.induction and self.rotor_geometry is None:
            raise InputError("induction", True, "a rotor (rotor_geometry) for the BEM induction")
        if self.aero.model == "viscous" and (self.aero.lift_slope is None or self.aero.drag_slope is None):
            # fit the polars once (not at every operating point)
            from dataclasses import replace

            cla, cda = lift_drag_slopes(self.sections, self.aero)
            self.aero = replace(self.aero, lift_slope=cla, drag_slope=cda)
        s = self.structure
        self.Mr = s.reduce(s.M)
        self.Kr0 = s.reduce(s.K)
        n = self.Mr.shape[0]
        self.Dr = s.reduce(s.D) if s.D is not None else sp.csr_matrix((n, n))
        if self.rotor is not None:
            self.G1 = s.reduce(self.rotor.G1)
            self.Kr1 = s.reduce(self.rotor.Kr1)
            self.Ks1 = s.reduce(self.rotor.Ksigma1) if self.rotor.Ksigma1 is not None else sp.csr_matrix((n, n))
        else:
            self.G1 = self.Kr1 = self.Ks1 = sp.csr_matrix((n, n))
        self.Phi = None
        if self.n_modes is not None and self.n_modes < n:
            self.Phi = self._basis()
            P = self.Phi
            self.Mr, self.Kr0, self.Dr, self.G1, self.Kr1, self.Ks1 = (
                P.T @ (A @ P) for A in (self.Mr, self.Kr0, self.Dr, self.G1, self.Kr1, self.Ks1))
            self.TPhi = self.structure.T @ P
        else:
            self.TPhi = None

    def add_modal_damping(self, zeta: float) -> None:
        """Add ``2 zeta omega_j`` damping to every non-rotating structural mode of the basis.

        ``D += (M V) diag(2 zeta omega) (M V)^T`` with ``V`` the M-orthonormal eigenvectors of the
        projected (K(Omega=0), M); the projected basis is required (a dense n x n matrix on the
        full model would not fit in memory for shell models).
        """
        if self.Phi is None:
            raise InputError("damping", "modal", "a projected model (n_modes set) for modal damping")
        if not (np.isfinite(zeta) and 0 <= zeta < 1):
            raise InputError("damping.ratio", zeta, "a damping ratio in [0, 1)")
        K0, M = np.asarray(self.Kr0), np.asarray(self.Mr)
        w2, V = symmetric_eigs(K0, M)
        MV = M @ V
        self.Dr = self.Dr + MV @ np.diag(2.0 * zeta * np.sqrt(np.maximum(w2, 0.0))) @ MV.T

    def add_low_rank_damping(self, U, c) -> None:
        """Add the damping ``U diag(c) U^T`` (``U`` (n_dof, k) in the unconstrained numbering, N s/m)
        in the working basis: ``W diag(c) W^T``, ``W = Phi^T T^T U`` -- the same as projecting it with
        the structure's ``D``.  The projected basis is required (as :meth:`add_modal_damping`)."""
        if self.Phi is None:
            raise InputError("reduction", "none", "a projected model (n_modes set) for the shell blades' modal "
                             "damping (a dense n x n matrix on the full model)")
        W = self.Phi.T @ np.asarray(self.structure.T.T @ np.asarray(U, float))
        self.Dr = self.Dr + (W * np.asarray(c, float)[None, :]) @ W.T

    @property
    def size(self) -> int:
        return self.Mr.shape[0]

    def structural_stiffness(self, omega_rot: float):
        """``Ks - Kr(Omega) + Ksigma(Omega)`` in the working basis."""
        return self.Kr0 - omega_rot**2 * self.Kr1 + omega_rot**2 * self.Ks1

    def structural_damping(self, omega_rot: float):
        return self.Dr + omega_rot * self.G1

    def _basis(self) -> np.ndarray:
        vecs = []
        for om in self.omega_ref:
            K = self.Kr0 - om**2 * self.Kr1 + om**2 * self.Ks1
            _, V = structural_modes(K, self.Mr, self.n_modes)
            vecs.append(V)
        V = np.hstack(vecs)
        if len(vecs) > 1:  # M-orthonormalize, dropping dependent vectors (sparse M times the basis)
            V = m_orthonormalize(V, self.Mr, tol=1e-10, largest_first=False)
        return V

    def bem(self, wind_speed: float, omega_rot: float):
        """Steady BEM state (:class:`~windflutter.aero.induction.BEMResult`) at (V m/s, Omega rad/s),
        cached per operating point.  Its validity warning is given at every use, cached or not (a
        point first met by the reduction basis, whose warnings are not shown, still warns when a
        search uses it)."""
        key = (float(wind_speed), float(omega_rot))
        if key not in self._induction_cache:
            self._induction_cache[key] = sections_induction(
                self.sections, self.rotor_geometry, wind_speed, omega_rot, n_blades=self.n_blades,
                pitch=self.pitch, air_density=self.air_density, high_thrust=self.high_thrust, warn=False)
        res = self._induction_cache[key]
        warn_outside_momentum_theory(res, float(wind_speed), float(omega_rot))
        warn_compressible(res.W, float(wind_speed), float(omega_rot))
        return res

    def operating_point(self, wind_speed: float, omega_rot: float) -> OperatingPoint:
        induction = None
        if self.induction:
            b = self.bem(wind_speed, omega_rot)
            induction = (b.a, b.ap)
        return OperatingPoint(wind_speed=wind_speed, omega=omega_rot, air_density=self.air_density,
                              rotor=self.rotor_geometry, pitch=self.pitch, induction=induction)

    def strip(self, wind_speed: float, omega_rot: float) -> StripAero:
        return StripAero(self.sections, self.operating_point(wind_speed, omega_rot), self.aero)

    def at(self, wind_speed: float, omega_rot: float) -> "OperatingSystem":
        """The system at one operating point, ready for solves at any frequency."""
        return OperatingSystem(self, wind_speed, omega_rot)


class OperatingSystem:
    """Coupled matrices at a fixed (V, Omega) as a function of the oscillation frequency."""

    def __init__(self, model: AeroelasticModel, wind_speed: float, omega_rot: float):
        self.model = model
        self.wind_speed = wind_speed
        self.omega_rot = omega_rot
        self.strip = model.strip(wind_speed, omega_rot)
        self.eig_cache: dict = {}
        self.Ks = model.structural_stiffness(omega_rot)
        self.Ds = model.structural_damping(omega_rot)
        if model.TPhi is not None:
            self._aero = self.strip.projected(model.TPhi)
        else:
            T = model.structure.T
            TT = T.T.tocsr()

            def f(om):
                return tuple((TT @ A @ T).tocsr() for A in self.strip.matrices(om))

            self._aero = f

    @property
    def size(self) -> int:
        """Coordinates of the working basis."""
        return int(self.model.size)

    def structural_pencil(self):
        """``(Ks(Omega), M)``: the structure with the rotor terms at this point, working basis."""
        return self.Ks, self.model.Mr

    def newton_pencil(self, lam: complex, omega: float):
        """``T = lam^2 Mt + lam Dt + Kt`` at frequency ``omega`` and ``x -> T'(lam) x = (2 lam Mt + Dt) x``.

        The same numbers as from :meth:`matrices`, cheaper on projected models (the aero's
        circulatory part enters ``lam Da + Ka`` as one product; :class:`~windflutter.aero.strip.
        ProjectedAero`); otherwise formed from :meth:`matrices`.
        """
        qp = getattr(self._aero, "qep_parts", None)
        if qp is None or sp.issparse(self.Ks):
            return qep_pencil(*self.matrices(omega), lam)
        if not hasattr(self, "_mt"):
            m = self.model
            self._mt = np.asarray(m.Mr - self._aero.Ma)
            self._d0 = np.asarray(self.Ds.toarray() if sp.issparse(self.Ds) else self.Ds)
            self._k0 = np.asarray(self.Ks)
        LK, apply_Da = qp(omega, lam)
        Mt, D0 = self._mt, self._d0
        T = (lam * lam) * Mt + lam * D0 + self._k0 - LK
        return T, lambda x: (2.0 * lam) * (Mt @ x) + D0 @ x - apply_Da(x)

    def matrices(self, omega: float):
        """``(Mt, Dt, Kt)`` with Theodorsen frozen at frequency ``omega`` (rad/s)."""
        Ma, Da, Ka = self._aero(omega)
        m = self.model
        return m.Mr - Ma, self.Ds - Da, self.Ks - Ka

    def reference(self, fraction: float = 0.75):
        """(U, b) of the strip nearest ``fraction`` of the largest radius (the seed's 75 % span)."""
        sec = self.model.sections
        r = np.asarray(sec.radius, float)
        if self.omega_rot == 0.0:  # fixed wing: spanwise station
            r = np.linalg.norm(np.asarray(sec.origin) - np.asarray(sec.origin)[np.argmin(r)], axis=1)
        target = fraction * r.max() if self.omega_rot == 0.0 else fraction * r.max()
        j = int(np.argmin(np.abs(r - target)))
        return float(self.strip.flow.U[j]), float(sec.semi_chord[j])

    def expand(self, x: np.ndarray) -> np.ndarray:
        """Working-basis vector -> unconstrained DOF vector."""
        m = self.model
        return m.TPhi @ x if m.TPhi is not None else m.structure.T @ x


__all__ = ["StructuralMatrices", "AeroelasticModel", "OperatingSystem", "structural_modes", "ModelError"]
