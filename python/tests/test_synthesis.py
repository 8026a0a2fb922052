"""Synthesis from Python against `mocapdb query` and `mocapdb synth` on the same stored model."""
import numpy as np
import pytest

import mocapdb
from conftest import cli_json, run_cli


@pytest.fixture(scope="module")
def model(test_db):
    with mocapdb.open(test_db) as db:
        return db.synthesis_model("walks")


def between_samples(model, a=0, b=1, f=0.37):
    s = model.sample_parameters
    return (1 - f) * s[a] + f * s[b]


def param_text(c):
    return ",".join(repr(float(v)) for v in c)


def test_pose_equals_the_cli_query(cli, test_db, model):
    c = between_samples(model)
    for t in (0.0, 12.5, model.frames - 1):
        query = cli_json(cli, "query", test_db, "--set", "walks", "--param", param_text(c), "--frame", t)
        pose = model.pose(c, t)
        assert pose.shape == (model.dofs,)
        assert np.allclose(pose, query["pose_vector"], rtol=0, atol=1e-9)
        assert model.reliability(c) == pytest.approx(query["reliability"], abs=1e-12)


def test_joint_positions_of_a_pose_equal_the_cli_query(cli, test_db, model):
    c = between_samples(model, 2, 5)
    query = cli_json(cli, "query", test_db, "--set", "walks", "--param", param_text(c), "--frame", 7.25, "--joints")
    skeleton = model.skeleton
    channels = skeleton.channels_from_pose_vectors(model.pose(c, 7.25)[None, :])
    xyz = mocapdb.Clip(skeleton, channels, model.frame_rate).joint_positions()[0]
    theirs = {j["name"]: j["position"] for j in query["joints"]}
    for name, position in zip(skeleton.joint_names, xyz):
        if name in theirs:
            assert np.allclose(position, theirs[name], rtol=0, atol=1e-6)
    assert len(theirs) > 20


def test_batched_poses_equal_single_poses(model):
    rng = np.random.default_rng(3)
    s = model.sample_parameters
    lo, hi = s.min(axis=0), s.max(axis=0)
    C = lo + rng.random((257, s.shape[1])) * (hi - lo)
    batch = model.poses(C, 11.0)
    assert batch.shape == (257, model.dofs)
    for q in (0, 100, 256):
        assert np.allclose(batch[q], model.pose(C[q], 11.0), rtol=0, atol=1e-9)
    rho = model.reliability(C)
    assert rho.shape == (257,)
    assert rho[5] == pytest.approx(model.reliability(C[5]), abs=1e-12)
    assert ((rho >= 0) & (rho <= 1)).all()


def test_motion_equals_the_cli_synth(cli, test_db, model, tmp_path):
    c = between_samples(model, 1, 4)
    out = tmp_path / "synth.bvh"
    report = cli_json(cli, "synth", test_db, "--set", "walks", "--param", param_text(c), "-o", out)
    motion = model.motion(c)
    assert motion.frames == report["frames"]
    assert motion.frame_rate == pytest.approx(report["frame_rate"])
    assert model.reliability(c) == pytest.approx(report["reliability"], abs=1e-12)
    written = mocapdb.read_clip(out)
    # The BVH holds 9 significant digits: joint positions agree to well below a millimetre.
    assert np.abs(written.joint_positions() - motion.joint_positions()).max() < 1e-3


def test_reliability_falls_away_from_the_samples(model):
    """The nugget is filtered (measurement noise), so rho is below 1 even at a sample; it must fall as
    a query leaves the samples, and the kriging weights must sum to 1 (unbiasedness)."""
    s = model.sample_parameters
    centre, spread = s.mean(axis=0), s.std(axis=0)
    rho = [model.reliability(centre + k * spread) for k in (0, 0.5, 2, 8)]
    assert all(0 <= r <= 1 for r in rho)
    assert rho[0] > rho[1] >= rho[2] >= rho[3]
    assert rho[3] < 0.5 * rho[0]
    assert model.reliability(s[3]) > rho[1]
    assert model.weights(s[3]).sum() == pytest.approx(1.0, abs=1e-9)
    assert model.weights(centre + 8 * spread).sum() == pytest.approx(1.0, abs=1e-9)


def test_naive_model_and_bad_queries(test_db, model):
    with mocapdb.open(test_db) as db:
        naive = db.synthesis_model("walks", naive=True)
    assert naive.kind == "naive" and model.kind == "tucker"
    assert naive.dofs == model.dofs and naive.frames == model.frames
    with pytest.raises(mocapdb.InvalidArgument):
        model.pose(np.zeros(5), 1.0)
    with pytest.raises(mocapdb.InvalidArgument):
        model.pose(model.sample_parameters[0], model.frames + 3.0)
    with pytest.raises(mocapdb.InvalidArgument):
        model.poses(np.zeros((4, 3)), 1.0)


def test_reliability_warning_and_variance_ratio_equal_the_cli(cli, test_db, model):
    shown = cli_json(cli, "set", "show", test_db, "walks")
    assert model.reliability_warning == shown["reliability_warning"]  # the same object, or None for both
    assert model.local_neighbours == 0  # a small set: exact kriging of all samples
    c = between_samples(model, 1, 3, 0.5)
    query = cli_json(cli, "query", test_db, "--set", "walks", "--param", param_text(c), "--frame", 3)
    assert model.variance_ratio(c) == pytest.approx(query["variance_ratio"], abs=1e-12)
    assert model.reliability(c) == pytest.approx(min(max(1 - model.variance_ratio(c), 0), 1), abs=1e-12)
    s = model.sample_parameters
    far = s.max(axis=0) + 3 * s.std(axis=0)
    assert model.variance_ratio(s[0]) < model.variance_ratio(far)  # not clamped: grows beyond rho's 0
