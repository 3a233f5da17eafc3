#!/usr/bin/env python3
"""Benchmark cloud: solid balls of radius 0.03 (400 points each) on a 0.08 lattice, plus 10 % uniform
leaf/outlier points. Binary PCD x y z rgb. Usage: make_balls_cloud.py N out.pcd (prints N and the
number of balls). Deterministic (seed 1). Standard library only."""
import random, struct, sys, math
n_target = int(sys.argv[1]); out = sys.argv[2]
rng = random.Random(1)
pts = []
# fruit: balls of radius 0.03 with ~400 points each on a loose lattice, plus 10% leaves/outliers
per = 400
nballs = int(n_target * 0.9 / per)
side = math.ceil(nballs ** (1/3))
k = 0
buf = bytearray()
count = 0
for i in range(side):
    for j in range(side):
        for l in range(side):
            if k >= nballs: break
            k += 1
            cx, cy, cz = i * 0.08, j * 0.08, l * 0.08
            m = 0
            while m < per:
                x, y, z = rng.uniform(-.03,.03), rng.uniform(-.03,.03), rng.uniform(-.03,.03)
                if x*x+y*y+z*z <= 0.0009:
                    buf += struct.pack('<fffI', cx+x, cy+y, cz+z, 0xF0A060); m += 1; count += 1
ext = side * 0.08
while count < n_target:
    buf += struct.pack('<fffI', rng.uniform(0, ext), rng.uniform(0, ext), rng.uniform(0, ext), 0x40A030 if rng.random() < .8 else 0xFFFFFF); count += 1
hdr = f"VERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH {count}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {count}\nDATA binary\n"
open(out, 'wb').write(hdr.encode() + bytes(buf))
print(count, nballs)
