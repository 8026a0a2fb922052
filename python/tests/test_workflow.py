"""The workflow steps from Python give what the CLI's steps give on a copy of the same database."""

import numpy as np
import pytest

import mocapdb
from conftest import cli_json, run_cli


def test_create_set_equals_the_cli(cli, db_copy, tmp_path):
    cli_copy = tmp_path / "cli.h5"
    mocapdb.copy_database(db_copy, cli_copy)
    ours = mocapdb.create_set(db_copy, "turns", ["16_1*", "16_2*"], extract=["turn", "speed"])
    run_cli(cli, "set", "create", cli_copy, "--name", "turns", "--clips", "16_1*", "16_2*", "--extract", "turn", "speed")
    theirs = cli_json(cli, "set", "show", cli_copy, "turns")
    assert ours["set"] == "turns" and ours["samples"] == len(theirs["samples"])
    assert ours["parameter_names"] == [p["name"] for p in theirs["parameters"]]
    assert np.allclose(ours["parameters"], [s["values"] for s in theirs["samples"]], rtol=1e-12, atol=0)
    with mocapdb.open(db_copy) as db:
        assert [s.clip for s in db.set("turns").samples] == [s["clip"] for s in theirs["samples"]]


def test_create_set_with_a_category_equals_the_cli(cli, db_copy, tmp_path):
    """categories={name: regex}: the level is the regex's first group in the clip id (16_1x against 16_2x)."""
    cli_copy = tmp_path / "cli.h5"
    mocapdb.copy_database(db_copy, cli_copy)
    ours = mocapdb.create_set(db_copy, "decades", ["16_*"], extract=["turn"], segment="none",
                              categories={"decade": "^16_([12])"})
    run_cli(cli, "set", "create", cli_copy, "--name", "decades", "--clips", "16_*", "--extract", "turn",
            "--segment", "none", "--category", "decade=^16_([12])")
    theirs = cli_json(cli, "set", "show", cli_copy, "decades")
    assert ours["parameter_names"] == ["turn", "decade"] == [p["name"] for p in theirs["parameters"]]
    assert theirs["parameters"][1]["levels"] == ["1", "2"]
    assert np.allclose(ours["parameters"], [s["values"] for s in theirs["samples"]], rtol=1e-12, atol=0)
    with mocapdb.open(db_copy) as db:
        s = db.set("decades")
        assert s.parameter_levels == [[], ["1", "2"]]
        assert [int(row[1]) for row in s.parameters] == [0 if x.clip < "16_20" else 1 for x in s.samples]
    with pytest.raises(mocapdb.InvalidArgument, match="does not match clip"):
        mocapdb.create_set(db_copy, "bad", ["16_*"], segment="none", categories={"decade": "^16_(1)"})


def test_pack_equals_the_cli(cli, db_copy, tmp_path):
    cli_copy = tmp_path / "cli.h5"
    mocapdb.copy_database(db_copy, cli_copy)
    ours = mocapdb.pack(db_copy, max_error_cm=0.5, replace=True)
    theirs = cli_json(cli, "pack", cli_copy, "--max-error-cm", "0.5", "--force")
    for key in ("bytes", "clips", "frames", "max_cm", "p99_cm", "rmse_cm", "float32_bytes", "max_error_cm"):
        assert ours[key] == theirs[key], key
    assert ours["max_cm"] <= 0.5
    assert ours["max_error_cm"] == 0.5
    with mocapdb.open(db_copy) as db:
        assert db.packed().bytes == ours["bytes"]
    # Bytes per kind of stored data, as the CLI gives them, summing exactly to the bytes.
    assert ours["parts"] == theirs["parts"]
    assert list(ours["parts"]) == list(theirs["parts"])
    assert sum(ours["parts"].values()) == ours["bytes"]
    assert [sum(g["parts"].values()) for g in ours["groups"]] == [g["bytes"] for g in theirs["groups"]]
    assert ours["budget"] is None
    # Runtime groups by default; the archive format on request, as the CLI's --format.
    assert [g["format"] for g in ours["groups"]] == ["runtime"] * len(ours["groups"])
    archive = mocapdb.pack(db_copy, max_error_cm=0.5, replace=True, format="archive")
    theirs = cli_json(cli, "pack", cli_copy, "--max-error-cm", "0.5", "--force", "--format", "archive")
    assert [g["format"] for g in archive["groups"]] == ["archive"] * len(archive["groups"])
    assert archive["bytes"] == theirs["bytes"] and archive["max_cm"] <= 0.5
    with pytest.raises(mocapdb.Error):
        mocapdb.pack(db_copy, max_error_cm=0.5, replace=True, format="fast")


def test_pack_to_a_byte_budget(cli, db_copy, tmp_path):
    cli_copy = tmp_path / "cli.h5"
    mocapdb.copy_database(db_copy, cli_copy)
    coarse = mocapdb.pack(db_copy, max_error_cm=1.0, replace=True)["bytes"]
    budget = int(coarse * 1.5)
    ours = mocapdb.pack(db_copy, max_bytes=budget, replace=True)
    theirs = cli_json(cli, "pack", cli_copy, "--max-bytes", str(budget), "--force")
    assert ours["bytes"] <= budget
    assert ours["max_error_cm"] < 1.0 and ours["max_cm"] <= ours["max_error_cm"]
    for key in ("bytes", "max_error_cm", "max_cm", "parts", "budget"):
        assert ours[key] == theirs[key], key
    assert ours["budget"]["max_bytes"] == budget
    with pytest.raises(mocapdb.Error, match="smallest this collection packs to"):
        mocapdb.pack(db_copy, max_bytes=10, replace=True)
    with pytest.raises(mocapdb.Error, match="not both"):
        mocapdb.pack(db_copy, max_error_cm=1.0, max_bytes=budget, replace=True)
    with mocapdb.open(db_copy) as db:
        assert db.packed().max_error_cm == ours["max_error_cm"]  # the failed calls changed nothing


def test_import_align_compress_equal_the_cli(cli, shared, tmp_path):
    """The whole chain from Python and from the CLI on the same clips gives the same database content."""
    amc = shared / "datasets" / "cmu-asfamc"
    files = [amc / f"16_{t}.amc" for t in range(11, 19)]
    ours, theirs = tmp_path / "py.h5", tmp_path / "cli.h5"

    imported = mocapdb.import_files(ours, files)
    run_cli(cli, "import", *files, "-o", theirs)
    assert imported["added"] == imported["clips_in_db"] == 8 and imported["skipped"] == 0
    again = mocapdb.import_files(ours, files[:2])
    assert again["added"] == 0 and again["skipped"] == 2 and len(again["not_added"]) == 2

    mocapdb.create_set(ours, "walks", ["16_*"], extract=["turn", "speed"])
    run_cli(cli, "set", "create", theirs, "--name", "walks", "--clips", "16_*", "--extract", "turn", "speed")
    aligned = mocapdb.align(ours, "walks", frames=30)
    run_cli(cli, "align", theirs, "--set", "walks", "--frames", "30")
    compressed = mocapdb.compress(ours, "walks", max_error_cm=1.0)
    cli_compressed = cli_json(cli, "compress", theirs, "--set", "walks", "--max-error-cm", "1")

    assert aligned["frames"] == 30 and aligned["dofs"] == 90
    for key in ("criterion", "target_met", "ranks", "bytes", "ratio", "max_cm", "p99_cm", "rmse_cm"):
        value = list(compressed[key]) if isinstance(compressed[key], tuple) else compressed[key]
        assert value == cli_compressed[key], key
    assert compressed["max_cm"] <= 1.0
    with mocapdb.open(ours) as a, mocapdb.open(theirs) as b:
        assert [c.sha256 for c in a.clips()] == [c.sha256 for c in b.clips()]
        info_a = [s for s in a.sets() if s.name == "walks"][0]
        info_b = [s for s in b.sets() if s.name == "walks"][0]
        assert info_a.tensor_shape == info_b.tensor_shape and info_a.model_ranks == info_b.model_ranks
        c = a.set("walks").parameters.mean(axis=0)
        assert np.array_equal(a.synthesis_model("walks").pose(c, 3.5), b.synthesis_model("walks").pose(c, 3.5))


def test_compress_reports_progress(db_copy):
    """compress calls progress(done, total, item) for the rank search, the kernel's candidate variograms and
    its factorized system: per item, done never decreases and reaches total."""
    calls = []
    mocapdb.compress(db_copy, "walks", max_error_cm=1.0,
                     progress=lambda done, total, item: calls.append((item, done, total)))
    items = {item for item, _, _ in calls}
    assert {"rank search", "kernel", "kernel system"} <= items
    for item in items:
        steps = [(done, total) for i, done, total in calls if i == item]
        assert all(a[0] <= b[0] and a[1] == b[1] for a, b in zip(steps, steps[1:])), item
        assert steps[-1][0] == steps[-1][1] > 0, item


def test_a_progress_callable_that_raises(db_copy):
    """The callable's exception is raised when the call returns (the library's callbacks cannot throw)."""
    with pytest.raises(ZeroDivisionError):
        mocapdb.compress(db_copy, "walks", progress=lambda done, total, item: 1 / 0)
    with pytest.raises(TypeError, match="progress: expected None or a callable"):
        mocapdb.compress(db_copy, "walks", progress=3)
    with mocapdb.open(db_copy) as db:
        calls = []
        db.synthesis_model("walks", naive=True, progress=lambda done, total, item: calls.append((item, done, total)))
        # A model fitted at load: its candidate variograms, then its system factorized (no stored one).
        assert [item for item, _, _ in calls][-1] == "kernel system" and calls[-1][1] == calls[-1][2]
        assert ("kernel", 1, calls[0][2]) == calls[0]


def test_workflow_errors(shared, tmp_path):
    with pytest.raises(mocapdb.InvalidArgument, match="no .bvh or .amc files found"):
        mocapdb.import_files(tmp_path / "x.h5", [tmp_path])
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n}\n")
    with pytest.raises(mocapdb.ParseError):
        mocapdb.import_files(tmp_path / "y.h5", [bad])
    done = mocapdb.import_files(tmp_path / "z.h5", [bad, shared / "datasets" / "cmu-asfamc" / "16_11.amc"], keep_going=True)
    assert done["added"] == 1 and done["failed"] == 1 and "bad.bvh" in done["errors"][0]
    with pytest.raises(mocapdb.InvalidArgument):
        mocapdb.compress(tmp_path / "z.h5", "walks", method="svd")


def _listing(folder):
    """Every file and folder under `folder` with its size (None for a folder), sorted."""
    return sorted((str(p.relative_to(folder)), p.stat().st_size if p.is_file() else None) for p in folder.rglob("*"))


def test_a_failure_on_a_worker_thread_is_an_exception_and_leaves_the_folder(db_copy):
    """A clip that cannot pack (a bound below what the float32 skeleton reaches: every clip
    fails, so both encoder threads do) raises mocapdb.Error instead of taking the interpreter down, and
    the database and its folder stay exactly as they were (no temporary file, lock or segment)."""
    folder = db_copy.parent
    # A database some session has written (the copy has not): its writer lock file exists, as it does
    # for good (never removed: writer_lock.hpp), and its readers' lock file.
    mocapdb.pack(db_copy, max_error_cm=1.0, replace=True)
    before = _listing(folder)
    assert (folder / "copy.h5.lock").exists()
    assert any(name.endswith(".h5") for name, _ in before)
    for threads in (2, 1):
        with pytest.raises(mocapdb.Error, match=r"window 0 frame \d+: even its source rows are .* over 1e-09 cm"):
            mocapdb.pack(db_copy, max_error_cm=1e-9, threads=threads, replace=True)
        assert _listing(folder) == before
    with mocapdb.open(db_copy) as db:
        assert db.packed().max_error_cm == 1.0  # the tier it had


def test_collection_report_equals_the_cli(cli, test_db):
    ours = mocapdb.collection_report(test_db, max_error_cm=[1.0])
    theirs = cli_json(cli, "report", test_db, "--collection", "--max-error-cm", "1", "--poses", "0")
    for key in ("clips", "frames", "groups", "float32_bytes"):
        assert ours[key] == theirs[key], key
    assert ours["lossless"]["bytes"] == theirs["lossless"]["bytes"]
    [a], [b] = ours["targets"], theirs["targets"]
    for key in ("max_error_cm", "bytes", "max_cm", "p99_cm", "rmse_cm", "clips", "frames", "resident_bytes"):
        assert a[key] == b[key], key
    assert a["max_cm"] <= 1.0
