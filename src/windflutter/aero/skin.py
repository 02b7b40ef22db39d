"""The seed's distribution of the strip aerodynamics on the blade's skin quads (Castillo Capponi
2010, sec. 3.2.2), as a drop-in replacement of the section-spline map.

The section-spline map (:mod:`windflutter.mesh.aero_map`) gives each strip ONE rigid motion,
fitted to its skin nodes, and applies the strip's Theodorsen matrices to it:
``A_spline = sum_j P_j^T (w_j A_j) P_j`` ("product of averages").

The seed instead lays bilinear quad "aero elements" on the skin: the strip's virtual work is
carried half by its upper (suction-side) and half by its lower skin, and integrated over each
skin quad with 2x2 Gauss points, the section quantities ``q = (h, alpha, s)`` being taken at each
Gauss point from the bilinear interpolation of the quad's nodal displacements:
``A_skin = sum_j sum_g (w_j c_g) P_g^T A_j P_g`` ("average of products"), with
``c_g = 1/2 dA_g / S_side(j)`` so that each side's weights sum to 1/2.

Because the second form is again "a motion map and strip matrices", it is returned as an
:class:`~windflutter.aero.sections.AeroSections` in which every Gauss point is a *sub-strip*:
the parent strip's geometry, chord, elastic axis, polar (hence the same relative flow and the
same Theodorsen blocks per unit span), width ``w_j c_g`` and the Gauss point's motion rows.
:class:`~windflutter.aero.strip.StripAero` then assembles exactly ``A_skin`` with no change.

Kinematics at a Gauss point x_g of a quad with nodes n = 1..4, shape functions N_n:

* translation ``u(x_g) = sum N_n u_n`` (seed eqs. 3.77-3.80);
* rotation ``theta(x_g)``: ``rotation="nodal"`` -- ``sum N_n theta_n``, the shell nodes' rotation
  DOFs (the seed's eqs. 3.81-3.83: ``alpha = e2 . theta``); ``rotation="gradient"`` -- the rigid
  rotation that best explains the surface gradient of the interpolated translations,
  least squares of ``theta x t_xi = du/dxi``, ``theta x t_eta = du/deta`` (out-of-plane
  components = the skin's slopes, in-plane = half the surface curl); only translations used,
  like the spline map; ``rotation="strip"`` -- the strip's rigid-fit rotation (spline map) at
  all its Gauss points (a hybrid: no local skin slopes in alpha);
* ``kinematics="section"`` (default): the point's motion is carried rigidly to the strip's
  elastic-axis point, ``u_ea = u(x_g) + theta(x_g) x (o_j - x_g)``; then
  ``h = e1 . u_ea, alpha = e2 . theta, s = e3 . u_ea``.  A rigid motion of the section gives
  the same q at every Gauss point, so both distributions give identical generalized forces on
  rigid section motions (tested);
* ``kinematics="seed"``: the thesis read literally, ``h = e1 . u(x_g)`` and ``s = e3 . u(x_g)``
  at the skin point itself.  A nose-up pitch then also "plunges" the skin points aft of the
  elastic axis: the lift does work on the skin area centroid's plunge, which adds a spurious
  pitching moment (lift x centroid offset) and a chordwise-variance term on top of Theodorsen's
  moment -- kept only to reproduce the seed.

Weighting of a Gauss point: ``dA_g = |t_xi x t_eta|`` (2x2 Gauss weights are 1 on [-1, 1]^2);
``weighting="projected"`` multiplies by ``|n . n_c|`` (the skin area projected on the chord
plane) instead of the true skin area.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from windflutter.aero.flow import unit as _unit
from windflutter.aero.sections import AeroSections
from windflutter.aero.strip import StripAero, section_matrices
from windflutter.errors import InputError
from windflutter.linalg_tools import skew as _skew

GAUSS_2 = 1.0 / np.sqrt(3.0)
_XI = np.array([-1.0, 1.0, 1.0, -1.0])  # corner coordinates of the 4 nodes (cyclic order)
_ETA = np.array([-1.0, -1.0, 1.0, 1.0])


@dataclass(frozen=True)
class SkinOptions:
    """How the skin-quad distribution samples the section motion.

    Parameters
    ----------
    kinematics : ``"section"`` (Gauss-point motion carried rigidly to the strip's elastic axis;
        rigid-consistent) or ``"seed"`` (h, s at the skin point itself, the thesis literally).
    rotation : ``"nodal"`` (interpolated shell rotation DOFs, the thesis), ``"gradient"``
        (from the surface gradient of the interpolated translations) or ``"strip"`` (the strip's
        rigid-fit rotation from the model's ``motion_map``, the same at all its Gauss points: local
        skin slopes then do not enter alpha, only the skin translations enter h and s).
    weighting : ``"area"`` (skin area) or ``"projected"`` (area projected on the chord plane).
    """

    kinematics: str = "section"
    rotation: str = "nodal"
    weighting: str = "area"

    def __post_init__(self):
        for name, choices in (("kinematics", ("section", "seed")), ("rotation", ("nodal", "gradient", "strip")),
                              ("weighting", ("area", "projected"))):
            if getattr(self, name) not in choices:
                raise InputError(f"skin.{name}", getattr(self, name), f"one of {choices}")


@dataclass
class SkinDistribution:
    """The skin-quad distribution of a model's strips.

    Attributes
    ----------
    sections : the sub-strip :class:`AeroSections` (one per Gauss point; drop-in for the solver).
    parent : (ng,) index of the original strip of each sub-strip.
    element : (ng,) shell element (row of ``fe.shell_conn``) of each Gauss point.
    upper : (ng,) True on the suction-side skin.
    point : (ng, 3) Gauss point position (m).
    fraction : (ng,) share of the parent strip's work, ``c_g`` (sums to 1 per strip).
    """

    sections: AeroSections
    parent: np.ndarray
    element: np.ndarray
    upper: np.ndarray
    point: np.ndarray
    fraction: np.ndarray




def gauss_points_2x2() -> tuple[np.ndarray, np.ndarray]:
    """(4,) xi and eta of the 2x2 Gauss-Legendre rule on [-1, 1]^2 (all weights 1)."""
    g = GAUSS_2
    return np.array([-g, g, g, -g]), np.array([-g, -g, g, g])


def shape_functions(xi, eta):
    """Bilinear shape functions and derivatives at (xi, eta) (arrays of equal shape).

    Returns N, dN/dxi, dN/deta, each of shape ``xi.shape + (4,)``.
    """
    xi, eta = np.asarray(xi, float)[..., None], np.asarray(eta, float)[..., None]
    N = 0.25 * (1 + _XI * xi) * (1 + _ETA * eta)
    dxi = 0.25 * _XI * (1 + _ETA * eta)
    deta = 0.25 * _ETA * (1 + _XI * xi)
    return N, dxi, deta


def skin_elements(fe) -> tuple[np.ndarray, np.ndarray]:
    """Skin quads of every blade from the model's regions named ``blade<k>:skin``.

    Returns
    -------
    elements : (ne,) rows of ``fe.shell_conn``.  blade : (ne,) blade index of each.
    """
    names = list(getattr(fe, "region_names", []) or [])
    reg = np.asarray(getattr(fe, "element_regions", {}).get("shell", np.zeros(0)), dtype=np.int64)
    els, bl = [], []
    for r, nm in enumerate(names):
        m = re.fullmatch(r"blade(\d+):skin", nm)
        if m is None:
            continue
        e = np.where(reg == r)[0]
        els.append(e)
        bl.append(np.full(e.size, int(m.group(1))))
    if not els or sum(e.size for e in els) == 0:
        raise InputError("fe.region_names", names[:6], "shell skin regions named 'blade<k>:skin' "
                         "(the skin-quad distribution needs a shell blade model)")
    return np.concatenate(els), np.concatenate(bl)


def assign_to_strips(centroids: np.ndarray, blade: np.ndarray, sections: AeroSections,
                     max_offset: float = 2.0) -> np.ndarray:
    """Strip of each element: the strip of the same blade whose span interval
    ``o_j +- w_j/2 e_span`` best contains the element centroid.

    Raises InputError if an element lies farther than ``max_offset`` half-widths from every strip
    (the skin and the strips do not describe the same blade).
    """
    sb = np.asarray(sections.blade)
    o = np.asarray(sections.origin, float)
    es = _unit(np.asarray(sections.e_span, float))
    hw = 0.5 * np.asarray(sections.width, float)
    out = np.full(len(centroids), -1, dtype=np.int64)
    for k in np.unique(blade):
        js = np.where(sb == k)[0]
        ek = np.where(blade == k)[0]
        if js.size == 0:
            raise InputError("sections.blade", int(k), "strips on every blade that has skin elements")
        t = np.einsum("ejc,jc->ej", centroids[ek, None, :] - o[None, js, :], es[js]) / hw[js][None, :]
        best = np.argmin(np.abs(t), axis=1)
        tb = np.abs(t[np.arange(ek.size), best])
        if np.any(tb > max_offset):
            e = int(ek[np.argmax(tb)])
            raise InputError("skin element", e, f"a skin quad inside a strip's span interval "
                             f"(it is {tb.max():.2f} half-widths from the nearest strip of blade {k})")
        out[ek] = js[best]
    return out


def _gauss_rows(x: np.ndarray, N: np.ndarray, dxi: np.ndarray, deta: np.ndarray, o: np.ndarray,
                options: SkinOptions) -> np.ndarray:
    """Motion rows of every Gauss point.

    Parameters
    ----------
    x : (ng, 4, 3) node coordinates of each Gauss point's quad (m).
    N, dxi, deta : (ng, 4) shape functions and derivatives at the point.
    o : (ng, 3) elastic-axis point of the parent strip (m).

    Returns
    -------
    W : (ng, 6, 4, 6): ``(u, theta)`` of the (transferred) point from the quad's 4 x 6 DOFs.
    """
    ng = x.shape[0]
    W = np.zeros((ng, 6, 4, 6))
    I3 = np.eye(3)
    W[:, :3, :, :3] = N[:, None, :, None] * I3[None, :, None, :]  # u = sum N_n u_n
    if options.rotation == "strip":  # added from the strip's rigid fit by _strip_rotation_rows
        return W
    if options.rotation == "nodal":
        W[:, 3:, :, 3:] = N[:, None, :, None] * I3[None, :, None, :]
    else:
        t_xi = np.einsum("gn,gnc->gc", dxi, x)
        t_eta = np.einsum("gn,gnc->gc", deta, x)
        # theta x t = -skew(t) theta = du/dxi  ->  A theta = [u_xi; u_eta], A = -[skew(t_xi); skew(t_eta)]
        A = -np.concatenate([_skew(t_xi), _skew(t_eta)], axis=1)  # (ng, 6, 3)
        B = np.linalg.solve(np.einsum("gki,gkj->gij", A, A), np.transpose(A, (0, 2, 1)))  # (ng, 3, 6)
        # [u_xi; u_eta] = D @ translations, D (ng, 6, 4, 3)
        D = np.zeros((ng, 6, 4, 3))
        D[:, :3] = dxi[:, None, :, None] * I3[None, :, None, :]
        D[:, 3:] = deta[:, None, :, None] * I3[None, :, None, :]
        W[:, 3:, :, :3] = np.einsum("gik,gknc->ginc", B, D)
    if options.kinematics == "section":
        xg = np.einsum("gn,gnc->gc", N, x)
        # u_ea = u + theta x (o - x_g) = u - skew(o - x_g) theta
        W[:, :3] -= np.einsum("gij,gjnc->ginc", _skew(o - xg), W[:, 3:])
    return W


def _strip_rotation_rows(sections: AeroSections, par: np.ndarray, xg: np.ndarray, o: np.ndarray,
                         transfer: bool) -> sp.csr_matrix:
    """Rows ``theta_g = theta_strip`` (the parent strip's rigid-fit rotation from its
    ``motion_map``) and, with ``transfer``, ``u_g += theta_strip x (o - x_g)``."""
    ng = par.size
    ns = sections.n_sections
    r, c, v = [], [], []
    for k in range(3):  # theta rows
        r.append(6 * np.arange(ng) + 3 + k)
        c.append(6 * par + 3 + k)
        v.append(np.ones(ng))
    if transfer:
        S = -_skew(o - xg)  # u += -skew(d) theta
        for i in range(3):
            for k in range(3):
                r.append(6 * np.arange(ng) + i)
                c.append(6 * par + 3 + k)
                v.append(S[:, i, k])
    sel = sp.csr_matrix((np.concatenate(v), (np.concatenate(r), np.concatenate(c))), shape=(6 * ng, 6 * ns))
    return (sel @ sp.csr_matrix(sections.motion_map)).tocsr()


def skin_distribution(fe, sections: AeroSections, options: SkinOptions | None = None,
                      elements: np.ndarray | None = None, element_blade: np.ndarray | None = None
                      ) -> SkinDistribution:
    """Distribute the strips of a shell blade model on its skin quads (seed sec. 3.2.2).

    Parameters
    ----------
    fe : :class:`~windflutter.structure.fem.FEModel` with shell skin quads.
    sections : the model's strips (from :func:`windflutter.mesh.turbine.build_model`); their
        geometry, chord, elastic axis and polars are kept, their ``motion_map`` is not used.
    options : :class:`SkinOptions`.
    elements : optional rows of ``fe.shell_conn`` forming the aerodynamic skin (default: the
        regions ``blade<k>:skin``); ``element_blade`` then gives their blade index (default 0).

    Returns
    -------
    :class:`SkinDistribution` (``.sections`` is the drop-in :class:`AeroSections`).
    """
    options = options or SkinOptions()
    ns = sections.n_sections
    if ns == 0:
        raise InputError("sections", 0, "at least one aerodynamic strip")
    elements, element_blade = _checked_skin_elements(fe, elements, element_blade)
    conn = np.asarray(fe.shell_conn, dtype=np.int64)[elements]  # (ne, 4)
    X = np.asarray(fe.nodes, float)[conn]  # (ne, 4, 3)
    strip = assign_to_strips(X.mean(axis=1), element_blade, sections)
    x, Ng, dxg, deg, nrm, dA = _gauss_geometry(X, elements)
    par = np.repeat(strip, 4)
    o = np.asarray(sections.origin, float)
    xg = np.einsum("gn,gnc->gc", Ng, x)
    upper, frac = _work_fractions(sections, par, xg, nrm, dA, options.weighting)
    W = _gauss_rows(x, Ng, dxg, deg, o[par], options)  # (ng, 6, 4, 6)
    mm = _motion_rows_matrix(W, conn, fe.n_dof)
    if options.rotation == "strip":
        mm = mm + _strip_rotation_rows(sections, par, xg, o[par], options.kinematics == "section")
    return SkinDistribution(sections=_sub_sections(sections, par, frac, mm), parent=par,
                            element=np.repeat(elements, 4), upper=upper, point=xg, fraction=frac)


def _checked_skin_elements(fe, elements, element_blade) -> tuple[np.ndarray, np.ndarray]:
    """``(elements, element_blade)``: the skin rows of ``fe.shell_conn`` and their blade index.

    None: the regions ``blade<k>:skin`` (:func:`skin_elements`); else the given rows, checked,
    with blade 0 unless ``element_blade`` is given (one per element).
    """
    if elements is None:
        return skin_elements(fe)
    elements = np.asarray(elements, dtype=np.int64)
    element_blade = np.zeros(elements.size, np.int64) if element_blade is None else np.asarray(element_blade, np.int64)
    if elements.size == 0 or elements.min() < 0 or elements.max() >= len(fe.shell_conn):
        raise InputError("elements", elements[:5].tolist(), f"shell element rows in [0, {len(fe.shell_conn)})")
    if element_blade.shape != elements.shape:
        raise InputError("element_blade", element_blade.shape, f"one blade index per element {elements.shape}")
    return elements, element_blade


def _gauss_geometry(X: np.ndarray, elements: np.ndarray):
    """2x2 Gauss points of the skin quads, flattened to ``g = 4 e + p``.

    Parameters
    ----------
    X : (ne, 4, 3) node coordinates of each quad (m).  elements : (ne,) their shell rows (for
        the error message).

    Returns
    -------
    x : (ng, 4, 3) the quad's nodes (m) at each Gauss point.  N, dxi, deta : (ng, 4) shape
    functions and derivatives.  nrm : (ng, 3) ``t_xi x t_eta`` (m^2).  dA : (ng,) its length,
    the area element (m^2, Gauss weight 1).

    Raises InputError on a quad with zero area at a Gauss point.
    """
    gxi, geta = gauss_points_2x2()
    N, dxi, deta = shape_functions(gxi, geta)  # (4, 4) each: Gauss point x node
    ne = len(elements)
    # flatten to Gauss points: g = 4 e + p
    x = np.repeat(X, 4, axis=0)  # (ng, 4, 3)
    Ng, dxg, deg = (np.tile(a, (ne, 1)) for a in (N, dxi, deta))
    t_xi = np.einsum("gn,gnc->gc", dxg, x)
    t_eta = np.einsum("gn,gnc->gc", deg, x)
    nrm = np.cross(t_xi, t_eta)
    dA = np.linalg.norm(nrm, axis=1)  # Jacobian x Gauss weight (1)
    if np.any(dA <= 0):
        e = int(elements[np.argmin(dA) // 4])
        raise InputError("fe.shell_conn", e, "non-degenerate skin quads (zero area at a Gauss point)")
    return x, Ng, dxg, deg, nrm, dA


def _work_fractions(sections: AeroSections, par: np.ndarray, xg: np.ndarray, nrm: np.ndarray, dA: np.ndarray,
                    weighting: str) -> tuple[np.ndarray, np.ndarray]:
    """Side and share of its parent strip's work of every Gauss point.

    Parameters
    ----------
    sections : the strips.  par : (ng,) parent strip.  xg : (ng, 3) Gauss point (m).
    nrm, dA : (ng, 3) surface normal ``t_xi x t_eta`` and (ng,) its length (m^2).
    weighting : ``"area"`` or ``"projected"`` (area projected on the chord plane).

    Returns
    -------
    upper : (ng,) True on the suction side.  frac : (ng,) ``c_g`` (-): each side carries half of
    its strip's work in proportion to the area, a strip with skin on one side only gives it all.

    Raises InputError if a strip has no skin quad.
    """
    ns = sections.n_sections
    o = np.asarray(sections.origin, float)
    nc = _unit(np.cross(np.asarray(sections.e_chord, float), np.asarray(sections.e_span, float)))  # suction side
    upper = np.einsum("gc,gc->g", xg - o[par], nc[par]) >= 0.0
    if weighting == "projected":
        dA = dA * np.abs(np.einsum("gc,gc->g", nrm / dA[:, None], nc[par]))
    # each side carries half of its strip's work; a strip with skin on one side only gives it all
    S_up = np.bincount(par[upper], weights=dA[upper], minlength=ns)
    S_lo = np.bincount(par[~upper], weights=dA[~upper], minlength=ns)
    missing = np.setdiff1d(np.arange(ns), par)
    if missing.size:
        raise InputError("sections", int(missing[0]), "strips that each have skin quads (strip without skin)")
    both = (S_up > 0) & (S_lo > 0)
    share = np.where(both, 0.5, 1.0)
    S = np.where(upper, S_up[par], S_lo[par])
    frac = share[par] * dA / S
    return upper, frac


def _motion_rows_matrix(W: np.ndarray, conn: np.ndarray, n_dof: int) -> sp.csr_matrix:
    """(6 ng, n_dof) sparse motion map from the Gauss-point rows ``W`` (ng, 6, 4, 6) of
    :func:`_gauss_rows` and the quads' node indices ``conn`` (ne, 4), ``g = 4 e + p``."""
    ng = W.shape[0]
    rows = np.broadcast_to((6 * np.arange(ng))[:, None, None, None] + np.arange(6)[None, :, None, None], W.shape)
    cols = np.broadcast_to((6 * np.repeat(conn, 4, axis=0))[:, None, :, None] + np.arange(6)[None, None, None, :], W.shape)
    keep = W != 0.0
    return sp.csr_matrix((W[keep], (rows[keep], cols[keep])), shape=(6 * ng, n_dof))


def _sub_sections(sections: AeroSections, par: np.ndarray, frac: np.ndarray, mm) -> AeroSections:
    """One sub-strip per Gauss point: the parent strip's data, width (m) times ``frac`` and the
    motion map ``mm`` (6 ng, n_dof)."""
    def pick(a):
        return np.asarray(a)[par]

    return replace(sections, blade=pick(sections.blade), radius=pick(sections.radius),
                   width=np.asarray(sections.width, float)[par] * frac, chord=pick(sections.chord),
                   elastic_axis=pick(sections.elastic_axis), origin=pick(sections.origin),
                   e_chord=pick(sections.e_chord), e_span=pick(sections.e_span), airfoil=pick(sections.airfoil),
                   twist=pick(sections.twist), motion_map=mm)


def skin_quad_sections(fe, sections: AeroSections, options: SkinOptions | None = None, **kwargs) -> AeroSections:
    """Drop-in :class:`AeroSections` for the seed's skin-quad distribution.

    Same strips (geometry, chord, elastic axis, polars, hence flow and Theodorsen blocks), one
    sub-strip per skin Gauss point; pass it wherever the model's ``sections`` go
    (:class:`~windflutter.solve.aeroelastic.AeroelasticModel`,
    :class:`~windflutter.aero.strip.StripAero`).  See :func:`skin_distribution`.
    """
    return skin_distribution(fe, sections, options, **kwargs).sections




# --------------------------------------------------------------------------- fast projection


@dataclass
class SkinStripAero(StripAero):
    """:class:`~windflutter.aero.strip.StripAero` for sub-strip sections whose ``parent`` strip is
    known: same matrices, but :meth:`projected` uses that all Gauss points of a strip share its
    Theodorsen blocks per unit span ``A_j``:
    ``sum_g R_g^T (w_g A_j) R_g = sum_j sum_ab A_j,ab H_j,ab`` with the frequency-independent
    ``H_j,ab = sum_{g in j} w_g R_g,a^T R_g,b`` (m x m) precomputed once, so a call costs
    ``9 ns m^2`` instead of ``n_gauss`` 3 x 3 x m products (exact, not an approximation).
    """

    parent: np.ndarray | None = None

    def __post_init__(self):
        super().__post_init__()
        par = np.asarray(self.parent, dtype=np.int64)
        if par.shape != (self.sections.n_sections,):
            raise InputError("parent", par.shape, f"one parent strip per sub-strip ({self.sections.n_sections},)")
        self._par = par
        self._n_par = int(par.max()) + 1
        first = np.full(self._n_par, -1, dtype=np.int64)
        first[par[::-1]] = np.arange(par.size)[::-1]
        if np.any(first < 0):
            raise InputError("parent", "gaps", "parent strip indices 0..n-1 each with sub-strips")
        self._rep = first

    def parent_blocks(self, omega: float):
        """(n_strips, 3, 3) Ma, Da, Ka per unit span of the parent strips at ``omega`` (rad/s)."""
        r = self._rep
        b, U = self.b[r], self.flow.U[r]
        C = self.circulation(abs(omega) * b / U)
        steady = None if self.steady is None else tuple(x[r] for x in self.steady)
        return section_matrices(b, self.a[r], U, C, self.op.air_density, self.cla[r], self.cda[r], self.am[r],
                                steady=steady)

    def projected(self, Phi: np.ndarray):
        PPhi = self.P @ Phi
        PPhi = PPhi.toarray() if sp.issparse(PPhi) else np.asarray(PPhi)
        R = PPhi.reshape(self.sections.n_sections, 3, -1) * np.sqrt(self.width)[:, None, None]
        m = R.shape[2]
        H = np.zeros((self._n_par, 3, 3, m, m))
        order = np.argsort(self._par, kind="stable")
        bounds = np.searchsorted(self._par[order], np.arange(self._n_par + 1))
        for j in range(self._n_par):
            Rj = R[order[bounds[j]:bounds[j + 1]]]  # (g, 3, m)
            H[j] = np.einsum("gai,gbk->abik", Rj, Rj, optimize=True)
        Hf = H.reshape(self._n_par * 9, m * m)

        def f(omega: float):
            out = []
            for blk in self.parent_blocks(omega):
                v = blk.reshape(1, -1)
                out.append((v.real @ Hf + 1j * (v.imag @ Hf)).reshape(m, m))
            return tuple(out)

        return f


__all__ = ["SkinOptions", "SkinDistribution", "skin_distribution", "skin_quad_sections", "skin_elements",
           "assign_to_strips", "shape_functions", "gauss_points_2x2", "SkinStripAero"]
