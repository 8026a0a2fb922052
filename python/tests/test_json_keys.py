"""Every workflow step gives the same JSON keys from Python as from the CLI's --json: both come from
one writer per step (json/mocapdb_json/step_json.hpp, report_json.hpp), so they cannot drift."""
import shutil

import mocapdb
from conftest import cli_json


def _shape(value):
    """The keys of a document, recursively (lists by their first element), without the values."""
    if isinstance(value, dict):
        return {k: _shape(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_shape(value[0])] if value else []
    return None


def _same_keys(ours, theirs, step):
    assert list(ours) == list(theirs), f"{step}: top-level keys differ"
    assert _shape(ours) == _shape(theirs), f"{step}: nested keys differ"


def test_every_step_has_the_clis_keys(cli, shared, tmp_path):
    walks = tmp_path / "walks"
    walks.mkdir()
    for name in ("16.asf", "16_11.amc", "16_12.amc", "16_13.amc", "16_14.amc", "16_15.amc", "16_16.amc"):
        shutil.copy(shared / "datasets" / "cmu-asfamc" / name, walks / name)
    ours, theirs = tmp_path / "py.h5", tmp_path / "cli.h5"

    _same_keys(mocapdb.import_files(ours, [walks]), cli_json(cli, "import", walks, "-o", theirs), "import")
    clips = ["16_1*"]
    _same_keys(mocapdb.create_set(ours, "walks", clips, extract=["turn", "speed"]),
               cli_json(cli, "set", "create", theirs, "--name", "walks", "--clips", *clips, "--extract", "turn", "speed"),
               "set create")
    _same_keys(mocapdb.align(ours, "walks", frames=30), cli_json(cli, "align", theirs, "--set", "walks", "--frames", "30"),
               "align")
    _same_keys(mocapdb.compress(ours, "walks", max_error_cm=1.0),
               cli_json(cli, "compress", theirs, "--set", "walks", "--max-error-cm", "1"), "compress")
    _same_keys(mocapdb.pack(ours, max_error_cm=1.0), cli_json(cli, "pack", theirs, "--max-error-cm", "1"), "pack")
    _same_keys(mocapdb.collection_report(ours, max_error_cm=[1.0]),
               cli_json(cli, "report", theirs, "--collection", "--max-error-cm", "1", "--poses", "0"), "report --collection")
