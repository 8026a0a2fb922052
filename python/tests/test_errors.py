"""Pythonic errors: KeyError for names the database does not hold, TypeError / ValueError naming the bad
argument (never pybind11's list of signatures), and short clips counted in a warning."""
import warnings

import numpy as np
import pytest

import mocapdb


def test_missing_names_are_key_errors(test_db):
    with mocapdb.open(test_db) as db:
        for lookup in (lambda: db.clip("no_such_clip"), lambda: db.clip("no_such_clip", tier="packed"),
                       lambda: db.set("no_such_set"), lambda: db.skeleton("no_such_skeleton"),
                       lambda: db.synthesis_model("no_such_set")):
            with pytest.raises(KeyError) as caught:
                lookup()
            # Still the library's StoreError with the file and HDF5 path in its message.
            assert isinstance(caught.value, mocapdb.StoreError) and isinstance(caught.value, mocapdb.NotFoundError)
            assert str(test_db) in str(caught.value) and "no_such_" in str(caught.value)
        with pytest.raises(KeyError, match="no such clip"):
            db.sampler(clips=["16_11", "no_such_clip"])
        sampler = db.sampler(length=16, batch=2)
        with pytest.raises(KeyError, match="not among the sampler's clips"):
            sampler.window("no_such_clip", 0)


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(seed=-1), ValueError, "seed must be at least 0, got -1"),
    (dict(seed=2**64), ValueError, "seed must be less than 2**64"),
    (dict(length=0), ValueError, "length must be at least 1, got 0"),
    (dict(batch=-5), ValueError, "batch must be at least 1, got -5"),
    (dict(length="64"), TypeError, "length must be an integer, got str"),
    (dict(length=64.0), TypeError, "length must be an integer, got float"),
    (dict(seed=True), TypeError, "seed must be an integer, got bool"),
    (dict(values=3), TypeError, "values must be a str, got int"),
    (dict(values="angles"), ValueError, "values: expected 'pose_vectors' or 'joint_positions', got 'angles'"),
    (dict(source="gpu"), ValueError, "source: expected 'auto', 'packed' or 'lossless', got 'gpu'"),
    (dict(clips=5), TypeError, "clips must be None, a str or a list of str, got int"),
    (dict(clips=["16_11", 7]), TypeError, "clips[i] must be a str, got int"),
    (dict(cache_clips=0), ValueError, "cache_clips must be at least 1"),
])
def test_bad_sampler_arguments_say_what_is_wrong(test_db, kwargs, error, words):
    with mocapdb.open(test_db) as db:
        with pytest.raises(error) as caught:
            db.sampler(**kwargs)
    message = str(caught.value)
    assert words in message
    assert "incompatible" not in message and "argument types" not in message


def test_numpy_integers_are_integers(test_db):
    with mocapdb.open(test_db) as db:
        a = db.sampler(length=np.int64(16), batch=np.uint8(2), seed=np.int32(3))
        b = db.sampler(length=16, batch=2, seed=3)
        assert np.array_equal(a.next(), b.next())
        with pytest.raises(ValueError, match="begin must be at least 0"):
            a.window(a.clips[0], -1)


def test_short_clips_are_counted_in_a_warning(test_db):
    with mocapdb.open(test_db) as db:
        frames = {c.name: c.frames for c in db.clips()}
        length = sorted(frames.values())[len(frames) // 2]  # about half the clips are shorter
        short = sorted(name for name, f in frames.items() if f < length)
        assert 0 < len(short) < len(frames)
        with pytest.warns(mocapdb.ShortClipsWarning, match=f"{len(short)} of {len(frames)} selected clips are shorter "
                                                           f"than the window \\({length} frames\\)"):
            sampler = db.sampler(length=length, batch=4)
        assert sorted(sampler.short_clips) == short
        assert sorted(sampler.clips + sampler.short_clips) == sorted(frames)
        for name, begin in sampler.next_with_windows()[1]:
            assert name not in short and begin + length <= frames[name]
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # no warning when every clip is long enough
            assert db.sampler(length=min(frames.values()), batch=4).short_clips == []


def test_a_key_error_reads_as_the_library_message(test_db):
    with mocapdb.open(test_db) as db:
        with pytest.raises(KeyError) as caught:
            db.clip("no_such_clip")
    assert str(caught.value) == f"{test_db}: /clips/no_such_clip: no such clip"


def test_short_clips_padded_on_request(test_db):
    with mocapdb.open(test_db) as db:
        frames = {c.name: c.frames for c in db.clips()}
        length = sorted(frames.values())[len(frames) // 2]
        short = sorted(name for name, f in frames.items() if f < length)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # padded: nothing to warn about
            padded = db.sampler(length=length, batch=64, seed=2, pad=True, source="lossless", dtype=np.float64)
        assert sorted(padded.short_clips) == short and sorted(padded.clips) == sorted(frames)
        assert padded.window_count == sum(f - length + 1 for f in frames.values() if f >= length) + len(short)
        for name in short:
            f = frames[name]
            w = padded.window(name, 0)
            assert w.shape == (length, padded.values_per_frame)
            # The clip's own frames in its canonical frame, then its last frame repeated.
            assert np.allclose(w[:f], db.clip(name).pose_vectors(), rtol=0, atol=1e-9)
            assert np.array_equal(w[f:], np.repeat(w[f - 1:f], length - f, axis=0))
            with pytest.raises(ValueError, match="beyond clip"):
                padded.window(name, 1)
        drawn = set()
        for _ in range(20):
            drawn |= {n for n, _ in padded.next_with_windows()[1]}
        assert drawn & set(short)  # short clips are drawn too
        with pytest.raises(TypeError, match="pad must be True or False"):
            db.sampler(pad=1)
