"""Whether two run.h5 files hold bitwise the same run: under /fields, /cells,
/diagnostics and /profiles the same objects, attributes, shapes, types and bytes (checkpoint_test.sh).
h5diff is not enough: it reports datasets of different lengths as "not comparable" and
still exits 0. Prints each difference; exits 1 if there is any."""
import sys

import h5py
import numpy as np


def contents(path):
    """{object path: (kind, value or bytes)} for every group, dataset and attribute."""
    out = {}
    with h5py.File(path, "r") as f:
        def add(name, obj):
            for key, value in obj.attrs.items():
                out[f"{name}@{key}"] = ("attr", np.asarray(value).tobytes() if not isinstance(value, str) else value)
            if isinstance(obj, h5py.Dataset):
                data = obj[()]
                out[name] = ("dataset", data.dtype.str, data.shape, data.tobytes())
            else:
                out[name] = ("group",)
        for group in ("fields", "cells", "diagnostics", "profiles"):
            if group in f:
                add(group, f[group])
                f[group].visititems(lambda name, obj, g=group: add(f"{g}/{name}", obj))
    return out


a, b = contents(sys.argv[1]), contents(sys.argv[2])
differences = [name for name in sorted(set(a) | set(b)) if a.get(name) != b.get(name)]
for name in differences[:20]:
    print(f"  {name}: " + ("only in one file" if name not in a or name not in b else "differs"))
print(f"  {len(a)} objects and attributes compared, {len(differences)} differ")
sys.exit(1 if differences else 0)
