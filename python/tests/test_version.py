"""The package's version is the project's one version (CMakeLists.txt's project(), configured into
mocapdb/core/version.hpp): the same as the CLI's --version."""
import re
import subprocess

import mocapdb


def test_version_is_the_clis(cli):
    assert re.fullmatch(r"[0-9]+\.[0-9]+\.[0-9]+", mocapdb.__version__)
    out = subprocess.run([str(cli), "--version"], check=True, capture_output=True, text=True).stdout
    assert out.strip() == "mocapdb " + mocapdb.__version__
