"""The library's errors say what is wrong and name no command-line flag; Python adds the keyword that
fixes it (the CLI adds its flag: tests/cli)."""
import pytest

import mocapdb


def test_refusals_name_the_python_keyword_not_the_flag(db_copy):
    mocapdb.create_set(db_copy, "walks2", ["16_1*"], extract=["speed"])
    with pytest.raises(mocapdb.InvalidArgument) as existing:
        mocapdb.create_set(db_copy, "walks2", ["16_1*"], extract=["speed"])
    assert "set 'walks2' exists; pass replace=True" in str(existing.value)
    with pytest.raises(mocapdb.InvalidArgument) as unaligned:
        mocapdb.compress(db_copy, "walks2")
    assert "is not aligned; run mocapdb.align(db, set) first" in str(unaligned.value)
    for error in (existing, unaligned):
        assert "--" not in str(error.value)
