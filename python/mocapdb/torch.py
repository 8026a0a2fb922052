"""PyTorch datasets of training windows (importable only when torch is installed).

WindowDataset is an IterableDataset whose epoch yields exactly `windows_per_epoch` distinct windows
(L, V), chosen without replacement by (seed, epoch) and split between the DataLoader's workers without
duplicates; WindowMapDataset is a map-style dataset over every (clip, first frame) window. Both hold a
picklable WindowSampler (the database reopens by path, read-only, in each worker, also when workers are
spawned) and decode each clip once into its cache.

Example:
    >>> from torch.utils.data import DataLoader
    >>> from mocapdb.torch import WindowDataset
    >>> data = WindowDataset("walks.h5", length=64, windows_per_epoch=10_000)
    >>> loader = DataLoader(data, batch_size=256, num_workers=2)
    >>> for epoch in range(10):
    ...     data.set_epoch(epoch)          # before iterating: another draw per epoch
    ...     for batch in loader:           # (256, 64, V) float32 tensors
    ...         ...
"""
import numpy as np
import torch
from torch.utils.data import Dataset, IterableDataset, get_worker_info

from . import Database, WindowSampler

__all__ = ["WindowDataset", "WindowMapDataset"]


def _sampler(path, length, clips, source, dtype, values, batch, pad):
    with Database(path) as db:
        return WindowSampler(db, length=length, batch=batch, seed=0, values=values, clips=clips, source=source,
                             dtype=dtype, pad=pad)


class _Windows:
    """Flat window numbers (0 .. window_count - 1, clip by clip in the sampler's order) to windows."""

    def __init__(self, sampler):
        self.sampler = sampler
        counts = np.asarray(sampler.window_counts, dtype=np.int64)
        self.ends = np.cumsum(counts)
        self.starts = self.ends - counts

    def __len__(self):
        return int(self.ends[-1])

    def refs(self, numbers):
        numbers = np.asarray(numbers, dtype=np.int64)
        clips = np.searchsorted(self.ends, numbers, side="right")
        return clips, numbers - self.starts[clips]

    def get(self, numbers):
        clips, begins = self.refs(numbers)
        return self.sampler.windows(clips, begins)


class WindowDataset(IterableDataset):
    """An epoch of exactly `windows_per_epoch` distinct random windows (L, V) as torch tensors.

    The epoch's windows are the first N of a permutation of all windows drawn from (seed, epoch); worker k
    of n takes every n-th of them, so the workers of a DataLoader together yield each exactly once. The
    same seed and epoch give the same windows (set_epoch before each iteration; not with persistent_workers,
    whose copies keep the epoch they started with). with_refs=True yields (window, clip name, first frame).
    source 'auto', 'packed' or 'lossless'; values 'pose_vectors' or 'joint_positions'; clips: names or
    fnmatch patterns (default every clip); dtype numpy.float32 (default) or numpy.float64; pad: clips
    shorter than L give one window, padded with their last frame (WindowSampler's pad).

    Example:
        >>> data = WindowDataset("walks.h5", length=64, seed=0, windows_per_epoch=4096)
        >>> loader = torch.utils.data.DataLoader(data, batch_size=128, num_workers=2)
        >>> next(iter(loader)).shape
        torch.Size([128, 64, 90])
    """

    def __init__(self, path, length=64, seed=0, windows_per_epoch=None, clips=None, source="auto",
                 dtype=np.float32, values="pose_vectors", with_refs=False, chunk=256, pad=False):
        super().__init__()
        self.sampler = _sampler(path, length, clips, source, dtype, values, chunk, pad)
        self._windows = _Windows(self.sampler)
        total = len(self._windows)
        n = total if windows_per_epoch is None else windows_per_epoch
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
            raise TypeError(f"WindowDataset: windows_per_epoch must be an integer, got {type(n).__name__}")
        if not 1 <= n <= total:
            raise ValueError(f"WindowDataset: windows_per_epoch must be between 1 and the {total} distinct windows "
                             f"of {length} frames, got {n}")
        self.windows_per_epoch = int(n)
        self.seed = seed
        self.epoch = 0
        self.with_refs = with_refs
        self.chunk = chunk

    def set_epoch(self, epoch):
        """Chooses the epoch's windows: the same (seed, epoch) gives the same windows.

        Example:
            >>> data.set_epoch(3)
        """
        self.epoch = int(epoch)

    def __len__(self):
        return self.windows_per_epoch

    def epoch_windows(self):
        """The epoch's window numbers, in order (all workers together).

        Example:
            >>> numbers = data.epoch_windows()   # (windows_per_epoch,) int64
        """
        rng = np.random.default_rng([self.seed, self.epoch])
        return rng.choice(len(self._windows), self.windows_per_epoch, replace=False)

    def __iter__(self):
        numbers = self.epoch_windows()
        info = get_worker_info()
        if info is not None:
            numbers = numbers[info.id::info.num_workers]
        names = self.sampler.clips
        for i in range(0, len(numbers), self.chunk):
            part = numbers[i:i + self.chunk]
            batch = torch.from_numpy(self._windows.get(part))
            if not self.with_refs:
                yield from batch
                continue
            clips, begins = self._windows.refs(part)
            for window, c, b in zip(batch, clips, begins):
                yield window, names[c], int(b)


class WindowMapDataset(Dataset):
    """Every window (L, V) of the selected clips, indexed 0 .. len - 1 clip by clip (clip order of
    .clips, first frames in order), or by (clip name, first frame); for samplers and shuffling of
    torch's own. Options as WindowDataset's.

    Example:
        >>> data = WindowMapDataset("walks.h5", length=64)
        >>> data[0].shape, data["16_11", 10].shape     # torch.Size([64, 90]) twice
    """

    def __init__(self, path, length=64, clips=None, source="auto", dtype=np.float32, values="pose_vectors", pad=False):
        super().__init__()
        self.sampler = _sampler(path, length, clips, source, dtype, values, 256, pad)
        self._windows = _Windows(self.sampler)
        self.clips = self.sampler.clips

    def __len__(self):
        return len(self._windows)

    def __getitem__(self, item):
        if isinstance(item, tuple):
            name, begin = item
            return torch.from_numpy(self.sampler.window(name, begin))
        index = int(item)
        if not -len(self) <= index < len(self):
            raise IndexError(f"WindowMapDataset: index {index} of {len(self)} windows")
        return torch.from_numpy(self._windows.get([index % len(self)])[0])
