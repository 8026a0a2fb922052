"""Rigs and files from arrays: local rotations and root positions of a clip, forward kinematics of them,
clips from them, and BVH written from arrays re-importing to the same joint positions."""
import numpy as np
import pytest

import mocapdb


def quat_mul(a, b):
    w1, x1, y1, z1 = np.moveaxis(a, -1, 0)
    w2, x2, y2, z2 = np.moveaxis(b, -1, 0)
    return np.stack([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2], axis=-1)


def quat_matrix(q):
    w, x, y, z = np.moveaxis(q, -1, 0)
    return np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                     np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                     np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], -2)


def clips(test_db, shared):
    bvh = sorted((shared / "datasets" / "cmu-walkrun-pfnn").glob("*.bvh"))[0]
    with mocapdb.open(test_db) as db:
        asf = db.clip("16_11")
    pfnn = mocapdb.read_clip(bvh)
    return [asf.slice(0, 200), pfnn.slice(0, min(200, pfnn.frames))]


def test_fk_of_the_arrays_is_the_clips_joint_positions(test_db, shared):
    for clip in clips(test_db, shared):
        q, p = clip.local_rotations(), clip.root_positions()
        assert q.shape == (clip.frames, len(clip.skeleton), 4) and p.shape == (clip.frames, 3)
        assert np.allclose(np.linalg.norm(q, axis=2), 1.0)
        assert np.abs(clip.skeleton.fk(q, p) - clip.joint_positions()).max() < 1e-6
        assert np.abs(clip.skeleton.fk(quat_matrix(q), p) - clip.joint_positions()).max() < 1e-6


def test_a_rotated_copy_written_as_bvh_reimports_to_the_same_positions(test_db, shared, tmp_path):
    angle = np.radians(40.0)
    turn = np.array([np.cos(angle / 2), 0.0, np.sin(angle / 2), 0.0])  # 40 degrees about +Y
    shift = np.array([100.0, 0.0, -50.0])
    for k, clip in enumerate(clips(test_db, shared)):  # an ASF clip (bone axes) and a PFNN BVH clip
        q, p = clip.local_rotations(), clip.root_positions()
        q[:, 0] = quat_mul(turn, q[:, 0])
        p = p @ quat_matrix(turn).T + shift
        expected = clip.joint_positions() @ quat_matrix(turn).T + shift
        for rotations in (q, quat_matrix(q)):
            copy = mocapdb.Clip.from_arrays(clip.skeleton, clip.frame_rate, rotations=rotations, root_positions=p)
            assert np.abs(copy.joint_positions() - expected).max() < 1e-6
        path = tmp_path / f"rotated_{k}.bvh"
        mocapdb.write_bvh(copy, path)
        back = mocapdb.read_clip(path)
        assert back.frames == clip.frames and back.skeleton.joint_names == clip.skeleton.joint_names
        assert np.abs(back.joint_positions() - expected).max() < 1e-3


def test_a_skeleton_from_arrays(tmp_path):
    rig = mocapdb.Skeleton(["hips", "knee", "foot"], [-1, 0, 1], np.array([[0, 90, 0], [0, -45, 0], [0, -45, 0]], float),
                           end_sites=[False, False, True])
    assert rig.joint_names == ["hips", "knee", "foot"] and rig.parents == [-1, 0, 1] and rig.end_sites == [False, False, True]
    assert rig.channel_names[:4] == ["hips.Xposition", "hips.Yposition", "hips.Zposition", "hips.Zrotation"]
    assert rig.channel_count == 9
    frames = 5
    bend = np.radians(np.linspace(0, 90, frames))
    q = np.zeros((frames, 3, 4))
    q[:, :, 0] = 1.0
    q[:, 1] = np.stack([np.cos(bend / 2), np.sin(bend / 2), 0 * bend, 0 * bend], -1)  # the knee about +X
    root = np.tile([10.0, 90.0, 0.0], (frames, 1))
    xyz = rig.fk(q, root)
    # Turning about +X takes the shin (0, -45, 0) to (0, -45 cos, -45 sin): the foot swings back.
    assert np.allclose(xyz[:, 1], [10, 45, 0])
    assert np.allclose(xyz[:, 2], np.stack([10 + 0 * bend, 45 - 45 * np.cos(bend), -45 * np.sin(bend)], -1))
    clip = mocapdb.Clip.from_arrays(rig, 30.0, rotations=q, root_positions=root, name="bend")
    assert np.allclose(clip.joint_positions(), xyz)
    mocapdb.write_bvh(clip, tmp_path / "bend.bvh")
    assert np.abs(mocapdb.read_clip(tmp_path / "bend.bvh").joint_positions() - xyz).max() < 1e-3
    custom = mocapdb.Skeleton(["a", "b"], [-1, 0], np.zeros((2, 3)), channels=[["Yrotation"], []])
    assert custom.channel_names == ["a.Yrotation"]


def test_bad_arrays_say_what_is_wrong():
    with pytest.raises(ValueError, match="unknown channel 'Wrotation'"):
        mocapdb.Skeleton(["a"], [-1], np.zeros((1, 3)), channels=[["Wrotation"]])
    with pytest.raises(ValueError, match="offsets of shape \\(2, 3\\)"):
        mocapdb.Skeleton(["a", "b"], [-1, 0], np.zeros((3, 3)))
    rig = mocapdb.Skeleton(["a", "b"], [-1, 0], np.zeros((2, 3)))
    with pytest.raises(ValueError, match="expected \\(F, 2, 4\\) quaternions"):
        rig.fk(np.zeros((4, 3, 4)), np.zeros((4, 3)))
    with pytest.raises(ValueError, match="expected a unit quaternion"):
        rig.fk(np.zeros((4, 2, 4)), np.zeros((4, 3)))
    with pytest.raises(ValueError, match="root_positions: expected shape \\(4, 3\\)"):
        mocapdb.Clip.from_arrays(rig, 30.0, rotations=np.tile([1.0, 0, 0, 0], (4, 2, 1)), root_positions=np.zeros((5, 3)))
    with pytest.raises(ValueError, match="is not a rotation"):
        rig.fk(np.ones((4, 2, 3, 3)), np.zeros((4, 3)))
