"""mocapdb from Python: motion capture databases, clips as numpy arrays, synthesis and training windows.

    import mocapdb
    db = mocapdb.open("walks.h5")
    clip = db.clip("16_11")                 # channels (F, C), cm and radians
    xyz = clip.joint_positions()            # (F, J, 3) cm, every joint and end site
    model = db.synthesis_model("walks")     # kriging of the set's Tucker model
    poses = model.poses(C, t=20.0)          # (Q, D) for Q characters at once
    for batch in db.sampler(length=64, batch=32, seed=1):   # (32, 64, D), endless
        ...

Arrays are float64 (training windows float32 by default) and frames come first. Errors are mocapdb.Error subclasses carrying the library's
one-line messages (InvalidArgument and ParseError are ValueErrors, IoError is an OSError, NotFoundError
- a clip, set or skeleton name the database does not hold - is a KeyError).
"""

import numpy as _np

from ._core import (  # noqa: F401  (the public names)
    ChecksumError,
    Clip,
    ClipInfo,
    Database,
    Error,
    InvalidArgument,
    IoError,
    MotionSet,
    NotFoundError,
    PackedClip,
    PackedGroup,
    PackedTier,
    ParseError,
    Sample,
    ShortClipsWarning,
    SetInfo,
    Skeleton,
    StoreError,
    SynthesisModel,
    WindowSampler,
    __version__,
    align,
    collection_report,
    compress,
    copy_database,
    create_set,
    import_files,
    pack,
    read_clip,
    write_bvh,
)


def open(path):  # noqa: A001  (mocapdb.open mirrors the built-in on purpose)
    """Opens a database file read-only: a Database (also a context manager that closes it).

    Example:
        >>> with mocapdb.open("walks.h5") as db:
        ...     print(len(db.clips()))
    """
    return Database(path)


def _sampler(self, length=64, batch=32, seed=0, values="pose_vectors", clips=None, source="auto", cache_clips=256,
             dtype=_np.float32, pad=False):
    """A WindowSampler of this database: random windows of `length` frames, `batch` per batch.

    values: 'pose_vectors' (D per frame) or 'joint_positions' (3 J per frame); clips: ids or fnmatch
    patterns (default: every clip; one rig and frame rate); source: 'auto', 'packed' or 'lossless';
    dtype: numpy.float32 (default) or numpy.float64, end to end (each drawn clip is decoded once, whole,
    into a cache of that type: sampler.cache_bytes; at most max(cache_clips, batch) clips).
    The same seed gives the same batches. Bad arguments raise TypeError or ValueError naming them; selected
    clips shorter than `length` give no windows and are counted in a ShortClipsWarning, or with pad=True
    one window each, from frame 0, whose missing rows repeat the clip's last frame.

    Example:
        >>> sampler = db.sampler(length=64, batch=256, seed=1)
        >>> batch = next(sampler)              # (256, 64, D)
    """
    return WindowSampler(self, length=length, batch=batch, seed=seed, values=values, clips=clips, source=source,
                         cache_clips=cache_clips, dtype=dtype, pad=pad)


Database.sampler = _sampler
