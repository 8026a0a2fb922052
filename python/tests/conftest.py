"""Fixtures of the Python tests: the CLI and the database ctest's fixture built with it (the C++ results
every test compares with), the shared CMU data, and a CLI runner."""
import json
import os
import subprocess
from pathlib import Path

import pytest

import mocapdb


def _env_path(name):
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"{name} is not set (run the tests through ctest)")
    return Path(value)


@pytest.fixture(scope="session")
def cli():
    return _env_path("MOCAPDB_CLI")


@pytest.fixture(scope="session")
def shared():
    path = _env_path("MOCAPDB_SHARED")
    if not (path / "datasets" / "cmu-asfamc" / "16_11.amc").exists():
        pytest.skip(f"shared data not found at {path}")
    return path


@pytest.fixture(scope="session")
def test_db(shared):
    """The read-only database: subject 16's walks 16_11..16_24, set 'walks' (turn, speed) aligned to 40
    frames, its Tucker model at 1 cm, and a packed tier at 1 cm (examples/make_example_db.sh)."""
    path = _env_path("MOCAPDB_TEST_DB")
    if not path.exists():
        pytest.skip(f"{path} was not built")
    return path


@pytest.fixture
def db_copy(test_db, tmp_path):
    """A private copy of the test database for tests that write."""
    path = tmp_path / "copy.h5"
    mocapdb.copy_database(test_db, path)
    return path


def run_cli(cli, *args, check=True):
    """Runs the CLI; returns (exit code, stdout, stderr)."""
    done = subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"mocapdb {' '.join(map(str, args))} failed: {done.stderr}")
    return done.returncode, done.stdout, done.stderr


def cli_json(cli, *args):
    return json.loads(run_cli(cli, *args, "--json")[1])
