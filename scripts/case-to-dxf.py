#!/usr/bin/env python3
"""Writes a case file's blocks as an ASCII DXF drawing (AutoCAD R12 entities), the way a CAD
user would draw them: each block a closed POLYLINE, supports on layer SUPPORT, the others on
layer MASONRY, each block's id as a TEXT at its centroid, units metres ($INSUNITS 6). Motion,
loads and solver settings are not geometry: `masonry cases import --merge` adds them back.
Densities and depths are not written either: the import takes them from its layers or options
(--density, --layers), depth 1 m by default, so a wall of depth 0.25 m comes back four times as
heavy unless its layer says otherwise.

    python3 scripts/case-to-dxf.py cases/pointed-arch.json cases/drawings/pointed-arch.dxf
"""
import json
import sys


def centroid(v):
    a = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1]):
        w = x0 * y1 - x1 * y0
        a += w
        cx += w * (x0 + x1)
        cy += w * (y0 + y1)
    return cx / (3 * a), cy / (3 * a)


def main(src, dst):
    case = json.load(open(src))
    out = []

    def put(code, value):
        out.append(f"{code}\n{value}\n")

    put(0, "SECTION"); put(2, "HEADER"); put(9, "$INSUNITS"); put(70, 6); put(0, "ENDSEC")
    put(0, "SECTION"); put(2, "ENTITIES")
    handle = 0x100
    for b in case["blocks"]:
        layer = "SUPPORT" if b.get("support") else "MASONRY"
        put(0, "POLYLINE"); put(5, f"{handle:X}"); put(8, layer); put(66, 1); put(70, 1)
        handle += 1
        for x, y in b["vertices"]:
            put(0, "VERTEX"); put(5, f"{handle:X}"); put(8, layer); put(10, repr(float(x))); put(20, repr(float(y)))
            handle += 1
        put(0, "SEQEND"); put(5, f"{handle:X}"); put(8, layer)
        handle += 1
        cx, cy = centroid(b["vertices"])
        put(0, "TEXT"); put(5, f"{handle:X}"); put(8, layer); put(10, repr(cx)); put(20, repr(cy)); put(40, 0.02); put(1, b["id"])
        handle += 1
    put(0, "ENDSEC"); put(0, "EOF")
    open(dst, "w").write("".join(out))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
