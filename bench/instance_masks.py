#!/usr/bin/env python3
"""Cameras and imperfect instance masks for bench/instances.sh.

  instance_masks.py rig OUT.json VIEWS DISTANCE   VIEWS cameras on three rings around the origin
                                                  (640 x 480, f 600), a nerfstudio transforms.json
  instance_masks.py degrade DIR MODE SEED         rewrites DIR's 16-bit id PNGs in place:
      none    as drawn
      dilate  every instance grown by 2 pixels into the background (masks that overhang)
      merge   in 3 of 10 views, instances that touch in the image share one id (under-segmented)
      drop    each instance of each view missing with chance 0.2 (a detector's misses)
      shuffle ids renumbered at random in each view (nothing may rely on one id across views)
      all     dilate, merge, drop and shuffle together
"""
import json
import math
import random
import sys
from pathlib import Path

import numpy as np
from PIL import Image


def rig(out, n, dist):
    frames = []
    for k in range(n):
        a, elev = 2 * math.pi * k / n, [-0.15, 0.25, 0.7][k % 3]
        eye = np.array([dist * math.cos(a) * math.cos(elev), dist * math.sin(a) * math.cos(elev),
                        dist * math.sin(elev)])
        fwd = -eye / np.linalg.norm(eye)
        right = np.cross(fwd, [0, 0, 1])
        right /= np.linalg.norm(right)
        up = np.cross(right, fwd)
        c2w = np.eye(4)
        c2w[:3, 0], c2w[:3, 1], c2w[:3, 2], c2w[:3, 3] = right, up, -fwd, eye
        frames.append({"file_path": f"images/v{k:03d}.png", "transform_matrix": c2w.tolist()})
    Path(out).write_text(json.dumps({"camera_model": "PINHOLE", "w": 640, "h": 480, "fl_x": 600.0,
                                     "fl_y": 600.0, "cx": 320.0, "cy": 240.0, "frames": frames}))


def grow(m, r):
    """Each background pixel within r pixels (a square) of an instance takes its largest id."""
    out = m.copy()
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            shifted = np.zeros_like(m)
            ys, yd = (slice(dy, None), slice(0, -dy or None)) if dy >= 0 else (slice(0, dy), slice(-dy, None))
            xs, xd = (slice(dx, None), slice(0, -dx or None)) if dx >= 0 else (slice(0, dx), slice(-dx, None))
            shifted[ys, xs] = m[yd, xd]
            out = np.where(m == 0, np.maximum(out, shifted), out)
    return out


def merge_touching(m):
    pairs = set()
    for a, b in ((m[:, :-1], m[:, 1:]), (m[:-1], m[1:])):
        touch = (a != b) & (a > 0) & (b > 0)
        pairs |= set(zip(a[touch].tolist(), b[touch].tolist()))
    parent = {}

    def root(x):
        while parent.get(x, x) != x:
            x = parent[x]
        return x
    for a, b in sorted(pairs):
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    return relabel(m, {v: root(v) for v in np.unique(m).tolist()})


def relabel(m, table):
    ids = np.array(sorted(table), dtype=np.int64)
    new = np.array([table[v] for v in ids], dtype=np.int64)
    return new[np.searchsorted(ids, m)]


def degrade(folder, mode, seed):
    rng = random.Random(seed)
    for p in sorted(Path(folder).glob("*.png")):
        m = np.array(Image.open(p)).astype(np.int64)
        if mode in ("dilate", "all"):
            m = grow(m, 2)
        if mode in ("merge", "all") and rng.random() < 0.3:
            m = merge_touching(m)
        ids = [v for v in np.unique(m).tolist() if v != 0]
        if mode in ("drop", "shuffle", "all") and ids:
            perm = list(range(1, len(ids) + 1))
            if mode != "drop":
                rng.shuffle(perm)
            table = {0: 0}
            for v, q in zip(ids, perm):
                table[v] = 0 if mode != "shuffle" and rng.random() < 0.2 else q
            m = relabel(m, table)
        Image.fromarray(m.astype(np.uint16)).save(p)


if __name__ == "__main__":
    if sys.argv[1] == "rig":
        rig(sys.argv[2], int(sys.argv[3]), float(sys.argv[4]))
    else:
        degrade(sys.argv[2], sys.argv[3], int(sys.argv[4]))
