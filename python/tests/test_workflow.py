"""The workflow steps from Python give what the CLI's steps give on a copy of the same database."""
import shutil

import numpy as np

import mocapdb
from conftest import cli_json, run_cli


def test_create_set_equals_the_cli(cli, db_copy, tmp_path):
    cli_copy = tmp_path / "cli.h5"
    shutil.copyfile(db_copy, cli_copy)
    ours = mocapdb.create_set(db_copy, "turns", ["16_1*", "16_2*"], extract=["turn", "speed"])
    run_cli(cli, "set", "create", cli_copy, "--name", "turns", "--clips", "16_1*", "16_2*", "--extract", "turn", "speed")
    theirs = cli_json(cli, "set", "show", cli_copy, "turns")
    assert ours["set"] == "turns" and ours["samples"] == len(theirs["samples"])
    assert ours["parameter_names"] == [p["name"] for p in theirs["parameters"]]
    assert np.allclose(ours["parameters"], [s["values"] for s in theirs["samples"]], rtol=1e-12, atol=0)
    with mocapdb.open(db_copy) as db:
        assert [s.clip for s in db.set("turns").samples] == [s["clip"] for s in theirs["samples"]]


def test_pack_equals_the_cli(cli, db_copy, tmp_path):
    cli_copy = tmp_path / "cli.h5"
    shutil.copyfile(db_copy, cli_copy)
    ours = mocapdb.pack(db_copy, max_error_cm=0.5, replace=True)
    theirs = cli_json(cli, "pack", cli_copy, "--max-error-cm", "0.5", "--force")
    for key in ("bytes", "clips", "frames", "max_cm", "p99_cm", "rmse_cm", "float32_bytes", "max_error_cm"):
        assert ours[key] == theirs[key], key
    assert ours["max_cm"] <= 0.5
    assert ours["tier"].max_error_cm == 0.5
    with mocapdb.open(db_copy) as db:
        assert db.packed().bytes == ours["bytes"]
