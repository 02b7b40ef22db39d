"""Issue 33's IEA 22 MW shell Campbell criteria, 3-25 m/s (docs/verification.md, docs/notes/shell_same_blade.md).

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/shell_campbell_criteria.py OUT_DIR
(three Campbell runs at the defaults of ``windflutter campbell``: the shell (about 13 min single thread
on the loaded 2-core machine), the beam on the file's 6x6 and the beam on the shell's own extracted
properties (40 stations; a minute each); their JSON is written to OUT_DIR and reused when present).

The criteria: no mode below 5 Hz with negative damping (rigid-body modes left out, issue 33 item
4); for the first families (1st and 2nd flap and edge, 1st torsion; BW, FW, collective) at every
wind speed, the shell's mode of that name within 5 % of the beam's frequency and within 1 point
or 35 % of its damping ratio -- at least 90 % of the pairs.  A name missing on either side is a
miss.  Also printed, for reading the misses: the same pairs by content -- on each side the mode with
the largest share of the identity among its two reported participations, whatever its name
(:func:`by_content`).
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import windflutter.api as api
from windflutter.mesh.shell_beam import with_shell_blade_properties
from windflutter.model import load_turbine
from windflutter.system.identity import identity_name

FIRST = [("flap", 1), ("flap", 2), ("edge", 1), ("edge", 2), ("torsion", 1)]
WHIRLS = ("BW", "FW", "collective")


def named(result: dict) -> dict:
    """``{(V, family, order, whirl): mode}`` (the largest share when a name repeats)."""
    out = {}
    for pt in result["points"]:
        for m in pt["modes"]:
            k = (pt["wind_speed"], m["family"], m["order"], m["whirl"])
            if k not in out or m["share"] > out[k]["share"]:
                out[k] = m
    return out


def by_content(result: dict) -> dict:
    """``{(V, family, order, whirl): mode}``: the mode with the largest share of that identity among
    the two participations each mode reports (its name not used)."""
    best = {}
    for pt in result["points"]:
        for m in pt["modes"]:
            for k in (1, 2):
                name, share = m[f"participation_{k}"], m[f"participation_{k}_share"]
                if name and share is not None and share > best.get((pt["wind_speed"], name), (-1.0,))[0]:
                    best[pt["wind_speed"], name] = (share, m)
    return {(v, fam, order, w): best[v, identity_name(fam, w, order)][1]
            for v, _ in best for fam, order in FIRST for w in WHIRLS if (v, identity_name(fam, w, order)) in best}


def pairs(beam: dict, shell: dict, pick=named):
    """(within, total, misses) of the first-family pairs, each side's mode of an identity chosen by
    ``pick`` (:func:`named`, the criterion; :func:`by_content`)."""
    b, s = pick(beam), pick(shell)
    ok, total, misses = 0, 0, []
    for pt in beam["points"]:
        for fam, order in FIRST:
            for w in WHIRLS:
                k = (pt["wind_speed"], fam, order, w)
                total += 1
                if k not in b or k not in s:
                    misses.append((*k, "missing in " + ("shell" if k in b else "beam")))
                    continue
                fb, fs = b[k]["frequency_hz"], s[k]["frequency_hz"]
                zb, zs = b[k]["damping_ratio"], s[k]["damping_ratio"]
                if abs(fs / fb - 1) <= 0.05 and (abs(zs - zb) <= 0.01 or abs(zs / zb - 1) <= 0.35):
                    ok += 1
                else:
                    misses.append((*k, f"f {fs:.3f}/{fb:.3f} Hz, zeta {100 * zs:.2f}/{100 * zb:.2f} %"))
    return ok, total, misses


def negative(result: dict, limit_hz: float = 5.0) -> list:
    return [(pt["wind_speed"], m["name"], round(m["frequency_hz"], 3), round(100 * m["damping_ratio"], 2))
            for pt in result["points"] for m in pt["modes"]
            if m["frequency_hz"] < limit_hz and m["damping_ratio"] < 0 and m["family"] != "rigid"]


def run(out: Path) -> dict:
    t = load_turbine("iea22mw")
    runs = {"shell": (t, "shell"), "beam": (t, "beam")}
    got = {}
    for label in ("shell", "beam", "beam_same_blade"):
        f = out / f"iea22mw_{label}.json"
        if not f.exists():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                tb, model = runs.get(label) or (with_shell_blade_properties(t, 40), "beam")
                f.write_text(json.dumps(api.campbell(tb, model=model).as_dict()))
        got[label] = json.loads(f.read_text())
    return got


def main(out: str) -> None:
    got = run(Path(out))
    for ref in ("beam", "beam_same_blade"):
        ok, total, misses = pairs(got[ref], got["shell"])
        print(f"shell against {ref}: {ok} of {total} pairs within ({100 * ok / total:.1f} %)")
        for m in misses:
            print("   ", m)
        ok, total, _ = pairs(got[ref], got["shell"], pick=by_content)
        print(f"  the same pairs by content (largest participation, names not used): {ok} of {total} "
              f"({100 * ok / total:.1f} %)")
    ok, total, _ = pairs(got["beam"], got["beam_same_blade"])
    print(f"beam on the shell's properties against the file's beam: {ok} of {total} ({100 * ok / total:.1f} %)")
    for label in ("shell", "beam", "beam_same_blade"):
        print(label, "negative damping below 5 Hz (rigid-body modes left out):", negative(got[label]))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
