#!/usr/bin/env python3
"""Whether two HDF5 files hold the same objects, values and attributes, as
`h5diff A B` answers it (object times and the file's layout aside): exit 0
when they do, else 1, naming the first difference. For machines without
HDF5's tools (tests/cli/measurements.sh uses it where h5diff is absent).
usage: h5_same.py A B"""
import sys

import h5py
import numpy as np


def same_values(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind in "fc":
        return bool(np.array_equal(a, b, equal_nan=True))
    return bool(np.array_equal(a, b))


def objects(f):
    found = {"/": f}
    f.visititems(lambda name, o: found.__setitem__(name, o))
    return found


def difference(path_a, path_b):
    with h5py.File(path_a, "r") as fa, h5py.File(path_b, "r") as fb:
        a, b = objects(fa), objects(fb)
        if sorted(a) != sorted(b):
            return "objects " + ", ".join(sorted(set(a) ^ set(b)))
        for name in sorted(a):
            oa, ob = a[name], b[name]
            if isinstance(oa, h5py.Dataset) != isinstance(ob, h5py.Dataset):
                return name + ": a dataset in one file only"
            if isinstance(oa, h5py.Dataset) and not same_values(oa[()], ob[()]):
                return name + ": values"
            if sorted(oa.attrs) != sorted(ob.attrs):
                return name + ": attribute names"
            for key in oa.attrs:
                if not same_values(oa.attrs[key], ob.attrs[key]):
                    return name + ": attribute " + key
    return None


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    d = difference(sys.argv[1], sys.argv[2])
    if d:
        print(f"{sys.argv[1]} and {sys.argv[2]} differ: {d}")
        sys.exit(1)
