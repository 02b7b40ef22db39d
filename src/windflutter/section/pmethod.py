"""p-method of the typical section: exact eigenvalues of a state space with aerodynamic lag states.

C(k) is replaced by a Roger rational-function approximation
(:func:`windflutter.aero.theodorsen.theodorsen_rfa`), so the aeroelastic system is linear and
time-invariant; flutter where the largest real part of its oscillatory eigenvalues crosses 0.
"""

from __future__ import annotations

import numpy as np
from scipy import optimize

from windflutter.aero.theodorsen import RogerRFA, theodorsen_rfa
from windflutter.errors import InputError
from windflutter.section.matrices import (
    aero_parts,
    companion_parts,
    natural_frequencies,
    structural_matrices,
)
from windflutter.section.model import TypicalSection
from windflutter.section.results import (
    SectionResult,
    StabilityCurves,
    check_speeds,
    default_speeds,
    section_result,
)


def rfa_state_matrix(sec: TypicalSection, U: float, rfa: RogerRFA) -> np.ndarray:
    """State matrix (1/s) for states ``[q, q', y_1..y_n]`` (h down) with C(s) from a Roger RFA.

    ``C(sbar) ~ A0 + sum c_j sbar/(sbar + beta_j)``, ``sbar = s b / U``.  With the 3/4-chord
    downwash ``w34 = r1 q' + r0 q`` and lag states ``y_j' = -beta_j (U/b) y_j + w34``::

        C w34 = (A0 + sum c_j) w34 - sum c_j beta_j (U/b) y_j

    so the ``[q, q']`` block is the companion matrix with ``C = A0 + sum c_j`` (its
    high-frequency value).
    """
    if np.ndim(rfa.A0) != 0 or abs(float(rfa.A1)) > 0 or abs(float(rfa.A2)) > 0:
        raise InputError("rfa", rfa, "a scalar Roger fit of C(k) without polynomial s terms")
    M, _ = structural_matrices(sec)
    A2, _, qc, w, r1, r0 = aero_parts(sec, U)
    b = sec.semi_chord
    nl = len(rfa.poles)
    base, dC = companion_parts(sec, U)
    c_inf = float(rfa.A0) + float(np.sum(rfa.lags))
    Minv = np.linalg.inv(M - A2)
    n = 2
    A = np.zeros((2 * n + nl, 2 * n + nl))
    A[: 2 * n, : 2 * n] = (base + c_inf * dC).real
    for j, (beta, cj) in enumerate(zip(rfa.poles, rfa.lags)):
        A[n:2 * n, 2 * n + j] = Minv @ (-qc * float(cj) * beta * (U / b) * w)
        A[2 * n + j, :n] = r0
        A[2 * n + j, n:2 * n] = r1
        A[2 * n + j, 2 * n + j] = -beta * U / b
    return A


def p_method(
    sec: TypicalSection,
    speeds: np.ndarray | None = None,
    *,
    rfa: RogerRFA | None = None,
) -> SectionResult:
    """p-method on ``speeds`` (m/s): eigenvalues of the RFA state space (default fit
    :func:`~windflutter.aero.theodorsen.theodorsen_rfa`); flutter where the largest real part of
    the oscillatory eigenvalues crosses 0 (bracket on the grid, then Brent)."""
    speeds = default_speeds(sec) if speeds is None else check_speeds(speeds)
    rfa = theodorsen_rfa() if rfa is None else rfa
    wscale = float(natural_frequencies(sec).max())

    def modes(U: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        lam, V = np.linalg.eig(rfa_state_matrix(sec, U, rfa))
        osc = np.where(lam.imag > 1e-6 * wscale)[0]
        return lam, V, osc

    lam_grid, sig_max = _p_grid(modes, speeds, 1j * natural_frequencies(sec))

    def f(U: float) -> float:
        lam, _, osc = modes(U)
        return float(lam[osc].real.max()) if osc.size else -1e300

    flutter = None
    idx = np.where((sig_max[:-1] < 0) & (sig_max[1:] >= 0))[0]
    if idx.size:
        i = int(idx[0])
        uf = optimize.brentq(f, speeds[i], speeds[i + 1], xtol=1e-12 * speeds[i + 1])
        lam, V, osc = modes(uf)
        j = osc[np.argmax(lam[osc].real)]
        wf = float(abs(lam[j].imag))
        flutter = (uf, wf, wf * sec.semi_chord / uf, V[:2, j])
    return section_result("p", sec, StabilityCurves.from_roots(speeds, lam_grid), speeds[-1], flutter)


def _p_grid(modes, speeds: np.ndarray, start: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The two structural roots on the grid (nearest match from ``start``; the aero lag roots
    are real) and the largest real part of the oscillatory roots at each speed."""
    nm = 2
    lam_grid = np.full((nm, speeds.size), np.nan + 0j)
    sig_max = np.full(speeds.size, np.nan)
    prev = start
    for i, U in enumerate(speeds):
        lam, _, osc = modes(U)
        lo = lam[osc]
        for m in range(nm):
            if lo.size:
                j = int(np.argmin(np.abs(lo - prev[m])))
                lam_grid[m, i] = lo[j]
        prev = lam_grid[:, i].copy()
        sig_max[i] = lo.real.max() if lo.size else -np.inf
    return lam_grid, sig_max
