"""Beam section <-> PBEAM / PBAR values.

PBEAM is written with a unit-modulus MAT1 (E = 1 Pa, nu = 0.3) so that A = EA, I1 = EIz,
I2 = EIy, I12 = -EIyz, J = GJ/G, K1 = GAy/(G A), K2 = GAz/(G A); all mass as non-structural
mass: NSM = m, M1/M2 = mass-centre offset, NSI = torsional inertia about it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.structure.fem import BeamSection

#: Unit-modulus material used for beams (stiffnesses are carried by the PBEAM "geometry").
BEAM_E = 1.0
BEAM_NU = 0.3
BEAM_G = BEAM_E / (2.0 * (1.0 + BEAM_NU))
#: relative tolerance for "the card still holds the value we wrote" (16-character fields)
CARD_RTOL = 1e-8


@dataclass(frozen=True)
class BeamCardValues:
    """The values a PBEAM (with the unit-modulus MAT1) carries, in windflutter terms (SI)."""

    EA: float
    GAy: float
    GAz: float
    GJ: float
    EIy: float
    EIz: float
    EIyz: float
    m: float
    cy: float
    cz: float
    nsi: float  # torsional mass inertia about the mass centre (kg m^2/m)
    Iyy_m: float = 0.0  # rotary inertia (only from a structural density on foreign decks)
    Izz_m: float = 0.0
    Iyz_m: float = 0.0

    @staticmethod
    def from_section(sec: BeamSection) -> "BeamCardValues":
        K = np.asarray(sec.stiffness, dtype=float)
        M = np.asarray(sec.mass, dtype=float)
        m = float(M[0, 0])
        cy = float(M[3, 2] / m) if m > 0 else 0.0
        cz = float(-M[3, 1] / m) if m > 0 else 0.0
        return BeamCardValues(
            EA=K[0, 0], GAy=K[1, 1], GAz=K[2, 2], GJ=K[3, 3], EIy=K[4, 4], EIz=K[5, 5],
            EIyz=0.5 * (K[4, 5] + K[5, 4]), m=m, cy=cy, cz=cz,
            nsi=float(M[3, 3] - m * (cy * cy + cz * cz)),
        )

    def section(self, name: str = "") -> BeamSection:
        """The BeamSection these card values represent exactly."""
        K = np.diag([self.EA, self.GAy, self.GAz, self.GJ, self.EIy, self.EIz]).astype(float)
        K[4, 5] = K[5, 4] = self.EIyz
        m, cy, cz = self.m, self.cy, self.cz
        S = np.array([[0.0, -cz, cy], [cz, 0.0, 0.0], [-cy, 0.0, 0.0]])
        M = np.zeros((6, 6))
        M[:3, :3] = m * np.eye(3)
        M[3:, :3] = m * S
        M[:3, 3:] = (m * S).T
        M[3, 3] = self.nsi + m * (cy * cy + cz * cz)
        M[4, 4] = self.Iyy_m + m * cz * cz
        M[5, 5] = self.Izz_m + m * cy * cy
        M[4, 5] = M[5, 4] = self.Iyz_m - m * cy * cz
        return BeamSection(stiffness=K, mass=M, name=name)

    def as_list(self) -> list[float]:
        return [self.EA, self.GAy, self.GAz, self.GJ, self.EIy, self.EIz, self.EIyz, self.m,
                self.cy, self.cz, self.nsi]

    def pbeam_fields(self, pid: int, mid: int) -> dict:
        """The PBEAM fields (by QRG name) of these values, constant section (end B = end A)."""
        A = self.EA / BEAM_E
        station = {"A": A, "I1": self.EIz / BEAM_E, "I2": self.EIy / BEAM_E, "I12": -self.EIyz / BEAM_E,
                   "J": self.GJ / BEAM_G, "NSM": self.m}
        zeros = dict.fromkeys(("C1", "C2", "D1", "D2", "E1", "E2", "F1", "F2"), 0.0)
        return {"PID": pid, "MID": mid, **station, **zeros, "SO": "YESA", "X/XB": 1.0,
                **{f"{k}(B)": v for k, v in station.items()},
                "K1": self.GAy / (BEAM_G * A), "K2": self.GAz / (BEAM_G * A), "S1": 0.0, "S2": 0.0,
                "NSI(A)": self.nsi, "NSI(B)": self.nsi, "CW(A)": 0.0, "CW(B)": 0.0,
                "M1(A)": self.cy, "M2(A)": self.cz, "M1(B)": self.cy, "M2(B)": self.cz,
                "N1(A)": 0.0, "N2(A)": 0.0, "N1(B)": 0.0, "N2(B)": 0.0}


def close(a: list[float], b: list[float]) -> bool:
    """``a`` and ``b`` agree to :data:`CARD_RTOL` entry by entry (offsets against the group's scale)."""
    a_, b_ = np.asarray(a, float), np.asarray(b, float)
    scale = np.maximum(np.abs(a_), np.abs(b_))
    # lengths (cg offsets) are compared against the overall magnitude of the entry group
    return bool(np.all(np.abs(a_ - b_) <= CARD_RTOL * np.maximum(scale, 1e-12 * np.max(scale) + 1e-300)))


def dropped_terms(sec: BeamSection, rep: BeamSection) -> str:
    """Describe the section entries the standard cards lose (empty if none)."""
    msgs = []
    for label, full, part in (("stiffness", sec.stiffness, rep.stiffness), ("mass", sec.mass, rep.mass)):
        full = np.asarray(full, float)
        diff = np.abs(full - part)
        ref = np.max(np.abs(np.diag(full))) or 1.0
        bad = np.argwhere(diff > 1e-9 * ref)
        bad = [(int(i), int(j)) for i, j in bad if i <= j]
        if bad:
            rel = float(np.max(diff) / ref)
            msgs.append(f"{label} entries {bad} (max {rel:.2e} of the largest diagonal term)")
    return "; ".join(msgs)


def beam_values(E, G, rho, A, I1, I2, I12, J, nsm, k1, k2, nsi, m1, m2) -> BeamCardValues:
    """Section values of a PBEAM / PBAR with material (E, G, rho) and non-structural mass."""
    EA = E * A
    big = 1e3 * max(EA, 1.0)  # K = 0 means shear-rigid in NASTRAN; same stand-in as BeamSection.from_properties
    m = rho * A + nsm
    cy = nsm * m1 / m if m > 0 else 0.0
    cz = nsm * m2 / m if m > 0 else 0.0
    # torsional inertia about the mass centre: structure (rho J_polar about the axis) + NSM part
    ixx = rho * (I1 + I2) + nsi + nsm * (m1 * m1 + m2 * m2)
    return BeamCardValues(
        EA=EA, GAy=k1 * G * A if k1 > 0 else big, GAz=k2 * G * A if k2 > 0 else big, GJ=G * J,
        EIy=E * I2, EIz=E * I1, EIyz=-E * I12, m=m, cy=cy, cz=cz, nsi=ixx - m * (cy * cy + cz * cz),
        Iyy_m=rho * I2, Izz_m=rho * I1, Iyz_m=-rho * I12,
    )
