#!/usr/bin/env python3
"""The Open3D and scikit-learn side of bench/run.sh, and the result checks. Run with Debian's
/usr/bin/python3 (python3-open3d, python3-sklearn, python3-scipy). Each operation prints
"seconds value" with the time of the algorithm alone (reading the file excluded).

  peers.py o3d_dbscan FILE EPS MIN_POINTS     Open3D cluster_dbscan -> clusters
  peers.py o3d_sor FILE K STD                 Open3D remove_statistical_outlier -> points kept
  peers.py o3d_hull FILE                      Open3D compute_convex_hull -> volume
  peers.py sk_dbscan FILE EPS MIN_POINTS      scikit-learn DBSCAN (kd_tree, n_jobs=-1) -> clusters
  peers.py check_dbscan FILE OURS EPS MIN     our labels (OURS: pc_dbscan output) vs scikit-learn
  peers.py check_knn FILE OURS K PCT          our outlier marks (pc_knn_outlier --mark outlier) vs
                                              numpy/scipy, and kNN distances vs brute force
  peers.py xyz_only FILE OUT                  the cloud with its x y z only (F 4, binary PCD)
"""
import sys
import time

import numpy as np

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from pcdio import read_pcd, xyz  # noqa: E402


def timed(f):
    t = time.perf_counter()
    v = f()
    return time.perf_counter() - t, v


def o3d_cloud(path):
    import open3d as o3d
    pc = o3d.geometry.PointCloud()
    pc.points = o3d.utility.Vector3dVector(xyz(read_pcd(path)))
    return pc


def main(argv):
    op, path = argv[1], argv[2]
    if op == 'xyz_only':
        p = xyz(read_pcd(path)).astype(np.float32)
        head = ('VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n'
                f'WIDTH {len(p)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(p)}\nDATA binary\n')
        with open(argv[3], 'wb') as f:
            f.write(head.encode() + np.ascontiguousarray(p).tobytes())
        print(f'0 {len(p)}')
    elif op == 'o3d_dbscan':
        pc = o3d_cloud(path)
        s, labels = timed(lambda: np.asarray(pc.cluster_dbscan(float(argv[3]), int(argv[4]), False)))
        print(f'{s:.6f} {labels.max() + 1}')
    elif op == 'o3d_sor':
        pc = o3d_cloud(path)
        s, (_, kept) = timed(lambda: pc.remove_statistical_outlier(int(argv[3]), float(argv[4])))
        print(f'{s:.6f} {len(kept)}')
    elif op == 'o3d_hull':
        pc = o3d_cloud(path)
        s, (mesh, _) = timed(lambda: pc.compute_convex_hull())
        print(f'{s:.6f} {mesh.get_volume():.9g}')
    elif op == 'sk_dbscan':
        from sklearn.cluster import DBSCAN
        p = xyz(read_pcd(path))
        s, m = timed(lambda: DBSCAN(eps=float(argv[3]), min_samples=int(argv[4]), algorithm='kd_tree', n_jobs=-1).fit(p))
        print(f'{s:.6f} {m.labels_.max() + 1}')
    elif op == 'check_dbscan':
        from sklearn.cluster import DBSCAN
        p = xyz(read_pcd(path))
        ours = read_pcd(argv[3])['label'].astype(np.int64)
        m = DBSCAN(eps=float(argv[4]), min_samples=int(argv[5]), algorithm='kd_tree', n_jobs=-1).fit(p)
        theirs = m.labels_
        core = np.zeros(len(p), bool)
        core[m.core_sample_indices_] = True
        noise_same = np.array_equal(theirs < 0, ours == 0)
        pairs = set(zip(theirs[core].tolist(), ours[core].tolist()))
        partition_same = len(pairs) == len(set(theirs[core])) == len(set(ours[core]))
        border = (~core) & (theirs >= 0)
        mapping = dict(pairs)
        border_diff = int(np.sum([mapping.get(t, -1) != o for t, o in zip(theirs[border], ours[border])]))
        print(f'dbscan vs scikit-learn: noise {"identical" if noise_same else "DIFFERENT"} ({int(np.sum(ours == 0))} points), '
              f'core partition {"identical" if partition_same else "DIFFERENT"} ({len(set(theirs[core]))} clusters), '
              f'{border_diff} of {int(border.sum())} border points in another cluster (nearest-core rule vs visiting order)')
        return 0 if noise_same and partition_same else 1
    elif op == 'check_knn':
        from scipy.spatial import cKDTree
        p = xyz(read_pcd(path))
        k, pct = int(argv[4]), float(argv[5])
        ours = read_pcd(argv[3])['outlier'].astype(bool)
        d, _ = cKDTree(p).query(p, k + 1)
        mean = d[:, 1:].mean(axis=1)
        theirs = mean >= np.percentile(mean, 100 - pct)
        rng = np.random.default_rng(1)
        sample = rng.choice(len(p), size=min(2000, len(p)), replace=False)
        worst = 0.0
        for i in sample:
            brute = np.sort(np.sqrt(((p - p[i]) ** 2).sum(axis=1)))[1:k + 1]
            worst = max(worst, float(np.abs(brute - d[i, 1:]).max()))
        same = np.array_equal(ours, theirs)
        print(f'knn outliers vs numpy/scipy: {"identical" if same else "DIFFERENT"} ({int(ours.sum())} outliers); '
              f'kd-tree distances vs brute force on {len(sample)} points: max difference {worst:.3g}')
        return 0 if same and worst < 1e-9 else 1
    else:
        print(__doc__, file=sys.stderr)
        return 2
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
