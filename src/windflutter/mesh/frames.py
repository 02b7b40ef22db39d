"""Rotations placing a blade (root frame) into the global frame (pure functions, SI, rad).

global = origin + R @ p_blade with ``R = R_tilt @ R_azimuth @ R_cone @ R_pitch``:

* pitch ``beta`` about ``-z_b`` (towards feather turns the chord LE -> TE towards +x_b),
* precone ``gamma`` (positive tilts the blade axis upwind, away from the tower),
* azimuth ``psi`` about the shaft (+x, right-handed: the rotor turns clockwise seen from upwind;
  blade 0 up at psi = 0 moves towards -y),
* shaft tilt ``tau`` about +y (raises the upwind end of the shaft).
"""

from __future__ import annotations

import numpy as np


def rot_x(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def blade_rotation(pitch: float, precone: float, azimuth: float, tilt: float) -> np.ndarray:
    """(3, 3) rotation from the blade root frame to the global frame."""
    return rot_y(tilt) @ rot_x(azimuth) @ rot_y(-precone) @ rot_z(-pitch)


def blade_placement(
    apex: np.ndarray, hub_radius: float, pitch: float, precone: float, azimuth: float, tilt: float
) -> tuple[np.ndarray, np.ndarray]:
    """(R, origin): rotation and global position of the blade root (on the pitch axis).

    The root lies ``hub_radius`` from the rotor apex along the coned blade axis.
    """
    R = blade_rotation(pitch, precone, azimuth, tilt)
    origin = np.asarray(apex, dtype=float) + R @ np.array([0.0, 0.0, hub_radius])
    return R, origin
