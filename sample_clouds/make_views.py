#!/usr/bin/env python3
"""Makes sample_clouds/views/: a small calibrated scene for pc_lift, written by this project.
Deterministic, standard library only.

Three fruit (spheres of radius 0.1 m, floating 0.05-0.25 m above the ground) over a ground plane,
seen by eight cameras (320 x 240 pixels, pinhole, f = 300) on a ring at 2 m, 1.2 m high, looking at
the origin. Written:
  cloud.pcd          x y z gt: sphere surface points (gt = fruit 1..3) and ground points (gt = 0)
  transforms.json    nerfstudio: camera-to-world in OpenGL axes, mask_path per frame
  masks/frame_K.png  8-bit masks, 255 where the pixel centre's ray meets a fruit before the ground
  colmap/            the same cameras as a COLMAP text model (world-to-camera, OpenCV axes)
"""
import json
import math
import random
import struct
import zlib
from pathlib import Path

OUT = Path(__file__).resolve().parent / "views"
CENTRES = [(0.0, 0.0, 0.15), (0.3, -0.2, 0.15), (-0.35, 0.3, 0.2)]
RADIUS = 0.1
W, H, F = 320, 240, 300.0


def sub(a, b): return [a[i] - b[i] for i in range(3)]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def norm(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


def look_at(eye):
    """World-to-camera rows (OpenCV axes: x right, y down, z forward) of a camera at eye."""
    forward = norm([-x for x in eye])
    right = norm(cross(forward, [0, 0, 1]))
    down = cross(forward, right)
    return [right, down, forward]


def mask(eye, rows):
    pixels = bytearray()
    for y in range(H):
        pixels.append(0)  # PNG filter: none
        for x in range(W):
            c = [(x + 0.5 - W / 2) / F, (y + 0.5 - H / 2) / F, 1.0]
            d = norm([sum(rows[k][i] * c[k] for k in range(3)) for i in range(3)])
            ground = -eye[2] / d[2] if d[2] < 0 else float("inf")
            fruit = False
            for centre in CENTRES:
                oc = sub(eye, centre)
                b = dot(d, oc)
                disc = b * b - (dot(oc, oc) - RADIUS * RADIUS)
                if disc >= 0 and 0 < -b - math.sqrt(disc) < ground:
                    fruit = True
            pixels.append(255 if fruit else 0)
    return bytes(pixels)


def write_png(path, raw):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    head = struct.pack(">IIBBBBB", W, H, 8, 0, 0, 0, 0)  # 8-bit greyscale
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", head) + chunk(b"IDAT", zlib.compress(raw, 9))
                     + chunk(b"IEND", b""))


def quaternion(r):
    """(w, x, y, z) of a rotation matrix given as rows."""
    t = r[0][0] + r[1][1] + r[2][2]
    if t > 0:
        s = 0.5 / math.sqrt(t + 1)
        return (0.25 / s, (r[2][1] - r[1][2]) * s, (r[0][2] - r[2][0]) * s, (r[1][0] - r[0][1]) * s)
    i = max(range(3), key=lambda k: r[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + r[i][i] - r[j][j] - r[k][k])
    q = [0.0] * 4
    q[0] = (r[k][j] - r[j][k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (r[j][i] + r[i][j]) / s
    q[1 + k] = (r[k][i] + r[i][k]) / s
    return tuple(q)


def main():
    (OUT / "masks").mkdir(parents=True, exist_ok=True)
    (OUT / "colmap").mkdir(exist_ok=True)
    frames, images = [], []
    for k in range(8):
        a = 2 * math.pi * k / 8
        eye = [2 * math.cos(a), 2 * math.sin(a), 1.2]
        rows = look_at(eye)
        name = f"frame_{k:02d}"
        write_png(OUT / "masks" / f"{name}.png", mask(eye, rows))
        # camera-to-world in OpenGL axes: columns right, up (= -down), back (= -forward)
        c2w = [[rows[0][i], -rows[1][i], -rows[2][i], eye[i]] for i in range(3)] + [[0, 0, 0, 1]]
        frames.append({"file_path": f"images/{name}.png", "mask_path": f"masks/{name}.png",
                       "transform_matrix": [[round(v, 12) for v in row] for row in c2w]})
        t = [-dot(rows[i], eye) for i in range(3)]
        q = quaternion(rows)
        images.append(f"{k + 1} " + " ".join(f"{v:.12f}" for v in q + tuple(t)) + f" 1 {name}.png\n\n")
    transforms = {"camera_model": "PINHOLE", "w": W, "h": H, "fl_x": F, "fl_y": F,
                  "cx": W / 2, "cy": H / 2, "frames": frames}
    (OUT / "transforms.json").write_text(json.dumps(transforms, indent=1) + "\n")
    (OUT / "colmap" / "cameras.txt").write_text(
        "# CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n" + f"1 PINHOLE {W} {H} {F} {F} {W / 2} {H / 2}\n")
    (OUT / "colmap" / "images.txt").write_text(
        "# IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n# POINTS2D[]\n" + "".join(images))
    points = []
    s = 0.02
    rng = random.Random(5)  # jittered: on an exact grid, pairs of points tie at the depth tolerance
    for i in range(-30, 31):
        for j in range(-30, 31):
            points.append((i * s + rng.uniform(-0.005, 0.005), j * s + rng.uniform(-0.005, 0.005), 0.0, 0))
    n = int(4 * math.pi * RADIUS * RADIUS / (0.01 * 0.01))
    for f, c in enumerate(CENTRES, start=1):
        for i in range(n):
            z = 1 - 2 * (i + 0.5) / n
            rho, phi = math.sqrt(1 - z * z), 2.399963 * i
            points.append((c[0] + RADIUS * rho * math.cos(phi), c[1] + RADIUS * rho * math.sin(phi),
                           c[2] + RADIUS * z, f))
    head = ("# .PCD v0.7 - made by sample_clouds/make_views.py\nVERSION 0.7\nFIELDS x y z gt\n"
            "SIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
            f"WIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(points)}\nDATA binary\n")
    body = b"".join(struct.pack("<fffI", *p) for p in points)
    (OUT / "cloud.pcd").write_bytes(head.encode() + body)
    print(f"{OUT}: {len(points)} points, {len(frames)} views")


if __name__ == "__main__":
    main()
