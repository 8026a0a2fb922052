// Refusing files that are not valid databases: foreign and newer files, truncated files,
// corrupted chunks (fletcher32), wrong dtypes and shapes. Every message names the file, the HDF5 path
// and what was expected. Fixtures: tests/data/bad-*.h5 (made by tests/data/make_bad_fixtures.py).
#include <catch2/catch.hpp>

#include <fstream>

#include "mocapdb/store/database.hpp"
#include "mocapdb/store/storage_extents.hpp"
#include "mocapdb/store/validate.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

std::string first_violation(const ValidationReport& r) {
    return r.violations.empty() ? std::string("(none)") : r.violations.front().path + ": " + r.violations.front().message;
}

}  // namespace

TEST_CASE("bad files: a newer format version is refused, saying so", "[store][bad]") {
    const auto file = test_data_dir() / "bad-newer-version.h5";
    CHECK_THROWS_AS(Database(file), StoreError);
    CHECK_THROWS_WITH(Database(file), Catch::Contains("bad-newer-version.h5: /: format_version is 5, newer than the "
                                                      "version 4 this mocapdb reads"));
    const ValidationReport r = validate_database(file);
    REQUIRE(r.violations.size() == 1);
    CHECK(r.violations[0].path == "/");
    CHECK(r.violations[0].message.find("newer than the version 4") != std::string::npos);
    // A writer on a copy: its lock file (DB.h5.lock) must not land in the source tree.
    TempDir dir("newer");
    std::filesystem::copy_file(file, dir / "newer.h5");
    CHECK_THROWS_AS(DatabaseWriter(dir / "newer.h5"), StoreError);
}

TEST_CASE("bad files: a foreign HDF5 file is refused", "[store][bad]") {
    const auto file = test_data_dir() / "bad-foreign.h5";
    CHECK(is_hdf5_file(file));
    CHECK_THROWS_WITH(Database(file),
                      Catch::Contains("bad-foreign.h5: /: not a mocapdb database: root attribute 'format' is missing "
                                      "(expected \"mocapdb\")"));
    CHECK_FALSE(validate_database(file).ok());
}

TEST_CASE("bad files: wrong dtype and wrong shape name the dataset and the expectation", "[store][bad]") {
    const auto dtype = test_data_dir() / "bad-dtype.h5";
    const Database db(dtype);  // the root is fine
    CHECK_THROWS_WITH(db.load_clip("tiny_walk"), Catch::Contains("bad-dtype.h5: /clips/tiny_walk/channels: expected "
                                                                 "float64 (frame, channel), found float32 (4, 9)"));
    const ValidationReport rd = validate_database(dtype);
    INFO(all_violations(rd));
    CHECK(has_violation(rd, "/clips/tiny_walk/channels", "expected float64 (F, C) dims (frame, channel), found float32 (4, 9)"));

    const auto shape = test_data_dir() / "bad-shape.h5";
    CHECK_THROWS_WITH(Database(shape).load_clip("tiny_walk"),
                      Catch::Contains("/clips/tiny_walk/channels: expected 9 columns (the channels of its skeleton), "
                                      "found shape (4, 8)"));
    const ValidationReport rs = validate_database(shape);
    INFO(all_violations(rs));
    CHECK(has_violation(rs, "/clips/tiny_walk/channels", "expected 9 columns"));
}

TEST_CASE("bad files: validate checks dims names and unknown attributes", "[store][bad]") {
    const ValidationReport r = validate_database(test_data_dir() / "bad-dims.h5");
    INFO(all_violations(r));
    CHECK(has_violation(r, "/sets/tiny_set/aligned/tensor",
                        "attribute 'dims': expected [\"sample\", \"time\", \"dof\"], found [\"dof\", \"time\", \"sample\"]"));
    CHECK(has_violation(r, "/clips/tiny_walk", "unexpected attribute 'colour'"));
    CHECK_FALSE(has_violation(r, "/clips/tiny_walk", "x_note"));
}

TEST_CASE("bad files: a truncated file is refused with the file named", "[store][bad]") {
    TempDir dir("truncated");
    const auto file = dir / "cut.h5";
    std::filesystem::copy_file(test_data_dir() / "reference-v2.h5", file);
    std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
    try {
        Database db(file);
        db.load_clip("tiny_walk");
        FAIL("a truncated file was accepted");
    } catch (const StoreError& e) {
        INFO(e.what());
        CHECK(std::string(e.what()).find("cut.h5") != std::string::npos);
        CHECK(std::string(e.what()).find("truncated") != std::string::npos);
    }
    CHECK_FALSE(validate_database(file).ok());
    CHECK_THROWS_AS(DatabaseWriter(file), StoreError);
}

TEST_CASE("bad files: flipped bytes in a clip's chunk give a checksum error naming the dataset", "[store][bad]") {
    TempDir dir("corrupt");
    const auto file = dir / "db.h5";
    {
        DatabaseWriter w(file);
        w.add_clip(synthetic_clip(2000, 6, 3), synthetic_source("16_15.bvh", "corrupt me"));
        w.add_clip(synthetic_clip(100, 6, 4), synthetic_source("intact.bvh", "keep me"));
        w.commit();
    }
    // Packed channels (format 3): flip bytes inside a chunk of zstd bytes.
    const std::string path = "/clips/16_15/channels_packed";
    const auto extents = dataset_extents(file, path);
    REQUIRE(!extents.empty());
    // The first chunk is full of zstd bytes (an edge chunk ends in zero padding, where Fletcher-32
    // cannot tell 0x0000 from 0xFFFF).
    const ByteExtent chunk = extents.front();
    REQUIRE(chunk.size > 16);
    flip_bytes(chunk.file, chunk.offset + chunk.size / 2, 4);

    const Database db(file);
    CHECK_NOTHROW(db.load_clip("intact"));
    CHECK_THROWS_AS(db.load_clip("16_15"), ChecksumError);
    CHECK_THROWS_WITH(db.load_clip("16_15"), Catch::Contains("db.h5: /clips/16_15/channels_packed: checksum mismatch in "
                                                             "dataset /clips/16_15/channels_packed"));
    const ValidationReport r = validate_database(file);
    INFO(first_violation(r));
    CHECK(has_violation(r, path, "checksum mismatch in dataset /clips/16_15/channels_packed"));

    const CommandResult cli = run_cli("validate " + quoted(file.string()));
    INFO(cli.output);
    CHECK(cli.exit_code == 1);
    CHECK(cli.output.find("/clips/16_15/channels_packed: ") != std::string::npos);
    CHECK(cli.output.find("checksum mismatch in dataset /clips/16_15/channels_packed") != std::string::npos);
    CHECK(cli.output.find("mocapdb: error: ") != std::string::npos);
}

TEST_CASE("bad files: a clip with both float64 and packed channels is refused, naming the clip", "[store][bad]") {
    TempDir dir("both-channels");
    const auto file = dir / "both.h5";
    std::filesystem::copy_file(test_data_dir() / "reference-v3.h5", file);
    const CommandResult copy = run_command("h5copy -i " + quoted((test_data_dir() / "reference-v2.h5").string()) +
                                           " -o " + quoted(file.string()) +
                                           " -s /clips/tiny_walk/channels -d /clips/tiny_walk/channels");
    if (copy.exit_code != 0) {
        WARN("h5copy is not available: " << copy.output);
        return;
    }
    const Database db(file);
    CHECK_THROWS_WITH(db.load_clip("tiny_walk"),
                      Catch::Contains("both.h5: /clips/tiny_walk: expected one of the datasets 'channels_packed' and "
                                      "'channels', found both"));
    const ValidationReport r = validate_database(file);
    INFO(all_violations(r));
    CHECK(has_violation(r, "/clips", "found both"));
}
