#!/usr/bin/env python3
"""Makes the lift bench's cameras and masks, and lifts with a numpy reference (projection + z-buffer
+ votes, pinhole cameras) to time beside pc_lift and to check that both agree.

  lift_reference.py make DIR VIEWS SIZE       transforms.json + masks/*.png (checkerboards)
  lift_reference.py lift DIR CLOUD SPACING OUT.npz
  lift_reference.py compare OURS.pcd OUT.npz  share of points whose views and votes agree
"""
import json
import math
import struct
import sys
import time
import zlib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from pcdio import read_pcd, xyz  # noqa: E402

CELL = 64  # checkerboard squares of the masks, pixels


def cameras(n, size):
    """n cameras on a spiral around the origin at 3 m, looking at it; c2w in OpenGL axes."""
    out = []
    for k in range(n):
        a = 2 * math.pi * k / n * 7.3
        el = 0.3 + 0.5 * (k % 10) / 10
        eye = np.array([3 * math.cos(a) * math.cos(el), 3 * math.sin(a) * math.cos(el), 3 * math.sin(el)])
        f = -eye / np.linalg.norm(eye)
        r = np.cross(f, [0, 0, 1])
        r /= np.linalg.norm(r)
        d = np.cross(f, r)
        c2w = np.eye(4)
        c2w[:3, 0], c2w[:3, 1], c2w[:3, 2], c2w[:3, 3] = r, -d, -f, eye
        out.append(c2w)
    return out


def mask(size):
    y, x = np.mgrid[0:size, 0:size]
    return (((x // CELL) + (y // CELL)) % 2).astype(np.uint8) * 255


def write_png(path, m):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    h, w = m.shape
    raw = b"".join(b"\x00" + m[r].tobytes() for r in range(h))
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def make(out, n, size):
    out = Path(out)
    (out / "masks").mkdir(parents=True, exist_ok=True)
    write_png(out / "masks" / "checker.png", mask(size))
    frames = [{"file_path": f"images/f{k:03d}.png", "mask_path": "masks/checker.png",
               "transform_matrix": c.tolist()} for k, c in enumerate(cameras(n, size))]
    f = 0.9 * size
    (out / "transforms.json").write_text(json.dumps(
        {"w": size, "h": size, "fl_x": f, "fl_y": f, "cx": size / 2, "cy": size / 2, "frames": frames}))


def lift(out, cloud, spacing, result):
    t = json.loads((Path(out) / "transforms.json").read_text())
    size, f = t["w"], t["fl_x"]
    m = mask(size).ravel() > 0
    pts = xyz(read_pcd(cloud))
    start = time.perf_counter()
    views = np.zeros(len(pts), np.uint32)
    votes = np.zeros(len(pts), np.uint32)
    gl_to_cv = np.diag([1.0, -1.0, -1.0, 1.0])
    for fr in t["frames"]:
        w2c = np.linalg.inv(np.array(fr["transform_matrix"]) @ gl_to_cv)
        q = pts @ w2c[:3, :3].T + w2c[:3, 3]
        z = q[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            u = f * q[:, 0] / z + size / 2
            v = f * q[:, 1] / z + size / 2
        ok = (z > 0) & (u >= 0) & (u < size) & (v >= 0) & (v < size)
        idx = np.nonzero(ok)[0]
        ui, vi, zi = u[idx].astype(np.int64), v[idx].astype(np.int64), z[idx].astype(np.float32)
        r = np.minimum(16, f * spacing / z[idx]).astype(np.int64)
        depth = np.full(size * size, np.inf, np.float32)
        for dy in range(-r.max(), r.max() + 1):
            for dx in range(-r.max(), r.max() + 1):
                s = (r >= max(abs(dx), abs(dy))) & (ui + dx >= 0) & (ui + dx < size) & (vi + dy >= 0) & (vi + dy < size)
                np.minimum.at(depth, (vi[s] + dy) * size + ui[s] + dx, zi[s])
        pix = vi * size + ui
        seen = zi <= depth[pix] + np.float32(2 * spacing)
        views[idx[seen]] += 1
        votes[idx[seen]] += m[pix[seen]]
    seconds = time.perf_counter() - start
    np.savez(result, views=views, votes=votes, seconds=seconds)
    print(f"{seconds:.2f}")


def compare(ours, result):
    a = read_pcd(ours)
    r = np.load(result)
    same = (a["views"] == r["views"]) & (a["votes"] == r["votes"])
    print(f"{same.mean():.6f}")


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "make":
        make(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))
    elif cmd == "lift":
        lift(sys.argv[2], sys.argv[3], float(sys.argv[4]), sys.argv[5])
    else:
        compare(sys.argv[2], sys.argv[3])
