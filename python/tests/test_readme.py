"""The README's Python snippet runs as written, on a copy of the examples' database named walks.h5."""
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import mocapdb


def test_readme_snippet_runs(test_db, tmp_path):
    readme = Path(os.environ.get("MOCAPDB_README", ""))
    if not readme.is_file():
        pytest.skip("MOCAPDB_README is not set (run the tests through ctest)")
    text = readme.read_text()
    found = re.search(r"<!-- python-snippet:begin -->\s*```python\n(.*?)```\s*<!-- python-snippet:end -->", text, re.S)
    assert found, "the README has no python snippet between the markers"
    mocapdb.copy_database(test_db, tmp_path / "walks.h5")
    (tmp_path / "snippet.py").write_text(found.group(1))
    done = subprocess.run([sys.executable, "snippet.py"], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "packed error" in done.stdout
    assert (tmp_path / "walker.bvh").stat().st_size > 1000
