#!/usr/bin/env python3
"""Generates the meshes (binary STL, closed and outward-oriented) of the robots we author.

Run from anywhere: `python3 robots/generate.py`. The URDF/SRDF/scene files beside it are written by
hand and refer to these meshes through package://octomotion_robots/... URIs (robots/package.xml).
Pure Python, no dependencies, deterministic output.
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def write_stl(path, triangles):
    """Binary STL; each triangle is ((x,y,z),(x,y,z),(x,y,z)) counter-clockwise seen from outside."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(b"octomotion generated mesh".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for a, b, c in triangles:
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            norm = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write(struct.pack("<3f", *[x / norm for x in n]))
            for p in (a, b, c):
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def quad(p0, p1, p2, p3):
    return [(p0, p1, p2), (p0, p2, p3)]


def box(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    t = []
    t += quad(c[0], c[3], c[2], c[1])  # -z
    t += quad(c[4], c[5], c[6], c[7])  # +z
    t += quad(c[0], c[1], c[5], c[4])  # -y
    t += quad(c[2], c[3], c[7], c[6])  # +y
    t += quad(c[1], c[2], c[6], c[5])  # +x
    t += quad(c[3], c[0], c[4], c[7])  # -x
    return t


def revolve(profile, segments, axis="z"):
    """A closed solid of revolution about the z axis from a profile [(r, z), ...] running from the
    bottom pole (r = 0) to the top pole (r = 0). Returns outward-oriented triangles."""
    rings = []
    for r, z in profile:
        ring = []
        for k in range(segments):
            a = 2 * math.pi * k / segments
            ring.append((r * math.cos(a), r * math.sin(a), z))
        rings.append(ring)
    tris = []
    for i in range(len(profile) - 1):
        r0, r1 = profile[i][0], profile[i + 1][0]
        for k in range(segments):
            k1 = (k + 1) % segments
            a, b = rings[i][k], rings[i][k1]
            c, d = rings[i + 1][k1], rings[i + 1][k]
            if r0 == 0:
                tris.append((a, c, d))
            elif r1 == 0:
                tris.append((a, b, c))
            else:
                tris += quad(a, b, c, d)
    # Poles were emitted once per segment with the same point: fine for a closed fan.
    return [orient(t, axis) for t in tris]


def orient(tri, axis):
    if axis == "z":
        return tri
    if axis == "x":  # z -> x, x -> y, y -> z (a proper rotation keeps the orientation)
        return tuple((p[2], p[0], p[1]) for p in tri)
    if axis == "y":  # z -> y, y -> x, x -> z
        return tuple((p[1], p[2], p[0]) for p in tri)
    raise ValueError(axis)


def cylinder(radius, z0, z1, segments=32, axis="z"):
    return revolve([(0, z0), (radius, z0), (radius, z1), (0, z1)], segments, axis)


def capsule(radius, z0, z1, segments=32, stacks=8, axis="z"):
    prof = []
    for i in range(stacks + 1):  # bottom hemisphere, pole first
        a = -math.pi / 2 + (math.pi / 2) * i / stacks
        prof.append((radius * math.cos(a), z0 + radius * math.sin(a)))
    for i in range(stacks + 1):  # top hemisphere
        a = (math.pi / 2) * i / stacks
        prof.append((radius * math.cos(a), z1 + radius * math.sin(a)))
    prof[0] = (0.0, prof[0][1])
    prof[-1] = (0.0, prof[-1][1])
    return revolve(prof, segments, axis)


def shift(tris, d):
    return [tuple((p[0] + d[0], p[1] + d[1], p[2] + d[2]) for p in t) for t in tris]


def extrude(polygon, z0, z1, kernel):
    """A closed prism from a simple polygon [(x, y), ...] given counter-clockwise. The caps are fans
    around `kernel`, a point that sees every edge (the polygons here are star-shaped)."""
    n = len(polygon)
    cx, cy = kernel
    tris = []
    for i in range(n):
        a, b = polygon[i], polygon[(i + 1) % n]
        tris.append(((cx, cy, z1), (a[0], a[1], z1), (b[0], b[1], z1)))
        tris.append(((cx, cy, z0), (b[0], b[1], z0), (a[0], a[1], z0)))
        tris += quad((a[0], a[1], z0), (b[0], b[1], z0), (b[0], b[1], z1), (a[0], a[1], z1))
    return tris


def drone():
    """A plus-shaped frame with four rotor guards floating just above the arm tips; every shell is
    closed and the shells are disjoint, so the solid fill is exact."""
    w, arm = 0.02, 0.17
    plus = [(w, -w), (arm, -w), (arm, w), (w, w), (w, arm), (-w, arm), (-w, w), (-arm, w),
            (-arm, -w), (-w, -w), (-w, -arm), (w, -arm)]
    t = extrude(plus, -0.015, 0.015, (0.0, 0.0))
    for dx, dy in ((arm, 0), (-arm, 0), (0, arm), (0, -arm)):
        t += shift(cylinder(0.06, 0.02, 0.035, 24), (dx, dy, 0))
    return t


def l_piece():
    """An L-shaped bar (30 x 24 cm legs, 6 cm square section), its origin at the corner."""
    a, b, s = 0.30, 0.24, 0.06
    return extrude([(0, 0), (a, 0), (a, s), (s, s), (s, b), (0, b)], 0.0, s, (s / 2, s / 2))


def main():
    m = os.path.join(HERE, "meshes")
    # octo6: an industrial 6-DoF arm (UR-like proportions).
    write_stl(f"{m}/octo6/base.stl", cylinder(0.08, 0.0, 0.1, 40))
    write_stl(f"{m}/octo6/shoulder.stl", cylinder(0.065, 0.0, 0.13, 40))
    write_stl(f"{m}/octo6/upper_arm.stl", capsule(0.055, 0.0, 0.425, 32, 8))
    write_stl(f"{m}/octo6/forearm.stl", capsule(0.045, 0.0, 0.392, 32, 8))
    write_stl(f"{m}/octo6/wrist.stl", cylinder(0.04, -0.05, 0.05, 32, axis="y"))
    # octo7: a 7-DoF arm with a two-finger gripper (iiwa-like in-line proportions: every link
    # frame sits on its joint with z along the chain at the zero configuration).
    write_stl(f"{m}/octo7/link0.stl", cylinder(0.09, 0.0, 0.14, 40))
    write_stl(f"{m}/octo7/link1.stl", capsule(0.065, 0.06, 0.15, 32, 6))
    write_stl(f"{m}/octo7/link2.stl", capsule(0.065, 0.04, 0.17, 32, 6))
    write_stl(f"{m}/octo7/link3.stl", capsule(0.06, 0.05, 0.16, 32, 6))
    write_stl(f"{m}/octo7/link4.stl", capsule(0.06, 0.04, 0.15, 32, 6))
    write_stl(f"{m}/octo7/link5.stl", capsule(0.055, 0.05, 0.17, 32, 6))
    write_stl(f"{m}/octo7/hand.stl", box((-0.025, -0.1, 0.0), (0.025, 0.1, 0.06)))
    write_stl(f"{m}/octo7/finger.stl", box((-0.01, -0.008, 0.0), (0.01, 0.008, 0.05)))
    # Free-flying rigid bodies.
    write_stl(f"{m}/rigid/l_piece.stl", l_piece())
    write_stl(f"{m}/rigid/drone.stl", drone())


if __name__ == "__main__":
    main()
