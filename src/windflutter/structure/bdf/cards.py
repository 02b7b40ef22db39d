"""The NASTRAN bulk-data cards windflutter writes and reads: one table per card.

Each :class:`Card` lists its fields in order with the name of the MSC/NX Quick Reference Guide,
the type (``I`` integer, ``R`` real, ``C`` character) and, for the cards :func:`read_bdf` takes,
the attribute of pyNastran's card object that holds the value and the value of a blank field.
The writer fills a card by field name (:meth:`Card.text`), the reader gets the named values
back (:meth:`Card.read`), so the two directions share one field list per card.

Cards are written in large-field fixed format: 16-character fields, four per line, ``*``
continuations (each small-field line of eight fields becomes two lines).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from windflutter.errors import InputError

class BdfApproximationWarning(UserWarning):
    """Part of the model cannot be represented exactly by standard NASTRAN cards."""


#: width (characters) of a large-field data field; the card name / continuation field is 8
FIELD_WIDTH = 16
NAME_WIDTH = 8


@dataclass(frozen=True)
class Field:
    """One field of a card: QRG name, type ``I``/``R``/``C``, pyNastran attribute, blank value.

    ``attr`` may index a sequence attribute (``"node_ids[2]"``); None: the field is not read.
    """

    name: str
    kind: str
    attr: str | None = None
    blank: Any = None


@dataclass(frozen=True)
class Card:
    """A card's field table.

    ``repeat`` is a group of fields repeated to the end of the card (plies, grid lists);
    ``parsed`` are values pyNastran derives from shared fields (e.g. G0 or X1..X3 from the
    ``X1/G0`` field), read but never written.
    """

    name: str
    fields: tuple[Field, ...]
    repeat: tuple[Field, ...] = ()
    parsed: tuple[Field, ...] = ()

    def text(self, rows: list[tuple] = (), **values: Any) -> str:
        """The card in large-field format from field values by name and the repeated group's
        ``rows`` (tuples in the order of ``repeat``).

        A field given as None, or not given but before one that is, is blank; the card ends
        after the last field given (all fixed fields when there are ``rows``).
        """
        names = [f.name for f in self.fields]
        unknown = set(values) - set(names)
        if unknown:
            raise KeyError(f"{self.name} has no field(s) {sorted(unknown)}")
        n = len(names) if rows else max((names.index(k) + 1 for k in values), default=0)
        out = [_typed(self.name, f, values.get(f.name)) for f in self.fields[:n]]
        for row in rows:
            if len(row) != len(self.repeat):
                raise ValueError(f"{self.name}: a repeated group has {len(self.repeat)} fields")
            out += [_typed(self.name, f, v) for f, v in zip(self.repeat, row)]
        return card_text(self.name, out)

    def read(self, obj: Any) -> dict[str, Any]:
        """Named values of the fields with an ``attr`` from a pyNastran card object.

        Scalars are converted to the field's type; a blank (None) field gives ``blank``;
        sequences (per-station PBEAM values, lists of plies or grids) are returned as they are.
        """
        out = {}
        for f in self.fields + self.repeat + self.parsed:
            if f.attr is None:
                continue
            v = _attribute(obj, f.attr)
            if v is None:
                out[f.name] = f.blank
            elif np.ndim(v) == 0 and not isinstance(v, (list, tuple)):
                out[f.name] = _CAST[f.kind](v)
            else:
                out[f.name] = v
        return out


def _attribute(obj: Any, attr: str) -> Any:
    name, _, index = attr.partition("[")
    v = getattr(obj, name, None)
    if index and v is not None:
        seq = list(v)
        i = int(index.rstrip("]"))
        v = seq[i] if i < len(seq) else None
    return v


def _int_or_real(v: Any) -> int | float:
    return int(v) if isinstance(v, (int, np.integer)) else float(v)


#: field types: I integer, R real, C character, IR integer or real (THETA/MCID: an integer
#: is a coordinate-system id, a real an angle)
_CAST = {"I": int, "R": float, "C": str, "IR": _int_or_real}


def _typed(card: str, f: Field, v: Any) -> Any:
    """``v`` as the Python type the formatter writes for field ``f`` (None stays blank)."""
    if v is None:
        return None
    if isinstance(v, (bool, np.bool_)):
        raise InputError(f"{card}.{f.name}", v, "an integer, real or string")
    return _CAST[f.kind](v)


# --------------------------------------------------------------------------------------
# large-field formatting
# --------------------------------------------------------------------------------------
def real16(x: float) -> str:
    """Format a real in at most 16 characters with as many significant digits as fit."""
    x = float(x)
    if not math.isfinite(x):
        raise InputError("BDF real field", x, "a finite number")
    if x == 0.0:
        return "0.0"
    # shortest general format that fits in 15 characters (keeps a blank between fields)
    for p in range(17, 8, -1):
        s = format(x, f".{p}g")
        mant, _, exp = s.partition("e")
        if "." not in mant:
            mant += "."
        s = mant + ("e" + exp if exp else "")
        if len(s) <= 15:
            return s
    for p in range(10, 0, -1):
        s = f"{x:.{p}e}"
        if len(s) <= FIELD_WIDTH:
            return s
    raise InputError("BDF real field", x, "a number representable in 16 characters")


def field16(v: Any) -> str:
    """One right-justified 16-character field: int, real (:func:`real16`), string or blank."""
    if v is None:
        return " " * FIELD_WIDTH
    if isinstance(v, (bool, np.bool_)):
        raise InputError("BDF field", v, "an integer, real or string")
    if isinstance(v, (int, np.integer)):
        s = str(int(v))
    elif isinstance(v, (float, np.floating)):
        s = real16(float(v))
    else:
        s = str(v)
    if len(s) > FIELD_WIDTH:
        raise InputError("BDF field", s, "at most 16 characters")
    return s.rjust(FIELD_WIDTH)


def card_text(name: str, fields: list[Any]) -> str:
    """One card in large-field format: each small-field line (8 fields) becomes two lines."""
    lines = []
    nchunks = max(1, math.ceil(len(fields) / 8))
    for i in range(nchunks):
        chunk = list(fields[8 * i : 8 * i + 8])
        head = (name + "*") if i == 0 else "*"
        lines.append(head.ljust(NAME_WIDTH) + "".join(field16(v) for v in chunk[:4]).rstrip())
        if len(chunk) > 4:
            lines.append("*".ljust(NAME_WIDTH) + "".join(field16(v) for v in chunk[4:8]).rstrip())
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------------------
# the card tables (MSC Nastran Quick Reference Guide field names)
# --------------------------------------------------------------------------------------
def _f(spec: str) -> tuple[Field, ...]:
    """Fields from ``"NAME:KIND[:attr[:blank]]"`` words (``blank`` a number, cast to KIND)."""
    out = []
    for word in spec.split():
        name, kind, *rest = word.split(":")
        attr = rest[0] if rest and rest[0] else None
        blank = _CAST[kind](float(rest[1])) if len(rest) > 1 else None
        out.append(Field(name, kind, attr, blank))
    return tuple(out)


#: PBEAM's section values at end A (at end B the same names with "(B)")
_STATION = "A:R:A I1:R:i1 I2:R:i2 I12:R:i12 J:R:j NSM:R:nsm"
_BAR_CONNECTION = ("EID:I:eid PID:I:pid GA:I:ga GB:I:gb X1:R X2:R X3:R OFFT:C PA:I:pa:0 PB:I:pb:0 "
                   "W1A:R W2A:R W3A:R W1B:R W2B:R W3B:R")
#: what pyNastran parses from the shared X1/G0 and the offset fields of CBAR / CBEAM
_BAR_PARSED = "G0:I:g0 X:R:x WA:R:wa WB:R:wb"

CARDS = {c.name: c for c in (
    Card("EIGRL", _f("SID:I V1:R V2:R ND:I")),
    Card("GRID", _f("ID:I CP:I X1:R X2:R X3:R")),
    Card("CORD2R", _f("CID:I RID:I A1:R A2:R A3:R B1:R B2:R B3:R C1:R C2:R C3:R")),
    Card("MAT1", _f("MID:I:mid E:R:e G:R:g NU:R:nu RHO:R:rho:0")),
    Card("MAT8", _f("MID:I:mid E1:R:e11 E2:R:e22 NU12:R:nu12 G12:R:g12 G1Z:R:g1z G2Z:R:g2z "
                    "RHO:R:rho:0")),
    Card("PSHELL", _f("PID:I:pid MID1:I:mid1 T:R:t MID2:I:mid2 12I/T**3:R:twelveIt3:1 MID3:I "
                      "TS/T:R NSM:R:nsm:0")),
    Card("PCOMP", _f("PID:I:pid Z0:R:z0 NSM:R:nsm:0 SB:R FT:C TREF:R GE:R LAM:C:lam"),
         repeat=_f("MID:I:mids T:R:thicknesses THETA:R:thetas SOUT:C")),
    Card("CQUAD4", _f("EID:I:eid PID:I:pid G1:I:node_ids[0] G2:I:node_ids[1] G3:I:node_ids[2] "
                      "G4:I:node_ids[3] THETA/MCID:IR:theta_mcid ZOFFS:R:zoffset:0")),
    Card("PBEAM", _f("PID:I:pid MID:I:mid " + _STATION + " C1:R C2:R D1:R D2:R E1:R E2:R F1:R F2:R "
                     "SO:C X/XB:R A(B):R I1(B):R I2(B):R I12(B):R J(B):R NSM(B):R "
                     "K1:R:k1:1 K2:R:k2:1 S1:R S2:R NSI(A):R:nsia:0 NSI(B):R CW(A):R CW(B):R "
                     "M1(A):R:m1a:0 M2(A):R:m2a:0 M1(B):R M2(B):R "
                     "N1(A):R:n1a:0 N2(A):R:n2a:0 N1(B):R:n1b:0 N2(B):R:n2b:0")),
    Card("PBAR", _f("PID:I:pid MID:I:mid A:R:A I1:R:i1 I2:R:i2 J:R:j NSM:R:nsm:0 BLANK:R C1:R C2:R D1:R D2:R "
                    "E1:R E2:R F1:R F2:R K1:R:k1:0 K2:R:k2:0 I12:R:i12:0")),
    Card("CBEAM", _f(_BAR_CONNECTION), parsed=_f(_BAR_PARSED)),
    Card("CBAR", _f(_BAR_CONNECTION), parsed=_f(_BAR_PARSED)),
    Card("CONM2", _f("EID:I:eid G:I:nid CID:I:cid M:R:mass X1:R:X[0] X2:R:X[1] X3:R:X[2] BLANK:R "
                     "I11:R I21:R I22:R I31:R I32:R I33:R")),
    Card("RBE2", _f("EID:I:eid GN:I:gn CM:C:cm"), repeat=_f("GM:I:Gmi")),
    Card("CELAS1", _f("EID:I:eid PID:I:pid G1:I:node_ids[0] C1:I:c1:0 G2:I:node_ids[1] C2:I:c2:0")),
    Card("CELAS2", _f("EID:I:eid K:R:k G1:I:node_ids[0] C1:I:c1:0 G2:I:node_ids[1] C2:I:c2:0")),
    Card("SPC1", _f("SID:I C:C:components"), repeat=_f("G:I:node_ids")),
    # two (grid, component, coefficient) terms per line, the last field and the continuation's first
    # blank: the repeated group spans one small-field line (the card is written, not read)
    Card("MPC", _f("SID:I"), repeat=_f("G1:I C1:I A1:R G2:I C2:I A2:R B1:I B2:I")),
    Card("SPC", _f("SID:I"), repeat=_f("G:I:node_ids C:C:components D:R:enforced")),
)}
