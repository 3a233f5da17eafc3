"""Binary PCD into a numpy structured array (the bench's own reader; numpy only)."""
import numpy as np

_TYPES = {('F', 4): '<f4', ('F', 8): '<f8', ('U', 1): 'u1', ('U', 2): '<u2', ('U', 4): '<u4',
          ('I', 1): 'i1', ('I', 2): '<i2', ('I', 4): '<i4', ('U', 8): '<u8', ('I', 8): '<i8'}


def read_pcd(path):
    with open(path, 'rb') as f:
        hdr = {}
        while True:
            line = f.readline().decode().strip()
            if not line or line.startswith('#'):
                continue
            key, *val = line.split()
            hdr[key] = val
            if key == 'DATA':
                break
        if hdr['DATA'][0] != 'binary':
            raise SystemExit(f'{path}: only binary PCD is read here')
        names, sizes, types = hdr['FIELDS'], list(map(int, hdr['SIZE'])), hdr['TYPE']
        counts = list(map(int, hdr.get('COUNT', ['1'] * len(names))))
        dt = np.dtype([(n if n != '_' else f'_{i}', _TYPES[(t, s)], (c,) if c > 1 else ())
                       for i, (n, t, s, c) in enumerate(zip(names, types, sizes, counts))])
        n = int(hdr['POINTS'][0])
        return np.frombuffer(f.read(n * dt.itemsize), dtype=dt, count=n)


def xyz(a):
    return np.stack([a['x'], a['y'], a['z']], axis=1).astype(np.float64)
