#!/usr/bin/env python3
"""Independent scorer for pc_eval (numpy + scipy Hungarian matching on IoU, not the toolkit code).

Usage: /usr/bin/python3 bench/independent_eval.py labelled.pcd truth.json
Needs python3-numpy and python3-scipy (Debian). Binary PCD with label and gt_instance only."""
import json
import sys

import numpy as np
from scipy.optimize import linear_sum_assignment

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from pcdio import read_pcd  # noqa: E402

a = read_pcd(sys.argv[1]); truth = json.load(open(sys.argv[2]))
pred = a['label'].astype(np.int64); gt = a['gt_instance'].astype(np.int64)
P = sorted(set(pred[pred>0])); G = sorted(set(gt[gt>0]))
pi = {p:i for i,p in enumerate(P)}; gi = {g:i for i,g in enumerate(G)}
M = np.zeros((len(P), len(G)))
for p, g in zip(pred, gt):
    if p > 0 and g > 0: M[pi[p], gi[g]] += 1
ps = np.array([np.sum(pred==p) for p in P]); gs = np.array([np.sum(gt==g) for g in G])
iou = M / (ps[:,None] + gs[None,:] - M)
r, c = linear_sum_assignment(-iou)
tp = int(np.sum(iou[r,c] > 0.5))
n_gt = truth['fruit_count']
merged = int(np.sum((M > 0.5*gs[None,:]).sum(1) >= 2)); split = int(np.sum((M > 0.5*ps[:,None]).sum(0) >= 2))
print(f"count {len(P)} gt {n_gt} tp {tp} f1 {2*tp/(len(P)+n_gt):.6f} merged {merged} split {split}")
