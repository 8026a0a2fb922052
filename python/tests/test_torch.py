"""mocapdb.torch with Debian's python3-torch: an epoch yields exactly N distinct windows split between a
DataLoader's workers (0 and 2, forked and spawned), the same windows again for the same seed and epoch,
and equal to the sampler's windows."""
import inspect

import numpy as np
import pytest

torch = pytest.importorskip("torch")
from torch.utils.data import DataLoader  # noqa: E402

import mocapdb  # noqa: E402
from mocapdb.torch import WindowDataset, WindowMapDataset  # noqa: E402


def epoch_windows(data, workers, context=None):
    loader = DataLoader(data, batch_size=50, num_workers=workers, multiprocessing_context=context)
    windows, refs = [], []
    for batch, names, begins in loader:
        windows.append(batch)
        refs += list(zip(names, begins.tolist()))
    return torch.cat(windows), refs


@pytest.mark.parametrize("workers, context", [(0, None), (2, "fork"), (2, "spawn")])
def test_an_epoch_is_n_distinct_windows_and_repeats(test_db, workers, context):
    data = WindowDataset(test_db, length=32, seed=4, windows_per_epoch=600, with_refs=True)
    data.set_epoch(1)
    x, refs = epoch_windows(data, workers, context)
    assert x.shape == (600, 32, data.sampler.values_per_frame) and x.dtype == torch.float32
    assert len(set(refs)) == 600  # no window twice, across the workers
    again_x, again = epoch_windows(data, workers, context)
    assert again == refs and torch.equal(again_x, x)  # the same epoch again: the same windows
    data.set_epoch(2)
    other = epoch_windows(data, workers, context)[1]
    assert len(set(other)) == 600 and set(other) != set(refs)
    # The windows themselves are the sampler's.
    with mocapdb.open(test_db) as db:
        sampler = db.sampler(length=32, batch=4)
        for k in (0, 299, 599):
            assert np.array_equal(x[k].numpy(), sampler.window(*refs[k]))


def test_workers_split_the_single_process_epoch(test_db):
    data = WindowDataset(test_db, length=32, seed=9, windows_per_epoch=400, with_refs=True)
    assert sorted(epoch_windows(data, 0)[1]) == sorted(epoch_windows(data, 2)[1])


def test_options_and_errors(test_db):
    data = WindowDataset(test_db, length=16, windows_per_epoch=10, dtype=np.float64, values="joint_positions",
                         clips=["16_1*"], source="lossless")
    window = next(iter(data))
    assert window.dtype == torch.float64 and window.shape == (16, data.sampler.values_per_frame)
    assert len(data) == 10
    with pytest.raises(ValueError, match="windows_per_epoch must be between 1 and the"):
        WindowDataset(test_db, length=16, windows_per_epoch=10**9)
    with pytest.raises(TypeError, match="windows_per_epoch must be an integer"):
        WindowDataset(test_db, windows_per_epoch=1.5)


def test_map_style_dataset_covers_every_window(test_db):
    data = WindowMapDataset(test_db, length=32)
    with mocapdb.open(test_db) as db:
        frames = {c.name: c.frames for c in db.clips()}
        sampler = db.sampler(length=32, batch=4)
    assert len(data) == sum(f - 31 for f in frames.values())
    first = data.clips[0]
    assert torch.equal(data[0], data[first, 0])
    assert torch.equal(data[len(data) - 1], data[data.clips[-1], frames[data.clips[-1]] - 32])
    assert np.array_equal(data[5].numpy(), sampler.window(first, 5))
    with pytest.raises(IndexError):
        data[len(data)]
    batch = next(iter(DataLoader(data, batch_size=8, shuffle=True, num_workers=2)))
    assert batch.shape == (8, 32, sampler.values_per_frame)


def test_public_names_have_examples():
    import mocapdb.torch as module
    assert ">>> " in module.__doc__
    for name in module.__all__:
        cls = getattr(module, name)
        assert ">>> " in cls.__doc__, name
        for member, value in vars(cls).items():
            if not member.startswith("_") and inspect.isfunction(value):
                assert ">>> " in (value.__doc__ or ""), f"{name}.{member}"
