#!/usr/bin/env python3
"""An outside solver for `masonry validate --solver`: one rigid block on a moving support, by
closed-form statics. Written from the published formats only (schemas/masonry-case.schema.json
in, schemas/masonry-results.schema.json out) and the README's section "Gate your own solver in
CI"; it shares no code with masonry.

    python3 examples/toppling_solver.py CASE OUT_DIR [--name NAME]

reads CASE (masonry-case/1) and writes OUT_DIR/results.json (masonry-results/1).

The model, as a limit-analysis code would see it (no sliding, rigid blocks, dead loads):
the case must have exactly one free block, resting on one flat face of one support block. The
block rides on the support, which moves by `translation * d` and turns by `rotation * d` about
`about` (motion.supports). At each d = k * step the block stands when the resultant of its
loads (its weight and the point loads, fixed in direction) presses on the contact face and its
line of action crosses the face between its ends; otherwise it turns about the face's end: the
capacity is the last d at which it stands. Sliding is not modelled (like PRD): a block judged
on a friction benchmark is out of this solver's scope.

Standard library only. Exit status 0 whenever it wrote results.json, including results that
say `"stopped": "error"` (a case outside the model above, with the reason in `message`), so
that the harness shows the reason; 2 when it could not even read its arguments.
"""
import argparse
import json
import math
import os
import sys

VERSION = "toppling_solver.py 1.0"


def polygon_area_centroid(pts):
    """Signed area and centroid of a simple polygon (shoelace)."""
    a = cx = cy = 0.0
    n = len(pts)
    for i in range(n):
        x0, y0 = pts[i]
        x1, y1 = pts[(i + 1) % n]
        cross = x0 * y1 - x1 * y0
        a += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    a *= 0.5
    return a, (cx / (6 * a), cy / (6 * a))


def cross(ax, ay, bx, by):
    return ax * by - ay * bx


def contact_segments(block, support, tol):
    """Pieces of the block's edges lying on the support's edges (collinear, overlapping)."""
    out = []
    pb, ps = block, support
    for i in range(len(pb)):
        p0, p1 = pb[i], pb[(i + 1) % len(pb)]
        for j in range(len(ps)):
            q0, q1 = ps[j], ps[(j + 1) % len(ps)]
            ux, uy = q1[0] - q0[0], q1[1] - q0[1]
            length = math.hypot(ux, uy)
            if length == 0:
                continue
            ux, uy = ux / length, uy / length
            # Both ends of the block's edge on the support edge's line.
            if any(abs(cross(ux, uy, p[0] - q0[0], p[1] - q0[1])) > tol for p in (p0, p1)):
                continue
            s0 = (p0[0] - q0[0]) * ux + (p0[1] - q0[1]) * uy
            s1 = (p1[0] - q0[0]) * ux + (p1[1] - q0[1]) * uy
            lo, hi = max(min(s0, s1), 0.0), min(max(s0, s1), length)
            if hi - lo > tol:
                out.append(((q0[0] + lo * ux, q0[1] + lo * uy), (q0[0] + hi * ux, q0[1] + hi * uy), (-uy, ux)))
    return out


def moved(point, motion, d):
    """A point attached to the support, after the support motion up to d."""
    tx, ty, rate, (ax, ay) = motion
    th = rate * d
    c, s = math.cos(th), math.sin(th)
    x, y = point[0] - ax, point[1] - ay
    return (ax + c * x - s * y + tx * d, ay + s * x + c * y + ty * d)


def turned(vector, motion, d):
    th = motion[2] * d
    c, s = math.cos(th), math.sin(th)
    return (c * vector[0] - s * vector[1], s * vector[0] + c * vector[1])


class OutOfScope(Exception):
    pass


def solve(case):
    g = case.get("gravity", 9.81)
    blocks = case["blocks"]
    tol = case.get("prd", {}).get("contact_tolerance", 1e-5)
    free = [b for b in blocks if not b.get("support", False)]
    if len(free) != 1:
        raise OutOfScope(f"this solver handles one free block; the case has {len(free)}")
    block = free[0]
    touching = []
    for b in blocks:
        if b is block or not b.get("support", False):
            continue
        segs = contact_segments(block["vertices"], b["vertices"], tol)
        if segs:
            touching.append((b, segs))
    if len(touching) != 1:
        raise OutOfScope(f"the block must rest on one support; it touches {len(touching)}")
    support, segs = touching[0]
    # One flat face: every piece on one line, the face's ends the extreme points along it.
    (a0, a1, normal) = segs[0]
    ux, uy = -normal[1], normal[0]
    for (p, q, n) in segs[1:]:
        if abs(cross(n[0], n[1], normal[0], normal[1])) > 1e-9 or abs((p[0] - a0[0]) * normal[0] + (p[1] - a0[1]) * normal[1]) > tol:
            raise OutOfScope("the block rests on more than one face of its support")
    along = [(pt[0] * ux + pt[1] * uy, pt) for seg in segs for pt in seg[:2]]
    face = (min(along)[1], max(along)[1])
    # The outward normal of the support at the face points into the block: check with the
    # block's centroid.
    area, centroid = polygon_area_centroid(block["vertices"])
    if (centroid[0] - face[0][0]) * normal[0] + (centroid[1] - face[0][1]) * normal[1] < 0:
        normal = (-normal[0], -normal[1])

    depth = block.get("depth", 1.0)
    loads = [((0.0, -block["density"] * g * abs(area) * depth), centroid)]
    for load in case.get("loads", []):
        loads.append((tuple(load["force"]), tuple(load.get("point", centroid))))
    fx = sum(f[0] for f, _ in loads)
    fy = sum(f[1] for f, _ in loads)

    motion_spec = case.get("motion", {})
    step = motion_spec.get("step", 0.001)
    max_steps = motion_spec.get("max_steps", 1000)
    motions = {}
    for m in motion_spec.get("supports", []):
        b = next(x for x in blocks if x["id"] == m["block"])
        about = tuple(m["about"]) if "about" in m else polygon_area_centroid(b["vertices"])[1]
        t = m.get("translation", [0.0, 0.0])
        motions[m["block"]] = (t[0], t[1], m.get("rotation", 0.0), about)
    fixed = (0.0, 0.0, 0.0, (0.0, 0.0))
    carrier = motions.get(support["id"], fixed)

    def record(k, d):
        """The configuration at d, or None where the block does not stand."""
        p, q = moved(face[0], carrier, d), moved(face[1], carrier, d)
        n = turned(normal, carrier, d)
        # Moment of the loads about the origin, each load at its material point carried along.
        moment = sum(cross(*moved(pt, carrier, d), f[0], f[1]) for f, pt in loads)
        denom = cross(q[0] - p[0], q[1] - p[1], fx, fy)
        if fx * n[0] + fy * n[1] >= 0 or denom == 0:
            return None  # the loads do not press on the face
        t = (moment - cross(p[0], p[1], fx, fy)) / denom
        if t < 0 or t > 1:
            return None  # the line of action passes beyond the face: the block turns about its end
        x = (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))  # where the resultant bears
        energy = -sum(f[0] * (moved(pt, carrier, d)[0] - pt[0]) + f[1] * (moved(pt, carrier, d)[1] - pt[1]) for f, pt in loads)
        about = moved(carrier[3], carrier, d)
        rx, ry = -fx, -fy  # the force the block receives from its support
        reactions = [{"support": support["id"], "force": [rx, ry], "moment": cross(x[0] - about[0], x[1] - about[1], rx, ry)}]
        for other in blocks:  # every other support carries nothing
            if other.get("support", False) and other is not support:
                reactions.append({"support": other["id"], "force": [0.0, 0.0], "moment": 0.0})
        poses = []
        for b in blocks:
            m = carrier if b is block else motions.get(b["id"], fixed)
            c0 = polygon_area_centroid(b["vertices"])[1]
            c1 = moved(c0, m, d)
            poses.append([c1[0], c1[1], m[2] * d])
        return {"step": k, "d": d, "energy": energy, "reactions": reactions, "poses": poses}

    steps = []
    stopped = "max_steps"
    for k in range(max_steps + 1):
        r = record(k, k * step)
        if r is None:
            stopped = "collapse"
            break
        steps.append(r)
    capacity = steps[-1]["d"] if steps else 0.0
    return {"capacity": capacity, "stopped": stopped, "stable_steps": steps[-1]["step"] if steps else 0, "steps": steps}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case")
    parser.add_argument("out")
    parser.add_argument("--name", default="toppling-closed-form")
    args = parser.parse_args()
    with open(args.case) as f:
        case = json.load(f)
    results = {"format": "masonry-results/1", "version": VERSION, "method": args.name, "case": case.get("name", args.case)}
    try:
        results.update(solve(case))
    except OutOfScope as e:
        results.update({"capacity": 0.0, "stopped": "error", "message": str(e), "steps": []})
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
