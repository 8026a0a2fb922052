// Issue #16, found 3 ("every write costs the whole file"): format 4 keeps a database as a small index
// of external links into segment files (schemas/format-v4.md §2.1, §10). A commit writes its own
// segment and a new index and never touches published segments; readers keep reading across
// commits; dead segments go once no reader is open; copies are independent. Real data: CMU subject
// 16's walks (AMC), imported with the CLI as a user would.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <map>
#include <optional>

#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

std::filesystem::path cmu() { return datasets_dir() / "cmu-asfamc"; }

struct SegmentFile {
    ino_t inode = 0;
    std::string sha;  // of the bytes
};

// The segment files of a database (name -> inode and content digest).
std::map<std::string, SegmentFile> segments_of(const std::filesystem::path& db) {
    std::map<std::string, SegmentFile> out;
    for (const auto& e : std::filesystem::directory_iterator(db.string() + ".d")) {
        if (e.path().extension() != ".h5") continue;
        struct stat st {};
        REQUIRE(::stat(e.path().c_str(), &st) == 0);
        out[e.path().filename().string()] = {st.st_ino, std::to_string(std::hash<std::string>{}(file_bytes(e.path())))};
    }
    return out;
}

void import_cli(const std::string& files, const std::filesystem::path& db) {
    const CommandResult r = run_cli("import " + files + " --asf " + quoted((cmu() / "16.asf").string()) + " -o " +
                                    quoted(db.string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
}

}  // namespace

TEST_CASE("segments: an append writes one new segment and leaves the published ones untouched", "[store][shared][segments]") {
    MOCAPDB_REQUIRE_SHARED(cmu());
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("segments-append");
    const auto db = dir / "walks.h5";
    import_cli(quoted((cmu() / "16_1").string()) + "*.amc", db);
    const auto before = segments_of(db);
    REQUIRE(before.size() == 1);
    const auto index_before = std::filesystem::file_size(db);

    import_cli(quoted((cmu() / "16_21.amc").string()), db);
    const auto after = segments_of(db);
    REQUIRE(after.size() == 2);
    for (const auto& [name, seg] : before) {
        INFO(name);
        REQUIRE(after.count(name) == 1);
        CHECK(after.at(name).inode == seg.inode);  // not rewritten, not replaced
        CHECK(after.at(name).sha == seg.sha);
    }
    // The new segment holds the one new clip; the index grew by one link.
    const Database view(db);
    CHECK(view.clips().size() == 11);
    std::uint64_t new_segment_bytes = 0;
    for (const auto& [name, seg] : after)
        if (before.count(name) == 0) new_segment_bytes = std::filesystem::file_size(db.string() + ".d/" + name);
    CHECK(new_segment_bytes < view.file_size() / 4);
    CHECK(std::filesystem::file_size(db) < index_before + 4096);
    CHECK(view.load_clip("16_21").frame_count() > 0);
    CHECK(validate_database(db).ok());
}

TEST_CASE("segments: a reader open across a commit keeps reading, dead segments go once it closes", "[store][shared][segments]") {
    MOCAPDB_REQUIRE_SHARED(cmu());
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("segments-reader");
    const auto db = dir / "walks.h5";
    import_cli(quoted((cmu() / "16_1").string()) + "*.amc", db);
    const CommandResult set = run_cli("set create " + quoted(db.string()) + " --name w --clips '16_1*' --segment none --extract speed");
    INFO(set.output);
    REQUIRE(set.exit_code == 0);
    const std::size_t segments_with_set = segments_of(db).size();
    REQUIRE(segments_with_set == 2);
    const MotionSet original = Database(db).load_set("w");

    std::optional<Database> reader;
    reader.emplace(db);  // opened before the replacing commit, reads nothing yet
    MotionSet replaced = original;
    replaced.parameters.array() += 1.0;
    {
        DatabaseWriter w(db);
        w.put_set(replaced, true);
        w.commit();
    }
    // The replaced set's segment is still there for the open reader, which sees its own snapshot.
    CHECK(segments_of(db).size() == 3);
    CHECK(reader->load_set("w").parameters == original.parameters);
    CHECK(Database(db).load_set("w").parameters == replaced.parameters);
    reader.reset();
    // The next commit without readers removes it.
    import_cli(quoted((cmu() / "16_21.amc").string()), db);
    CHECK(segments_of(db).size() == 3);  // the clips', the new set's, the new clip's
    CHECK(database_disk_bytes(db) == Database(db).file_size());
    CHECK(validate_database(db).ok());
}

TEST_CASE("segments: a copy is independent of its original", "[store][shared][segments]") {
    MOCAPDB_REQUIRE_SHARED(cmu());
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("segments-copy");
    const auto db = dir / "walks.h5";
    import_cli(quoted((cmu() / "16_1").string()) + "*.amc", db);
    std::filesystem::create_directories(dir / "elsewhere");
    const auto copy = dir / "elsewhere" / "copy.h5";
    copy_database(db, copy);
    CHECK_THROWS_AS(copy_database(db, copy), IoError);  // never over an existing path
    CHECK(validate_database(copy).ok());
    // Writing to the copy leaves the original as it was, and removing the original leaves the copy whole.
    const auto original_segments = segments_of(db);
    import_cli(quoted((cmu() / "16_21.amc").string()), copy);
    CHECK(segments_of(db).size() == original_segments.size());
    std::filesystem::remove_all(db.string() + ".d");
    std::filesystem::remove(db);
    const Database c(copy);
    CHECK(c.clips().size() == 11);
    for (const ClipRecord& r : c.clips()) CHECK_NOTHROW(c.load_clip(r.id));
    CHECK(validate_database(copy).ok());
}

TEST_CASE("segments: many small appends keep the folder to a few segments", "[store][segments]") {
    TempDir dir("segments-many");
    const auto db = dir / "db.h5";
    for (int k = 0; k < 40; ++k) {
        DatabaseWriter w(db);
        w.add_clip(synthetic_clip(30, 4, static_cast<unsigned>(k)), synthetic_source("c" + std::to_string(k) + ".bvh", std::to_string(k)));
        w.commit();
    }
    const auto segments = segments_of(db);
    INFO(segments.size() << " segments after 40 single-clip commits");
    CHECK(segments.size() <= 33);
    const Database view(db);
    CHECK(view.clips().size() == 40);
    for (const ClipRecord& r : view.clips()) CHECK(view.load_clip(r.id).frame_count() == 30);
    CHECK(database_disk_bytes(db) == view.file_size());
    CHECK(validate_database(db).ok());
}
