#!/usr/bin/env python3
"""Makes the shipped sample clouds. Deterministic (fixed seeds), standard library only.

fruit_small.ply: an Open3D-style binary PLY (double x y z, uchar red green blue) of a toy peach
tree in metres: 12 solid fruit of radius 3 cm (one pair 2 mm apart), green leaf points, dark
background points and sparse outliers. Ground truth: 12 fruit; centres in fruit_small.json.
"""
import json
import math
import random
import struct
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def ball(rng, centre, radius, n):
    pts = []
    while len(pts) < n:
        p = [rng.uniform(-radius, radius) for _ in range(3)]
        if sum(c * c for c in p) <= radius * radius:
            pts.append([centre[i] + p[i] for i in range(3)])
    return pts


def write_open3d_ply(path, points, colours):
    head = (
        "ply\nformat binary_little_endian 1.0\ncomment Created by Open3D\n"
        f"element vertex {len(points)}\n"
        "property double x\nproperty double y\nproperty double z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(head.encode())
        for p, c in zip(points, colours):
            f.write(struct.pack("<dddBBB", *p, *c))


def fruit_small():
    rng = random.Random(20261122)
    r = 0.03
    centres = []
    # ten well separated fruit on a ring, and one pair 2 mm apart near the middle
    for k in range(10):
        a = 2 * math.pi * k / 10
        centres.append([0.3 * math.cos(a), 0.3 * math.sin(a), rng.uniform(-0.1, 0.1)])
    centres.append([-0.031, 0.0, 0.0])
    centres.append([0.031, 0.0, 0.0])
    points, colours = [], []
    for c in centres:
        for p in ball(rng, c, r, 300):
            points.append(p)
            colours.append((rng.randint(220, 255), rng.randint(140, 200), rng.randint(60, 120)))
    for _ in range(1200):  # leaves: green, spread through the canopy
        points.append([rng.uniform(-0.45, 0.45), rng.uniform(-0.45, 0.45), rng.uniform(-0.2, 0.2)])
        colours.append((rng.randint(30, 70), rng.randint(90, 150), rng.randint(20, 60)))
    for _ in range(800):  # dark background
        points.append([rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6), rng.uniform(-0.4, -0.2)])
        v = rng.randint(5, 60)
        colours.append((v, v, v))
    for _ in range(40):  # bright sparse outliers (pass the colour filter, fail kNN)
        points.append([rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.2, 0.2)])
        colours.append((rng.randint(200, 255), rng.randint(150, 255), rng.randint(150, 255)))
    order = list(range(len(points)))
    rng.shuffle(order)
    write_open3d_ply(HERE / "fruit_small.ply", [points[i] for i in order],
                     [colours[i] for i in order])
    (HERE / "fruit_small.json").write_text(json.dumps(
        {"fruit_count": len(centres), "radius": r, "centres": centres}, indent=1) + "\n")


if __name__ == "__main__":
    fruit_small()
    sys.exit(0)
