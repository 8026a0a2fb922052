# Damages one object of a mocapdb file in place, for the tests of refused writes
# (tests/store/test_damaged_writes.cpp). Needs h5py.
#   damage_dataset.py FILE nan PATH     sets the first value of float64 dataset PATH to NaN
#                                       (rewritten through HDF5: its checksum stays valid)
#   damage_dataset.py FILE nanclip CLIP replaces /clips/CLIP/channels_packed by float64 channels
#                                       (format-v3 'channels') holding a NaN
#   damage_dataset.py FILE attrs PATH NAME:T=VALUE ...
#                                       sets attributes of object PATH: T is s (string), f (float64)
#                                       or i (int64)
#   damage_dataset.py FILE deflate PATH rewrites dataset PATH (values and attributes kept) with shuffle +
#                                       deflate + fletcher32, as files written before 2026-12-06 hold
#                                       the synthesis kernel's covariance_inverse
#   damage_dataset.py FILE filters PATH prints the filters of dataset PATH, comma-separated
import sys

import h5py
import numpy as np

file, mode, path = sys.argv[1:4]
assignments = sys.argv[4:]
with h5py.File(file, "r+") as f:
    if mode == "nan":
        d = f[path]
        a = d[...]
        a.flat[0] = np.nan
        d[...] = a
    elif mode == "nanclip":
        g = f["/clips/" + path]
        packed = g["channels_packed"]
        frames = int(packed.attrs["frames"])
        channels = len(packed.attrs["channel_scale"])
        del g["channels_packed"]
        a = np.zeros((frames, channels))
        a[frames // 2, channels - 1] = np.nan
        d = g.create_dataset("channels", data=a, chunks=True, fletcher32=True, compression="gzip", shuffle=True)
        d.attrs["dims"] = np.array(["frame", "channel"], dtype=h5py.string_dtype())
        d.attrs["units"] = "cm|rad"
    elif mode == "attrs":
        for a in assignments:
            name, value = a.split("=", 1)
            name, kind = name.split(":")
            if kind == "i":
                f[path].attrs[name] = np.int64(value)
            else:
                f[path].attrs[name] = float(value) if kind == "f" else value
    elif mode == "deflate":
        d = f[path]
        values, attrs = d[...], dict(d.attrs)
        parent, name = d.parent, path.rsplit("/", 1)[1]
        del parent[name]
        d = parent.create_dataset(name, data=values, chunks=True, shuffle=True, compression="gzip",
                                  fletcher32=True)
        for key, value in attrs.items():
            d.attrs[key] = value
    elif mode == "filters":
        d = f[path]
        names = (["shuffle"] if d.shuffle else []) + (["deflate"] if d.compression == "gzip" else [])
        print(",".join(names + (["fletcher32"] if d.fletcher32 else [])))
    else:
        sys.exit("unknown mode " + mode)
