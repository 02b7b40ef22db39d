"""Structural damping matrices: Rayleigh (mass/stiffness proportional) and modal damping."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.structure.assembly import Structural


def rayleigh_coefficients(f1: float, f2: float, zeta1: float, zeta2: float | None = None) -> tuple[float, float]:
    """Rayleigh coefficients (alpha 1/s, beta s) giving damping ratios zeta1, zeta2 at f1, f2 (Hz).

    zeta(omega) = alpha / (2 omega) + beta omega / 2.
    """
    zeta2 = zeta1 if zeta2 is None else zeta2
    w1, w2 = 2 * np.pi * float(f1), 2 * np.pi * float(f2)
    if not (w1 > 0 and w2 > 0 and w1 != w2):
        raise InputError("f1/f2", (f1, f2), "two different positive frequencies (Hz)")
    A = np.array([[1 / (2 * w1), w1 / 2], [1 / (2 * w2), w2 / 2]])
    alpha, beta = np.linalg.solve(A, [zeta1, zeta2])
    return float(alpha), float(beta)


def damping_matrix(
    struct: Structural,
    kind: str = "rayleigh",
    alpha: float = 0.0,
    beta: float = 0.0,
    modes=None,
    zeta: float | np.ndarray | None = None,
    reduced: bool = False,
) -> sp.csr_matrix | np.ndarray:
    """Structural damping matrix.

    Parameters
    ----------
    struct : assembled structure.
    kind : ``"rayleigh"`` (``D = alpha M + beta K``; use ``alpha=0`` for stiffness-proportional,
        ``beta=0`` for mass-proportional) or ``"modal"``.
    alpha : mass-proportional coefficient (1/s).
    beta : stiffness-proportional coefficient (s).
    modes : :class:`~windflutter.structure.modal.Modes` (kind="modal"), unit modal mass.
    zeta : damping ratio(s) (-) of those modes (kind="modal"); scalar or one per mode.
    reduced : return the matrix in reduced coordinates q (``T^T D T``) instead of the full numbering.

    Returns
    -------
    D : CSR for "rayleigh"; for "modal" a dense (n, n) array in the requested numbering,
        ``D = M Phi diag(2 zeta omega) Phi^T M`` so that ``Phi^T D Phi = diag(2 zeta omega)``.
        Unretained modes get no damping.
    """
    if kind == "rayleigh":
        for name, v in (("alpha", alpha), ("beta", beta)):
            if not np.isfinite(v) or v < 0:
                raise InputError(name, v, "a finite non-negative Rayleigh coefficient")
        if reduced:
            return (alpha * struct.Mr + beta * struct.Kr).tocsr()
        return (alpha * struct.M + beta * struct.K).tocsr()
    if kind == "modal":
        if modes is None or zeta is None:
            raise InputError("modes/zeta", None, "a Modes result and damping ratio(s) for kind='modal'")
        z = np.broadcast_to(np.asarray(zeta, dtype=float), modes.freq.shape)
        if np.any(~np.isfinite(z)) or np.any(z < 0):
            raise InputError("zeta", zeta, "finite non-negative damping ratios")
        omega = 2 * np.pi * np.abs(modes.freq)
        if reduced:
            MP = struct.Mr @ modes.q
        else:
            MP = struct.M @ modes.shapes
        return (MP * (2 * z * omega)[None, :]) @ MP.T
    raise InputError("kind", kind, "'rayleigh' or 'modal'")
