"""Small linear-algebra helpers used across the layers (bottom layer: imports only NumPy).

* :func:`skew` -- the cross-product matrix, ``skew(v) @ b == cross(v, b)``, vectorised;
* :func:`mac`, :func:`mac_matrix` -- the modal assurance criterion of two vectors and of every
  column of one matrix against every column of another (Allemang & Brown 1982), with the
  Hermitian inner product so complex mode shapes are compared up to a complex factor.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["skew", "mac", "mac_matrix"]


def skew(v: ArrayLike) -> np.ndarray:
    """(..., 3, 3) cross-product matrices of the vectors ``v`` (..., 3): ``skew(v) @ b = v x b``."""
    v = np.asarray(v, dtype=float)
    S = np.zeros(v.shape[:-1] + (3, 3))
    S[..., 0, 1], S[..., 0, 2] = -v[..., 2], v[..., 1]
    S[..., 1, 0], S[..., 1, 2] = v[..., 2], -v[..., 0]
    S[..., 2, 0], S[..., 2, 1] = -v[..., 1], v[..., 0]
    return S


def mac(a: np.ndarray, b: np.ndarray) -> float:
    """Modal assurance criterion ``|a^H b|^2 / ((a^H a)(b^H b))`` of two vectors (0..1; 0 if
    either is zero)."""
    num = abs(np.vdot(a, b)) ** 2
    den = np.vdot(a, a).real * np.vdot(b, b).real
    return float(num / den) if den > 0 else 0.0


def mac_matrix(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """MAC of every column of ``A`` (rows of the result) against every column of ``B``
    (columns); 0 for a zero column."""
    A, B = np.asarray(A), np.asarray(B)
    num = np.abs(A.conj().T @ B) ** 2
    den = np.outer(np.sum(np.abs(A) ** 2, axis=0), np.sum(np.abs(B) ** 2, axis=0))
    return num / np.where(den > 0, den, 1.0)


def congruence(B: np.ndarray, A: np.ndarray) -> np.ndarray:
    """``B[e]^T A[e] B[e]`` for stacks of element matrices (``(..., k, i)``, ``(..., k, k)`` ->
    ``(..., i, i)``) by batched matmul: the same as ``einsum("eki,ekl,elj->eij", B, A, B)``, whose
    unoptimized three-operand loop took 30-80x longer on beam element stacks (0.3-0.9 ms against
    0.01 ms for 30 elements)."""
    return np.swapaxes(B, -1, -2) @ A @ B
