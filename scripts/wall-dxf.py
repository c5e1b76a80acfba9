#!/usr/bin/env python3
"""Writes a running-bond brick wall as an ASCII DXF drawing, the size of a real facade, to time
`masonry cases import` and `masonry cases show` on drawings of thousands of blocks (README,
"Speed"): COURSES courses of BRICKS bricks 0.25 x 0.125 m (every other course starting and
ending with a half brick), each a closed LWPOLYLINE on layer MASONRY with its id as a TEXT at its
centre, on one ground block on layer SUPPORT; metres ($INSUNITS 6).

    python3 scripts/wall-dxf.py 100 100 /tmp/wall.dxf     # 10,050 bricks and the ground
"""
import sys


def main(courses, bricks, dst):
    L, H = 0.25, 0.125
    out = ["0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n6\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"]
    handle = 0x100

    def poly(layer, pts):
        nonlocal handle
        out.append(f"0\nLWPOLYLINE\n5\n{handle:X}\n8\n{layer}\n90\n{len(pts)}\n70\n1\n")
        handle += 1
        for x, y in pts:
            out.append(f"10\n{x!r}\n20\n{y!r}\n")

    def text(layer, x, y, s):
        nonlocal handle
        out.append(f"0\nTEXT\n5\n{handle:X}\n8\n{layer}\n10\n{x!r}\n20\n{y!r}\n40\n0.02\n1\n{s}\n")
        handle += 1

    width = bricks * L
    poly("SUPPORT", [(-0.5, -0.3), (width + 0.5, -0.3), (width + 0.5, 0.0), (-0.5, 0.0)])
    text("SUPPORT", width / 2, -0.15, "ground")
    for r in range(courses):
        y0, y1 = r * H, (r + 1) * H
        edges = [k * L for k in range(bricks + 1)] if r % 2 == 0 else [0.0] + [(k + 0.5) * L for k in range(bricks)] + [width]
        for k in range(len(edges) - 1):
            x0, x1 = edges[k], edges[k + 1]
            poly("MASONRY", [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
            text("MASONRY", (x0 + x1) / 2, (y0 + y1) / 2, f"b{r}-{k}")
    out.append("0\nENDSEC\n0\nEOF\n")
    with open(dst, "w") as f:
        f.write("".join(out))


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]), sys.argv[3])
