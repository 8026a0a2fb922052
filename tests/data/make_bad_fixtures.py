#!/usr/bin/python3
"""Makes the malformed database fixtures of tests/store/test_bad_files.cpp from reference-v2.h5
(version-2 files: their clips have float64 channels, which version 3 still reads).

Each file breaks one rule of schemas/format-v2.md the way a foreign writer (here h5py) might; the
library never writes them. Run from this folder with Debian's python3-h5py:
    /usr/bin/python3 make_bad_fixtures.py
"""
import shutil

import h5py
import numpy as np

REF = "reference-v2.h5"
CHANNELS = "/clips/tiny_walk/channels"
MODEL = "/sets/tiny_set/model"


def copy(name):
    shutil.copyfile(REF, name)
    return h5py.File(name, "r+")


def replace_dataset(f, path, data):
    attrs = dict(f[path].attrs)
    del f[path]
    d = f.create_dataset(path, data=data, chunks=True, shuffle=True, compression="gzip", fletcher32=True)
    for k, v in attrs.items():
        d.attrs[k] = v


# A newer format version.
with copy("bad-newer-version.h5") as f:
    f.attrs["format_version"] = np.int64(5)

# An HDF5 file that is not a mocapdb database at all.
with h5py.File("bad-foreign.h5", "w") as f:
    f.create_dataset("/data", data=np.arange(12.0).reshape(3, 4))
    f.attrs["title"] = "someone else's file"

# Clip channels stored as float32.
with copy("bad-dtype.h5") as f:
    replace_dataset(f, CHANNELS, f[CHANNELS][...].astype(np.float32))

# Clip channels with one column too few for the skeleton (9 channels).
with copy("bad-shape.h5") as f:
    replace_dataset(f, CHANNELS, f[CHANNELS][:, :8])

# Tensor whose `dims` attribute names the axes in Eigen's order, plus an unknown attribute.
with copy("bad-dims.h5") as f:
    t = f["/sets/tiny_set/aligned/tensor"]
    t.attrs["dims"] = np.array([b"dof", b"time", b"sample"], dtype=h5py.string_dtype())
    f["/clips/tiny_walk"].attrs["colour"] = "blue"
    f["/clips/tiny_walk"].attrs["x_note"] = "user attributes are allowed"

# Model whose dof basis has one row too few for the aligned tensor (D = 9).
with copy("bad-model-shape.h5") as f:
    replace_dataset(f, MODEL + "/dof_basis", f[MODEL + "/dof_basis"][:8, :])

# Model of sample rank R3 = 3 > N = 2 (core and sample basis padded with zeros: shapes agree).
with copy("bad-model-rank.h5") as f:
    core = f[MODEL + "/core"][...]
    replace_dataset(f, MODEL + "/core", np.concatenate([core, np.zeros((1,) + core.shape[1:])], axis=0))
    basis = f[MODEL + "/sample_basis"][...]
    replace_dataset(f, MODEL + "/sample_basis", np.concatenate([basis, np.zeros((basis.shape[0], 1))], axis=1))

# Model with a NaN in its time basis.
with copy("bad-model-nan.h5") as f:
    basis = f[MODEL + "/time_basis"][...]
    basis[1, 0] = np.nan
    replace_dataset(f, MODEL + "/time_basis", basis)

# Model without the aligned tensor it describes.
with copy("bad-model-orphan.h5") as f:
    del f["/sets/tiny_set/aligned"]
