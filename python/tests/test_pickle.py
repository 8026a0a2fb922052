"""Every handle pickles (a database reopens by path, read-only), so that spawn-started workers get them;
samplers continue their stream exactly and draw per-(seed, epoch, worker) streams."""
import multiprocessing
import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import mocapdb


def round_trip(obj):
    return pickle.loads(pickle.dumps(obj))


def test_database_reopens_by_path(test_db):
    with mocapdb.open(test_db) as db:
        copy = round_trip(db)
        assert copy.path == db.path and [c.name for c in copy.clips()] == [c.name for c in db.clips()]
        assert np.array_equal(copy.clip("16_11").channels, db.clip("16_11").channels)
    copy.close()


def test_clips_and_skeletons_keep_every_joint(test_db, shared):
    bvh = sorted((shared / "datasets" / "cmu-walkrun-pfnn").glob("*.bvh"))[0]
    with mocapdb.open(test_db) as db:
        clips = [db.clip("16_11"), db.clip("16_12", tier="packed"), mocapdb.read_clip(bvh)]
    for clip in clips:  # ASF axes, packed skeleton, BVH channels and end sites
        copy = round_trip(clip)
        assert copy.name == clip.name and copy.frame_rate == clip.frame_rate
        assert np.array_equal(copy.channels, clip.channels)
        s, t = clip.skeleton, round_trip(clip.skeleton)
        assert t.joint_names == s.joint_names and np.array_equal(t.offsets, s.offsets)
        assert np.array_equal(copy.joint_positions(), clip.joint_positions())
        assert np.array_equal(copy.pose_vectors(), clip.pose_vectors())


@pytest.mark.parametrize("naive", [False, True])
def test_synthesis_models_load_again(test_db, naive):
    with mocapdb.open(test_db) as db:
        model = db.synthesis_model("walks", naive=naive)
    copy = round_trip(model)
    c = model.sample_parameters[:3]
    assert copy.kind == model.kind
    assert np.array_equal(copy.poses(c, 12.0), model.poses(c, 12.0))


def test_a_pickled_sampler_continues_its_stream(test_db):
    with mocapdb.open(test_db) as db:
        for dtype in (np.float32, np.float64):
            sampler = db.sampler(length=32, batch=8, seed=5, clips=["16_1*"], dtype=dtype, values="joint_positions")
            sampler.next()
            copy = round_trip(sampler)
            assert copy.dtype == dtype and copy.clips == sampler.clips and copy.values_per_frame == sampler.values_per_frame
            for _ in range(3):
                assert np.array_equal(copy.next(), sampler.next())


def test_epochs_and_workers_draw_their_own_reproducible_streams(test_db):
    with mocapdb.open(test_db) as db:
        a, b = db.sampler(length=32, batch=16, seed=7), db.sampler(length=32, batch=16, seed=7)
        fresh = a.next_with_windows()[1]
        streams = {}
        for epoch in range(3):
            for worker in range(3):
                a.set_epoch(epoch, worker=worker)
                streams[epoch, worker] = a.next_with_windows()[1]
        assert streams[0, 0] == fresh  # a new sampler draws stream (seed, 0, 0)
        assert len({tuple(w) for w in streams.values()}) == len(streams)  # every stream its own
        b.set_epoch(2, worker=1)
        assert (b.epoch, b.worker) == (2, 1)
        assert b.next_with_windows()[1] == streams[2, 1]  # reproducible
        assert round_trip(b).worker == 1
        with pytest.raises(ValueError, match="epoch must be at least 0"):
            b.set_epoch(-1)


def _first_batch(sampler):
    return sampler.next()


def test_spawned_workers_get_the_sampler(test_db):
    with mocapdb.open(test_db) as db:
        sampler = db.sampler(length=32, batch=4, seed=3)
        expected = round_trip(sampler).next()
        with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
            got = pool.submit(_first_batch, sampler).result(timeout=120)
    assert np.array_equal(got, expected)
