"""mocapdb.open and clips from Python against the CLI's JSON and exported files, and the source files."""
import numpy as np
import pytest

import mocapdb
from conftest import cli_json, run_cli


def test_clip_records_equal_the_cli_listing(cli, test_db):
    listing = cli_json(cli, "info", test_db)
    with mocapdb.open(test_db) as db:
        clips = db.clips()
        assert db.format_version == listing["format_version"]
        assert db.file_size == listing["file_bytes"]
    assert [c.name for c in clips] == [c["id"] for c in listing["clips"]]
    for ours, theirs in zip(clips, listing["clips"]):
        assert ours.frames == theirs["frames"]
        assert ours.frame_rate == theirs["frame_rate"]
        assert ours.skeleton == theirs["skeleton"]
        assert ours.channels == theirs["channels"]
        assert ours.sha256 == theirs["source_sha256"]
        assert ours.source_file == theirs["source_file"]


def test_lossless_clip_is_the_source_file_exactly(test_db, shared):
    amc = shared / "datasets" / "cmu-asfamc" / "16_11.amc"
    source = mocapdb.read_clip(amc)
    with mocapdb.open(test_db) as db:
        stored = db.clip("16_11")
    assert stored.frames == source.frames and stored.frame_rate == source.frame_rate
    assert np.array_equal(stored.channels, source.channels)
    assert stored.skeleton.joint_names == source.skeleton.joint_names
    assert np.array_equal(stored.skeleton.offsets, source.skeleton.offsets)


def test_joint_positions_equal_those_of_the_cli_export(cli, test_db, tmp_path):
    """FK in Python of the stored ASF clip = FK of the BVH the CLI exports (another rig encoding of the
    same motion: BVH Euler channels instead of ASF axes), every joint and end site."""
    out = tmp_path / "16_11.bvh"
    run_cli(cli, "export", test_db, "--clip", "16_11", "-o", out, "--precision", "17")
    with mocapdb.open(test_db) as db:
        ours = db.clip("16_11").joint_positions()
    exported = mocapdb.read_clip(out)
    theirs = exported.joint_positions()
    assert ours.shape == theirs.shape == (exported.frames, len(exported.skeleton), 3)
    assert np.abs(ours - theirs).max() < 1e-6
    # A figure standing on its feet: about 1.5 to 2 m from the lowest to the highest joint at frame 0.
    height = ours[0, :, 1].max() - ours[0, :, 1].min()
    assert 140.0 < height < 210.0


def test_packed_tier_records_and_bound(cli, test_db, tmp_path):
    with mocapdb.open(test_db) as db:
        tier = db.packed()
        assert tier is not None and tier.max_error_cm == 1.0
        assert tier.clips == len(db.clips())
        lossless = db.clip("16_12")
        packed = db.clip("16_12", tier="packed")
        part = db.clip("16_12", tier="packed", begin=10, end=30)
    error = np.linalg.norm(packed.joint_positions() - lossless.joint_positions(), axis=2)
    assert error.max() <= tier.max_error_cm + 1e-4
    record = [c for g in tier.groups for c in g.clips if c.name == "16_12"][0]
    assert error.max() == pytest.approx(record.max_cm, abs=1e-4)
    assert np.array_equal(part.channels, packed.channels[10:30])
    # The CLI's export from the packed tier is the same motion.
    out = tmp_path / "packed.bvh"
    run_cli(cli, "export", test_db, "--clip", "16_12", "--from-packed", "-o", out, "--precision", "17")
    assert np.abs(mocapdb.read_clip(out).joint_positions() - packed.joint_positions()).max() < 1e-6


def test_sets_and_their_parameters_equal_the_cli(cli, test_db):
    shown = cli_json(cli, "set", "show", test_db, "walks")
    with mocapdb.open(test_db) as db:
        info = [s for s in db.sets() if s.name == "walks"][0]
        walks = db.set("walks")
    assert info.aligned and info.model and shown["aligned"]
    assert info.samples == len(walks.samples) == len(shown["samples"])
    assert walks.parameter_names == [p["name"] for p in shown["parameters"]]
    assert info.tensor_shape == (info.samples, shown["frames"], shown["dofs"])
    for ours, value, theirs in zip(walks.samples, walks.parameters, shown["samples"]):
        assert (ours.clip, ours.begin, ours.end) == (theirs["clip"], theirs["begin"], theirs["end"])
        assert np.allclose(value, theirs["values"], rtol=1e-12, atol=0)


def test_pose_vectors_invert_to_the_channels(test_db):
    with mocapdb.open(test_db) as db:
        clip = db.clip("16_13")
    poses = clip.pose_vectors(canonical=False)
    assert poses.shape == (clip.frames, clip.skeleton.pose_values)
    channels = clip.skeleton.channels_from_pose_vectors(poses)
    back = mocapdb.Clip(clip.skeleton, channels, clip.frame_rate)
    assert np.abs(back.joint_positions() - clip.joint_positions()).max() < 1e-6


def test_write_bvh_round_trip(tmp_path, shared):
    source = mocapdb.read_clip(shared / "datasets" / "cmu-walkrun-pfnn" / sorted(
        p.name for p in (shared / "datasets" / "cmu-walkrun-pfnn").glob("*.bvh"))[0])
    out = tmp_path / "copy.bvh"
    source.write_bvh(out, precision=17)
    again = mocapdb.read_clip(out)
    # Radians -> degrees in the file -> radians: equal to the last bits of a double.
    assert np.allclose(again.channels, source.channels, rtol=1e-14, atol=1e-14)
    assert np.abs(again.joint_positions() - source.joint_positions()).max() < 1e-9
    assert again.frame_rate == pytest.approx(source.frame_rate, rel=1e-12)


def test_errors_are_exceptions_with_the_cli_message(cli, test_db, tmp_path):
    missing = tmp_path / "missing.h5"
    with pytest.raises(mocapdb.IoError) as caught:
        mocapdb.open(missing)
    assert isinstance(caught.value, OSError) and str(missing) in str(caught.value)

    with mocapdb.open(test_db) as db:
        with pytest.raises(mocapdb.StoreError) as caught:
            db.synthesis_model("no_such_set")
    code, _, err = run_cli(cli, "query", test_db, "--set", "no_such_set", "--param", "0,0", "--frame", "0", check=False)
    assert code != 0
    assert err == f"mocapdb: error: {caught.value}\n"  # the same one-line message

    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n}\n")
    with pytest.raises(mocapdb.ParseError) as caught:
        mocapdb.read_clip(bad)
    assert isinstance(caught.value, ValueError)
    assert caught.value.file.endswith("bad.bvh") and caught.value.line == 5  # the "}" where a number was due

    with pytest.raises(mocapdb.InvalidArgument):
        mocapdb.open(test_db).clip("16_11", tier="zipped")
    db = mocapdb.open(test_db)
    db.close()
    with pytest.raises(mocapdb.InvalidArgument, match="closed"):
        db.clips()


def test_written_bvh_is_the_cli_export_byte_for_byte(cli, test_db, tmp_path):
    ours, theirs = tmp_path / "py.bvh", tmp_path / "cli.bvh"
    with mocapdb.open(test_db) as db:
        db.clip("16_14").write_bvh(ours)
    run_cli(cli, "export", test_db, "--clip", "16_14", "-o", theirs)
    assert ours.read_bytes() == theirs.read_bytes()
