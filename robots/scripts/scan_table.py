#!/usr/bin/env python3
"""Simulates a depth-camera scan of a table scene and writes it as a binary PCD point cloud.

The scene (a table with a crate, a thermos, a tray and a cup on it) is made of upright boxes and
vertical cylinders. A pinhole camera above and behind the robot casts one ray per pixel; the
nearest hit becomes a point, displaced along its ray by Gaussian depth noise (fixed seed), as a
structured-light or time-of-flight sensor would report it. Pixels that see nothing are dropped,
and so is the floor (as a ground-plane filter would), so the cloud only holds the obstacles.

Run from anywhere: `python3 robots/scripts/scan_table.py` rewrites
robots/scenes/scan_table.pcd, which robots/scenes/scan_table.yaml loads. Pure Python standard
library, deterministic output.
"""
import argparse
import math
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_OUT = os.path.normpath(os.path.join(HERE, "..", "scenes", "scan_table.pcd"))

# Boxes: (centre, full size, yaw about z). Cylinders: (centre, radius, length), axis along z.
BOXES = [
    ((0.6, 0.0, 0.18), (0.6, 1.0, 0.04), 0.0),  # table top, its surface at z = 0.2
    ((0.33, 0.47, 0.08), (0.04, 0.04, 0.16), 0.0),  # legs
    ((0.33, -0.47, 0.08), (0.04, 0.04, 0.16), 0.0),
    ((0.87, 0.47, 0.08), (0.04, 0.04, 0.16), 0.0),
    ((0.87, -0.47, 0.08), (0.04, 0.04, 0.16), 0.0),
    ((0.6, -0.16, 0.275), (0.1, 0.16, 0.15), 0.25),  # crate
    ((0.45, -0.3, 0.225), (0.18, 0.14, 0.05), -0.4),  # tray
]
CYLINDERS = [
    ((0.76, 0.2, 0.325), 0.04, 0.25),  # thermos
    ((0.40, 0.26, 0.25), 0.04, 0.10),  # cup
    ((0.62, 0.06, 0.3), 0.03, 0.2),  # bottle
]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalized(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def hit_box(o, d, centre, size, yaw):
    """Nearest positive ray parameter t of the ray o + t d on the box, or None (slab method in
    the box frame, which is the world frame turned by `yaw` about z)."""
    c, s = math.cos(yaw), math.sin(yaw)
    p = sub(o, centre)
    # World to box frame: rotate by -yaw about z.
    ol = (c * p[0] + s * p[1], -s * p[0] + c * p[1], p[2])
    dl = (c * d[0] + s * d[1], -s * d[0] + c * d[1], d[2])
    t0, t1 = -math.inf, math.inf
    for k in range(3):
        h = size[k] / 2
        if abs(dl[k]) < 1e-12:
            if abs(ol[k]) > h:
                return None
            continue
        a, b = (-h - ol[k]) / dl[k], (h - ol[k]) / dl[k]
        t0, t1 = max(t0, min(a, b)), min(t1, max(a, b))
    if t0 > t1 or t1 <= 0:
        return None
    return t0 if t0 > 0 else None  # a camera inside a box sees nothing of it


def hit_cylinder(o, d, centre, radius, length):
    """Nearest positive t on a closed vertical cylinder, or None."""
    p = sub(o, centre)
    h = length / 2
    best = None
    a = d[0] * d[0] + d[1] * d[1]
    if a > 1e-12:  # the side
        b = 2 * (p[0] * d[0] + p[1] * d[1])
        cc = p[0] * p[0] + p[1] * p[1] - radius * radius
        disc = b * b - 4 * a * cc
        if disc >= 0:
            for t in ((-b - math.sqrt(disc)) / (2 * a), (-b + math.sqrt(disc)) / (2 * a)):
                if t > 0 and abs(p[2] + t * d[2]) <= h:
                    best = t if best is None else min(best, t)
                    break
    if abs(d[2]) > 1e-12:  # the caps
        for zc in (-h, h):
            t = (zc - p[2]) / d[2]
            x, y = p[0] + t * d[0], p[1] + t * d[1]
            if t > 0 and x * x + y * y <= radius * radius:
                best = t if best is None else min(best, t)
    return best


def scan(eye, target, width, height, fov_deg, noise, seed):
    """One ray per pixel of a pinhole camera at `eye` looking at `target` (z up)."""
    rng = random.Random(seed)
    forward = normalized(sub(target, eye))
    right = normalized(cross(forward, (0.0, 0.0, 1.0)))
    up = cross(right, forward)
    f = (width / 2) / math.tan(math.radians(fov_deg) / 2)  # focal length in pixels
    points = []
    for v in range(height):
        for u in range(width):
            x, y = (u + 0.5 - width / 2) / f, (height / 2 - v - 0.5) / f
            d = normalized(tuple(forward[k] + x * right[k] + y * up[k] for k in range(3)))
            hits = [hit_box(eye, d, *b) for b in BOXES]
            hits += [hit_cylinder(eye, d, *c) for c in CYLINDERS]
            hits = [t for t in hits if t is not None]
            if not hits:
                continue
            t = min(hits) + (rng.gauss(0.0, noise) if noise > 0 else 0.0)
            points.append(tuple(eye[k] + t * d[k] for k in range(3)))
    return points


def write_pcd(path, points):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    header = (
        "# .PCD v0.7 - simulated depth-camera scan (robots/scripts/scan_table.py)\n"
        "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
        f"WIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(points)}\n"
        "DATA binary\n"
    )
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        for p in points:
            f.write(struct.pack("<3f", *p))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=DEFAULT_OUT, help="PCD file to write")
    parser.add_argument("--width", type=int, default=320, help="image width in pixels")
    parser.add_argument("--height", type=int, default=240, help="image height in pixels")
    parser.add_argument("--fov", type=float, default=70.0, help="horizontal field of view (deg)")
    parser.add_argument("--noise", type=float, default=0.002, help="depth noise sigma (m)")
    parser.add_argument("--seed", type=int, default=7, help="noise seed")
    args = parser.parse_args()
    # The camera looks down at the table from above and behind the robot's base, like a head
    # camera.
    points = scan(eye=(-0.3, -0.4, 1.4), target=(0.6, 0.0, 0.2), width=args.width,
                  height=args.height, fov_deg=args.fov, noise=args.noise, seed=args.seed)
    write_pcd(args.out, points)
    print(f"{args.out}: {len(points)} points")


if __name__ == "__main__":
    main()
