"""Co-rotational beam: the geometrically nonlinear form of the 2-node Timoshenko element, its
internal forces and its consistent tangent about a finitely deformed configuration.

The nonlinear structure is the linear element of :mod:`windflutter.structure.beam` in a frame that
follows the element (Crisfield 1990, *Comput. Methods Appl. Mech. Eng.* 81:131; Battini & Pacoste
2002, *Comput. Methods Appl. Mech. Eng.* 191:1755): large rotations, small strains.

Configuration (:class:`BeamConfiguration`)
    node positions ``x`` (n, 3) and node rotations ``R`` (n, 3, 3), the rotation of each node's
    triad from the reference to the current configuration (global axes).  Variations are
    translations ``dx`` and *spatial* spins ``dtheta`` (``R -> expm(S(dtheta)) R``): the rotational
    DOFs of the linear FE model, so a linearization about a configuration keeps the DOF numbering.

Element
    * frame ``E = [e1 e2 e3]``: ``e1`` along the current chord ``x_b - x_a`` (length ``l``); ``e2``
      the reference section axis y turned by the mean nodal rotation
      ``R_m = R_a expm(log(R_a^T R_b) / 2)`` and made normal to ``e1``; ``e3 = e1 x e2``;
    * local deformation ``d`` (12, the DOF order of the linear element in its section frame):
      node a at rest, node b stretched along ``e1`` by ``l - l0 + bow``, nodal rotations relative to
      the frame ``phi_a = log(E^T R_a E0)``, ``phi_b = log(E^T R_b E0)`` (``E0`` the reference
      section frame);
    * ``bow = l0/2 sum_planes [phi_a, phi_b] G [phi_a, phi_b]^T``, ``G = [[2/15, -1/30], [-1/30,
      2/15]]``: the chord shortening of the cubic (Hermite) deflection inside the element, so that
      with an axial force ``N`` alone the geometric stiffness is the element's Hermite
      ``N int(v'^2 + w'^2) dx`` (:func:`windflutter.structure.beam.beam_geometric_matrices`);
    * strain energy ``U = 1/2 d^T K_loc d`` (``K_loc`` the exact linear element).

Tangent (:func:`beam_tangent`)
    the Hessian ``H`` of ``sum U`` in ``(dx, dtheta)``, split into the material part
    ``K_mat = B^T K_loc B`` (``B = dd/dq``: the elastic stiffness of the deformed geometry, zero on
    rigid-body motions) and the geometric part ``K_geo = sum_k g_k d^2 d_k / dq^2`` with the local
    resultants ``g = K_loc d`` (axial force, shear forces, torsion and bending moments at the element
    ends): the initial-stress matrix of the current stress.  ``H`` is symmetric; at an equilibrium
    under conservative loads it is the stiffness of the linearized equations, whatever the
    parametrization of the rotations (the gradient of the total potential vanishes there).
    ``B`` and ``d^2 d`` come from central differences of ``d`` over the 12 element DOFs, every
    perturbation of every element in one vectorized evaluation (163 per element, of the chord and the two nodal
    spins; steps 1e-4 rad and 1e-4 ``l0``: truncation ~1e-8 relative, round-off far below).

:func:`solve_equilibrium` finds a configuration where the internal forces balance given,
possibly configuration-dependent, external loads (Newton on the Hessian).

Units: SI (m, rad, N, N m).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.spatial.transform import Rotation

from windflutter.errors import InputError, ModelError
from windflutter.linalg_tools import congruence, skew
from windflutter.structure.assembly import coo_matrix_of, spring_matrices
from windflutter.structure.beam import beam_frames, beam_local_matrices, block_rotation, element_dofs
from windflutter.structure.fem import FEModel

__all__ = ["BeamConfiguration", "BeamTangent", "reference_configuration", "linear_configuration",
           "chained_configuration", "displaced",
           "deformed_model", "beam_tangent", "linear_resultants", "internal_forces", "solve_equilibrium",
           "Equilibrium", "beam_elements", "beam_internal_forces"]

#: central-difference steps: rotations (rad) and translations (fraction of the element length)
STEP_ROTATION = 1e-4
STEP_TRANSLATION = 1e-4
_BOW = np.array([[2.0 / 15.0, -1.0 / 30.0], [-1.0 / 30.0, 2.0 / 15.0]])


def _expm(v: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of rotation vectors (..., 3) (rad): ``I + a S + b S^2`` with
    ``a = sin t / t``, ``b = (1 - cos t) / t^2`` (Taylor series below 1e-4 rad)."""
    v = np.asarray(v, float)
    t2 = np.einsum("...i,...i->...", v, v)
    t = np.sqrt(t2)
    small = t < 1e-4
    ts = np.where(small, 1.0, t)
    a = np.where(small, 1.0 - t2 / 6.0, np.sin(ts) / ts)
    b = np.where(small, 0.5 - t2 / 24.0, (1.0 - np.cos(ts)) / ts**2)
    eye = np.broadcast_to(np.eye(3), v.shape[:-1] + (3, 3))
    return ((1.0 - b * t2)[..., None, None] * eye + a[..., None, None] * skew(v)
            + b[..., None, None] * (v[..., :, None] * v[..., None, :]))


def _logm(Q: np.ndarray) -> np.ndarray:
    """Rotation vectors (..., 3) (rad) of rotation matrices (..., 3, 3): the axial vector of the
    skew part scaled to the angle ``atan2(|axial|, (tr Q - 1) / 2)``; angles above 90 degrees
    (not met in an element) go through SciPy's quaternion route."""
    Q = np.asarray(Q, float)
    w = 0.5 * np.stack([Q[..., 2, 1] - Q[..., 1, 2], Q[..., 0, 2] - Q[..., 2, 0], Q[..., 1, 0] - Q[..., 0, 1]], axis=-1)
    c = 0.5 * (np.trace(Q, axis1=-2, axis2=-1) - 1.0)
    s = np.linalg.norm(w, axis=-1)
    ang = np.arctan2(s, c)
    ratio = np.where(s > 1e-8, ang / np.where(s > 1e-8, s, 1.0), 1.0 + s**2 / 6.0)
    out = w * ratio[..., None]
    far = c < 0.0
    if np.any(far):
        out[far] = Rotation.from_matrix(Q[far]).as_rotvec()
    return out


@dataclass(frozen=True)
class BeamConfiguration:
    """Node positions ``x`` (n, 3) (m) and node rotations ``R`` (n, 3, 3) (reference -> current)."""

    x: np.ndarray
    R: np.ndarray


def reference_configuration(fe: FEModel) -> BeamConfiguration:
    """The undeformed configuration of ``fe``."""
    n = fe.n_nodes
    return BeamConfiguration(x=np.asarray(fe.nodes, float).copy(), R=np.broadcast_to(np.eye(3), (n, 3, 3)).copy())


def _check_u(fe: FEModel, u: np.ndarray) -> np.ndarray:
    u = np.asarray(u, float)
    if u.shape != (fe.n_dof,) or not np.all(np.isfinite(u)):
        raise InputError("u", u.shape, f"a finite ({fe.n_dof},) displacement vector (full numbering)")
    return u.reshape(-1, 6)


def linear_configuration(fe: FEModel, u: np.ndarray) -> BeamConfiguration:
    """The configuration of a linear displacement field ``u`` (full numbering): ``x + u_t``, ``expm(theta)``."""
    un = _check_u(fe, u)
    return BeamConfiguration(x=np.asarray(fe.nodes, float) + un[:, :3], R=_expm(un[:, 3:]))


def chained_configuration(fe: FEModel, u: np.ndarray, base: BeamConfiguration | None = None) -> BeamConfiguration:
    """``base`` (default: the reference) moved by the displacement ``u`` keeping the beams' lengths:
    node rotations ``expm(theta) R``; each element's chord ``c`` plus its linear strain
    ``du - theta_mid x c`` turned by ``expm(theta_mid)`` and laid from its first node (elements in
    ``beam_conn`` order, each starting where an earlier one ends or at a node it does not share).
    To first order it is :func:`displaced`; it has no spurious stretch ``~theta^2 / 2`` under large
    rotations (a start, and the update, of :func:`solve_equilibrium`)."""
    un = _check_u(fe, u)
    base = base or reference_configuration(fe)
    x = base.x + un[:, :3]
    conn = np.asarray(fe.beam_conn, dtype=np.int64)
    c = base.x[conn[:, 1]] - base.x[conn[:, 0]]
    th = 0.5 * (un[conn[:, 0], 3:] + un[conn[:, 1], 3:])
    piece = np.einsum("eij,ej->ei", _expm(th), c + (un[conn[:, 1], :3] - un[conn[:, 0], :3]) - np.cross(th, c))
    for e, (a, b) in enumerate(conn):  # sequential along the chain: one 3-vector per element
        x[b] = x[a] + piece[e]
    return BeamConfiguration(x=x, R=_expm(un[:, 3:]) @ base.R)


def _is_chain(fe: FEModel) -> bool:
    """The beams form one chain in ``beam_conn`` order (each element starts where the last ended)."""
    conn = np.asarray(fe.beam_conn, dtype=np.int64)
    return len(conn) > 0 and bool(np.all(conn[1:, 0] == conn[:-1, 1])) and len(np.unique(conn[:, 1])) == len(conn)


def displaced(config: BeamConfiguration, du: np.ndarray) -> BeamConfiguration:
    """``config`` moved by ``du`` (full numbering): translations added, spins composed on the left."""
    d = np.asarray(du, float).reshape(-1, 6)
    return BeamConfiguration(x=config.x + d[:, :3], R=_expm(d[:, 3:]) @ config.R)


def deformed_model(fe: FEModel, config: BeamConfiguration) -> FEModel:
    """A copy of ``fe`` built on the configuration: nodes moved; beam section axes and lumped masses
    turned with their nodes (a beam's section y axis by the mean rotation of its two nodes, as
    the co-rotated frame).  For the mass matrix and the geometry of the deformed structure."""
    if len(fe.shell_conn):
        raise InputError("model", "shell", "beam elements (the co-rotational form is for beams)")
    conn = np.asarray(fe.beam_conn, dtype=np.int64)
    orient = np.asarray(fe.beam_orient, float)
    if conn.size:
        _, R0 = beam_frames(fe)
        Ra, Rb = config.R[conn[:, 0]], config.R[conn[:, 1]]
        Rm = Ra @ _expm(0.5 * _logm(np.einsum("eji,ejk->eik", Ra, Rb)))
        orient = np.einsum("eij,ej->ei", Rm, R0[:, 1, :])
    masses = [replace(m, inertia=config.R[m.node] @ np.asarray(m.inertia, float) @ config.R[m.node].T,
                      offset=config.R[m.node] @ np.asarray(m.offset, float)) for m in fe.masses]
    return replace(fe, nodes=np.asarray(config.x, float).copy(), beam_orient=orient, masses=masses)


@dataclass
class BeamTangent:
    """Internal forces and tangent of the beams of a model at a configuration (full numbering).

    Attributes
    ----------
    f_int : (n_dof,) internal nodal forces (N, N m): the gradient of the strain energy.
    K_mat, K_geo : (n_dof, n_dof) CSR material and geometric (initial-stress) stiffness; their sum
        is the Hessian of the strain energy.
    resultants : (nb, 12) local end loads ``g = K_loc d`` (element frame: force, moment at node a,
        force, moment at node b; ``resultants[:, 6]`` the axial force, tension positive).
    frames : (nb, 3, 3) current element frames (columns ``e1, e2, e3``).
    """

    f_int: np.ndarray
    K_mat: sp.csr_matrix
    K_geo: sp.csr_matrix
    resultants: np.ndarray
    frames: np.ndarray

    @property
    def K(self) -> sp.csr_matrix:
        """The tangent stiffness ``K_mat + K_geo``."""
        return (self.K_mat + self.K_geo).tocsr()


class _Elements:
    """Reference data of the beam elements of a model."""

    def __init__(self, fe: FEModel):
        if not len(fe.beam_conn):
            raise InputError("beam_conn", 0, "a model with beam elements")
        self.conn = np.asarray(fe.beam_conn, dtype=np.int64)
        K_loc, _, self.l0, R0 = beam_local_matrices(fe)
        self.K_loc = 0.5 * (K_loc + np.transpose(K_loc, (0, 2, 1)))
        self.E0 = np.transpose(R0, (0, 2, 1))  # columns: reference section axes
        nb = len(self.l0)
        # the element depends on the chord c = x_b - x_a and the two nodal spins: 9 variables
        self.steps = np.concatenate([STEP_TRANSLATION * self.l0[:, None] * np.ones((nb, 3)),
                                     np.full((nb, 6), STEP_ROTATION)], axis=1)
        self.dofs = element_dofs(self.conn)

    def deformation(self, c, Ra, Rb) -> tuple[np.ndarray, np.ndarray]:
        """Local deformations ``d`` (..., 12) and frames (..., 3, 3) of the elements for chords ``c``
        and node rotations (arrays with a leading batch shape ``(..., nb)``)."""
        length = np.linalg.norm(c, axis=-1)
        e1 = c / length[..., None]
        Rm = Ra @ _expm(0.5 * _logm(np.swapaxes(Ra, -1, -2) @ Rb))
        y = np.einsum("...ij,...j->...i", Rm, self.E0[..., :, 1])
        y = y - np.sum(y * e1, axis=-1, keepdims=True) * e1
        e2 = y / np.linalg.norm(y, axis=-1, keepdims=True)
        E = np.stack([e1, e2, np.cross(e1, e2)], axis=-1)
        Et = np.swapaxes(E, -1, -2)
        pa, pb = _logm(Et @ Ra @ self.E0), _logm(Et @ Rb @ self.E0)
        bow = 0.5 * self.l0 * sum(_BOW[0, 0] * pa[..., k] ** 2 + 2 * _BOW[0, 1] * pa[..., k] * pb[..., k]
                                  + _BOW[1, 1] * pb[..., k] ** 2 for k in (1, 2))
        d = np.zeros(c.shape[:-1] + (12,))
        d[..., 3:6], d[..., 9:12] = pa, pb
        d[..., 6] = length - self.l0 + bow
        return d, E


def _perturbations(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit perturbations of ``n`` variables for central first and second differences: the rows
    of ``P`` (1 + 2n + 2n(n-1), n) are 0, +e_i, -e_i and +-e_i +-e_j (i < j); ``pairs`` the (i, j)."""
    eye = np.eye(n)
    pairs = np.array([(i, j) for i in range(n) for j in range(i + 1, n)])
    mixed = np.concatenate([eye[pairs[:, 0]] * a + eye[pairs[:, 1]] * b for a, b in ((1, 1), (1, -1), (-1, 1), (-1, -1))])
    return np.concatenate([np.zeros((1, n)), eye, -eye, mixed]), pairs


_NV = 9
_P, _PAIRS = _perturbations(_NV)
#: element DOFs (x_a, theta_a, x_b, theta_b) -> variables (c = x_b - x_a, theta_a, theta_b)
_A = np.zeros((_NV, 12))
_A[0:3, 0:3], _A[0:3, 6:9], _A[3:6, 3:6], _A[6:9, 9:12] = -np.eye(3), np.eye(3), np.eye(3), np.eye(3)


def _element_derivatives(el: _Elements, config: BeamConfiguration, g: np.ndarray | None):
    """``(E, B, Hg, g)``: frames at the configuration, ``B = dd/dq`` (nb, 12, 12) and
    ``Hg = d^2 (g . d) / dq^2`` (nb, 12, 12) for the resultants ``g`` (default ``K_loc d``)."""
    a, b = el.conn[:, 0], el.conn[:, 1]
    dz = _P[:, None, :] * el.steps[None, :, :]  # (npert, nb, 9)
    c = (config.x[b] - config.x[a])[None] + dz[..., 0:3]
    Ra, Rb = _expm(dz[..., 3:6]) @ config.R[a][None], _expm(dz[..., 6:9]) @ config.R[b][None]
    d, E = el.deformation(c, Ra, Rb)
    if g is None:
        g = np.einsum("eij,ej->ei", el.K_loc, d[0])
    h = el.steps.T  # (9, nb)
    n = _NV
    Bz = np.transpose((d[1:n + 1] - d[n + 1:2 * n + 1]) / (2.0 * h[:, :, None]), (1, 2, 0))  # (nb, 12, 9)
    s = np.einsum("pek,ek->pe", d, g)
    Hz = np.zeros((len(el.l0), n, n))
    idx = np.arange(n)
    Hz[:, idx, idx] = ((s[1:n + 1] - 2.0 * s[0][None] + s[n + 1:2 * n + 1]) / h**2).T
    m = s[2 * n + 1:].reshape(4, len(_PAIRS), -1)
    i, j = _PAIRS[:, 0], _PAIRS[:, 1]
    off = ((m[0] - m[1] - m[2] + m[3]) / (4.0 * h[i] * h[j])).T
    Hz[:, i, j] = off
    Hz[:, j, i] = off
    return E[0], Bz @ _A, congruence(_A, Hz), g


def _assemble(mats: np.ndarray, dofs: np.ndarray, n: int) -> sp.csr_matrix:
    k = dofs.shape[1]
    A = sp.coo_matrix((mats.ravel(), (np.repeat(dofs, k, axis=1).ravel(), np.tile(dofs, (1, k)).ravel())),
                      shape=(n, n)).tocsr()
    return ((A + A.T) * 0.5).tocsr()


def _check_config(fe: FEModel, config: BeamConfiguration) -> None:
    x, R = np.asarray(config.x), np.asarray(config.R)
    if x.shape != (fe.n_nodes, 3) or R.shape != (fe.n_nodes, 3, 3) or not (np.all(np.isfinite(x)) and np.all(np.isfinite(R))):
        raise InputError("configuration", (x.shape, R.shape), f"finite positions ({fe.n_nodes}, 3) and rotations "
                                                              f"({fe.n_nodes}, 3, 3)")


def beam_tangent(fe: FEModel, config: BeamConfiguration, resultants: np.ndarray | None = None,
                 elements: _Elements | None = None) -> BeamTangent:
    """Internal forces, material and geometric stiffness of the beams of ``fe`` at ``config``.

    Parameters
    ----------
    fe : the model (its beam elements; other elements are not included).
    config : the configuration (:class:`BeamConfiguration`).
    resultants : optional (nb, 12) local end loads to build ``K_geo`` (and ``f_int``) with in place
        of the configuration's own ``K_loc d``: e.g. :func:`linear_resultants` of a linear solution
        at the reference configuration (the classical initial-stress matrix).
    elements : the model's reference element data (an iteration passes it; built when None).
    """
    _check_config(fe, config)
    el = elements if elements is not None else _Elements(fe)
    if resultants is not None:
        resultants = np.asarray(resultants, float)
        if resultants.shape != (len(el.l0), 12) or not np.all(np.isfinite(resultants)):
            raise InputError("resultants", resultants.shape, f"finite ({len(el.l0)}, 12) element end loads")
    E, B, Hg, g = _element_derivatives(el, config, resultants)
    Km = congruence(B, el.K_loc)
    f = np.zeros(fe.n_dof)
    np.add.at(f, el.dofs, np.einsum("eki,ek->ei", B, g))
    n = fe.n_dof
    return BeamTangent(f_int=f, K_mat=_assemble(Km, el.dofs, n), K_geo=_assemble(Hg, el.dofs, n), resultants=g,
                       frames=E)


def beam_elements(fe: FEModel) -> _Elements:
    """The reference element data of the beams of ``fe`` (to pass to repeated evaluations)."""
    return _Elements(fe)


def beam_internal_forces(fe: FEModel, config: BeamConfiguration, elements: _Elements | None = None) -> np.ndarray:
    """(n_dof,) internal nodal forces of the beams of ``fe`` at ``config`` (``beam_tangent(...).f_int``
    without the tangent: the first central differences of ``d`` alone, 19 evaluations per element
    instead of 163; for a time integration that evaluates the forces at every iteration)."""
    el = elements if elements is not None else _Elements(fe)
    a, b = el.conn[:, 0], el.conn[:, 1]
    n = _NV
    P = _P[:2 * n + 1]
    dz = P[:, None, :] * el.steps[None, :, :]
    c = (config.x[b] - config.x[a])[None] + dz[..., 0:3]
    Ra, Rb = _expm(dz[..., 3:6]) @ config.R[a][None], _expm(dz[..., 6:9]) @ config.R[b][None]
    d, _ = el.deformation(c, Ra, Rb)
    g = np.einsum("eij,ej->ei", el.K_loc, d[0])
    Bz = np.transpose((d[1:n + 1] - d[n + 1:2 * n + 1]) / (2.0 * el.steps.T[:, :, None]), (1, 2, 0))
    f = np.zeros(fe.n_dof)
    np.add.at(f, el.dofs, np.einsum("eki,ek->ei", Bz @ _A, g))
    return f


def linear_resultants(fe: FEModel, u: np.ndarray) -> np.ndarray:
    """(nb, 12) local end loads ``K_loc T u_e`` of the linear elements for the displacement ``u``
    (section frames of the reference configuration)."""
    un = _check_u(fe, u).reshape(-1)
    el = _Elements(fe)
    _, R0 = beam_frames(fe)
    ul = np.einsum("eij,ej->ei", block_rotation(R0), un[el.dofs])
    return np.einsum("eij,ej->ei", el.K_loc, ul)


@dataclass
class Equilibrium:
    """A converged static configuration: ``config``, the tangent there, the external loads and their
    stiffness ``K_ext = d f_ext / dq`` (full numbering), the Newton iterations and the last
    increment (m, rad)."""

    config: BeamConfiguration
    tangent: BeamTangent
    f_ext: np.ndarray
    K_ext: sp.spmatrix | None
    iterations: int
    increment: float


def solve_equilibrium(fe: FEModel, T: sp.spmatrix, external: Callable, start: BeamConfiguration | None = None,
                      tol: float = 1e-10, max_iterations: int = 40, load_steps: int = 1,
                      final: bool = True, damped: bool = True) -> Equilibrium:
    """Newton iteration to ``f_int(config) = f_ext(config)`` on the free DOFs ``u = T q``.

    Parameters
    ----------
    fe : the model (beams; springs enter linearly).
    T : (n_dof, nq) constraint map (:attr:`~windflutter.structure.assembly.Structural.T`).
    external : ``external(config, factor) -> (f_ext (n_dof,), K_ext (n_dof, n_dof) or None)``: the
        loads at a configuration scaled by the load factor ``factor`` and their derivative with
        respect to ``(dx, dtheta)`` (e.g. spin softening; for a conservative load, minus the Hessian
        of its potential).
    start : initial configuration (default: the reference).
    tol : stop when the largest translation increment is below ``tol`` x the model size and the
        largest rotation increment below ``tol`` rad.
    load_steps : equal load increments (each solved to ``tol``).
    final : evaluate the tangent and the loads at the converged configuration; False leaves
        ``tangent``, ``f_ext`` and ``K_ext`` None (an outer iteration that needs the configuration
        alone saves one tangent and one load evaluation).
    damped : limit the step: a Newton increment more than :data:`STEP_GROWTH` times the last applied
        one (its size as in ``tol``) is halved until it is not (at most :data:`MAX_HALVINGS` times);
        the first step of each load step is taken whole.  Near a solution the increments shrink, so
        the steps plain Newton converges with are unchanged; far from one (a cantilever elastica
        at ``P L^2 / EI = 10`` in one load step) the full step overshoots into a far configuration
        and plain Newton wanders.  False: plain Newton.

    Raises
    ------
    ModelError when an iteration does not converge (no equilibrium, or a limit point on the path).
    """
    config = start or reference_configuration(fe)
    _check_config(fe, config)
    size = max(float(np.ptp(np.asarray(fe.nodes, float), axis=0).max()), 1.0)
    K_spring = _spring_stiffness(fe)
    chain = _is_chain(fe)
    el = _Elements(fe)
    total = 0
    for step in range(1, load_steps + 1):
        factor = step / load_steps
        last = None  # the size of the last applied increment of this load step
        for it in range(1, max_iterations + 1):
            tan = beam_tangent(fe, config, elements=el)
            f_ext, K_ext = external(config, factor)
            K = tan.K if K_spring is None else tan.K + K_spring
            f_int = internal_forces(fe, config, tan, K_spring)
            A = T.T @ ((K - K_ext) if K_ext is not None else K) @ T
            r = T.T @ (np.asarray(f_ext, float) - f_int)
            dq = spla.spsolve(sp.csc_matrix(A), r) if sp.issparse(A) else np.linalg.solve(A, r)
            du = np.asarray(T @ dq).reshape(-1, 6)
            inc = _increment(du, size)
            if damped and last is not None and np.isfinite(inc):
                du, inc = _limited(du, inc, last)
            config = chained_configuration(fe, du.reshape(-1), config) if chain else displaced(config, du)
            last = inc
            total += 1
            if not np.isfinite(inc):
                break
            if inc <= tol:
                break
        else:
            inc = np.inf
        if not inc <= tol:
            raise ModelError(f"the co-rotational static iteration did not converge at load factor {factor:.3g} "
                             f"({max_iterations} iterations): no equilibrium near the start, or a limit point; "
                             "use more load steps" + ("" if damped else " or the damped iteration"))
    if not final:
        return Equilibrium(config=config, tangent=None, f_ext=None, K_ext=None, iterations=total, increment=inc)
    tan = beam_tangent(fe, config, elements=el)
    f_ext, K_ext = external(config, 1.0)
    return Equilibrium(config=config, tangent=tan, f_ext=np.asarray(f_ext, float), K_ext=K_ext, iterations=total,
                       increment=inc)


#: a Newton increment longer than this many times the last applied one is halved (``damped``)
STEP_GROWTH = 4.0
#: at most this many halvings of one increment
MAX_HALVINGS = 8


def _increment(du: np.ndarray, size: float) -> float:
    """Size of an (n, 6) increment: the largest translation over the model size, or the largest rotation (rad)."""
    return max(float(np.abs(du[:, :3]).max(initial=0.0)) / size, float(np.abs(du[:, 3:]).max(initial=0.0)))


def _limited(du: np.ndarray, inc: float, last: float) -> tuple[np.ndarray, float]:
    """``(du, inc)`` (``inc`` its :func:`_increment`) halved until no longer than :data:`STEP_GROWTH` x
    ``last`` (at most :data:`MAX_HALVINGS` times; halving is exact, so is the size's)."""
    k = 0
    while k < MAX_HALVINGS and inc > STEP_GROWTH * last:
        inc, k = 0.5 * inc, k + 1
    return (du * 0.5**k if k else du), inc


def internal_forces(fe: FEModel, config: BeamConfiguration, tangent: BeamTangent | None = None,
                    K_spring: sp.spmatrix | None = None) -> np.ndarray:
    """(n_dof,) internal nodal forces (N, N m, global axes) of the model at ``config``: its beams'
    (``tangent.f_int``, computed when not given) and its springs' (linear in the nodal motion)."""
    tangent = tangent if tangent is not None else beam_tangent(fe, config)
    K_spring = K_spring if K_spring is not None else _spring_stiffness(fe)
    if K_spring is None:
        return tangent.f_int
    u_s = np.zeros(fe.n_dof)
    u_s.reshape(-1, 6)[:, :3] = config.x - np.asarray(fe.nodes, float)
    u_s.reshape(-1, 6)[:, 3:] = _logm(config.R)
    return tangent.f_int + K_spring @ u_s


def _spring_stiffness(fe: FEModel) -> sp.csr_matrix | None:
    if not fe.springs:
        return None

    gk, gd, tk, td = spring_matrices(fe)
    parts = [coo_matrix_of(m, d) for m, d in ((gk, gd), (tk, td)) if len(m)]
    r, c, v = (np.concatenate(z) for z in zip(*parts))
    return sp.coo_matrix((v, (r, c)), shape=(fe.n_dof, fe.n_dof)).tocsr()
