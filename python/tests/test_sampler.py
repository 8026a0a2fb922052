"""Training windows: reproducible by seed, equal to the clips they come from, one rig per sampler."""
import numpy as np
import pytest

import mocapdb
from conftest import run_cli


def test_same_seed_same_batches(test_db):
    with mocapdb.open(test_db) as db:
        a = db.sampler(length=64, batch=16, seed=11, dtype=np.float64)
        b = db.sampler(length=64, batch=16, seed=11, dtype=np.float64)
        c = db.sampler(length=64, batch=16, seed=12, dtype=np.float64)
        first = [a.next() for _ in range(3)]
        again = [b.next() for _ in range(3)]
        other = c.next()
    assert a.from_packed  # the test database has a packed tier holding every clip
    assert first[0].shape == (16, 64, a.values_per_frame)
    for x, y in zip(first, again):
        assert np.array_equal(x, y)
    assert not np.array_equal(first[0], other)
    assert not np.array_equal(first[0], first[1])


def test_windows_are_the_clips_in_their_canonical_frame(test_db):
    with mocapdb.open(test_db) as db:
        packed = db.sampler(length=48, batch=8, seed=5, dtype=np.float64)
        lossless = db.sampler(length=48, batch=8, seed=5, source="lossless", dtype=np.float64)
        batch, windows = packed.next_with_windows()
        exact, same_windows = lossless.next_with_windows()
        assert windows == same_windows  # the draw does not depend on the source
        for k, (name, begin) in enumerate(windows):
            end = begin + 48
            assert 0 <= begin and end <= db.clip(name, tier="packed").frames
            assert np.allclose(batch[k], db.clip(name, tier="packed", begin=begin, end=end).pose_vectors(), rtol=0, atol=1e-9)
            # The cached world values with the window's rigid motion removed: equal but for rounding.
            assert np.allclose(exact[k], db.clip(name).slice(begin, end).pose_vectors(), rtol=0, atol=1e-9)
            assert np.array_equal(packed.window(name, begin), batch[k])
        assert not lossless.from_packed


def test_joint_positions_match_the_pose_vectors(test_db):
    with mocapdb.open(test_db) as db:
        poses = db.sampler(length=32, batch=4, seed=2, source="lossless", dtype=np.float64)
        points = db.sampler(length=32, batch=4, seed=2, source="lossless", values="joint_positions", dtype=np.float64)
        skeleton = db.skeleton(db.clips()[0].skeleton)
        p, windows = poses.next_with_windows()
        x = points.next()
    assert x.shape == (4, 32, 3 * len(skeleton))
    assert points.joint_names == skeleton.joint_names
    for k in range(4):
        clip = mocapdb.Clip(skeleton, skeleton.channels_from_pose_vectors(p[k]), poses.frame_rate)
        assert np.abs(clip.joint_positions().reshape(32, -1) - x[k]).max() < 1e-6
        # Canonical: the window's first frame has its root above the origin.
        assert abs(p[k, 0, 0]) < 1e-9 and abs(p[k, 0, 2]) < 1e-9


def test_one_rig_per_sampler(cli, shared, tmp_path):
    bvh = sorted((shared / "datasets" / "cmu-walkrun-pfnn").glob("*.bvh"))[0]
    amc = shared / "datasets" / "cmu-asfamc" / "16_11.amc"
    db_path = tmp_path / "mixed.h5"
    run_cli(cli, "import", amc, bvh, "-o", db_path)
    with mocapdb.open(db_path) as db:
        with pytest.raises(mocapdb.InvalidArgument, match="select clips of one"):
            db.sampler(length=16)
        only_asf = db.sampler(length=16, batch=2, clips=["16_*"])
        assert only_asf.clips == ["16_11"] and not only_asf.from_packed
        with pytest.raises(mocapdb.InvalidArgument, match="not in the packed tier"):
            db.sampler(length=16, source="packed", clips=["16_*"])
        with pytest.raises(mocapdb.InvalidArgument, match="no clip matches"):
            db.sampler(clips=["nothing*"])
        with pytest.raises(mocapdb.InvalidArgument, match="frames"):
            db.sampler(length=10**6, clips=["16_*"])
        with pytest.raises(mocapdb.InvalidArgument):
            db.sampler(values="angles")


def test_threads_share_a_packed_sampler_safely(test_db):
    """Batches from the packed tier run without the GIL; threads on one sampler take turns."""
    import threading

    with mocapdb.open(test_db) as db:
        shared = db.sampler(length=32, batch=8, seed=4)
        alone = db.sampler(length=32, batch=8, seed=4)
        assert shared.dtype == np.float32
        expected = [alone.next() for _ in range(8)]
        got = []
        lock = threading.Lock()

        def work():
            for _ in range(2):
                batch = shared.next()
                with lock:
                    got.append(batch)

        threads = [threading.Thread(target=work) for _ in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    assert len(got) == 8
    # The same eight batches, in whatever order the threads took them.
    assert sorted(b.tobytes() for b in got) == sorted(b.tobytes() for b in expected)


@pytest.mark.parametrize("source", ["packed", "lossless"])
@pytest.mark.parametrize("values", ["pose_vectors", "joint_positions"])
def test_float32_by_default_float64_on_request(test_db, source, values):
    with mocapdb.open(test_db) as db:
        single = db.sampler(length=40, batch=8, seed=3, source=source, values=values)
        double = db.sampler(length=40, batch=8, seed=3, source=source, values=values, dtype="float64")
        a, windows = single.next_with_windows()
        b, same = double.next_with_windows()
        assert single.dtype == np.float32 and a.dtype == np.float32 and b.dtype == np.float64
        assert windows == same
        # The decoded clips: F x V values of the dtype and 3 float64 (heading and floor position) per frame.
        frames = {c.name: c.frames for c in db.clips()}
        V = single.values_per_frame
        assert single.cache_bytes == sum(frames[n] * (4 * V + 24) for n in set(n for n, _ in windows))
        assert double.cache_bytes == sum(frames[n] * (8 * V + 24) for n in set(n for n, _ in same))
        # float32 end to end: within float32 rounding of the float64 windows (values up to a few 100 cm).
        assert np.abs(a - b).max() < 1e-3
        assert np.abs(a - b).max() > 0  # not a float64 batch cast afterwards: decoded as float32
        name, begin = windows[0]
        assert single.window(name, begin).dtype == np.float32
        assert np.array_equal(single.window(name, begin), a[0])
        out = np.zeros_like(a)
        assert single.next(out=out) is out and not np.array_equal(out, a)
        with pytest.raises(ValueError, match="out must be a writeable C-contiguous float32 array of shape"):
            single.next(out=np.zeros(a.shape, np.float64))


def test_bad_dtype(test_db):
    with mocapdb.open(test_db) as db:
        with pytest.raises(ValueError, match="dtype must be float32 or float64, got int32"):
            db.sampler(dtype=np.int32)
        with pytest.raises(TypeError, match="dtype must be numpy.float32 or numpy.float64"):
            db.sampler(dtype="no such type")
