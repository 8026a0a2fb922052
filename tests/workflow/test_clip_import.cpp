// The import step in-process (workflow/clip_import.hpp, issue #17): clips stored and counted, the
// duplicates and the readers' warnings reported in the outcome (not printed), --force's new file,
// the errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/clip_import.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

TEST_CASE("workflow: import_clips stores new clips, reports duplicates, replaces the file with force",
          "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("workflow_import");
    const auto db = dir / "walks.h5";
    std::vector<std::filesystem::path> files = walk_files();
    files.resize(4);  // 16_11 .. 16_14

    std::uint64_t last_done = 0, total = 0;
    const workflow::ImportOutcome first =
        workflow::import_clips(db, files, workflow::ImportOptions{}, false, [&](const Progress& p) {
            last_done = p.done;
            total = p.total;
        });
    CHECK_FALSE(first.existed);
    CHECK(first.summary.files == 4);
    CHECK(first.summary.added == 4);
    CHECK(first.summary.skipped == 0);
    CHECK(first.summary.frames > 4 * 100);
    // A clip of F frames at 120 Hz lasts (F - 1) / 120 s.
    CHECK(first.summary.seconds == Approx(static_cast<double>(first.summary.frames - 4) / 120.0));
    CHECK(first.clips_in_db == 4);
    CHECK(first.file_bytes == database_disk_bytes(db));
    CHECK(first.messages.empty());
    CHECK(first.not_added.empty());
    CHECK(total > 0);
    CHECK(last_done == total);  // bytes of every file read
    {
        const Database stored(db);
        REQUIRE(stored.clips().size() == 4);
        CHECK(stored.has_clip("16_11"));
        CHECK(stored.has_clip("16_14"));
        CHECK(stored.load_clip("16_12").frame_rate == 120.0);
    }

    // Appending: the four are already stored (same sha256), one is new.
    std::vector<std::filesystem::path> more = files;
    more.push_back(datasets_dir() / "cmu-asfamc" / "16_15.amc");
    const workflow::ImportOutcome second = workflow::import_clips(db, more, workflow::ImportOptions{}, false);
    CHECK(second.existed);
    CHECK(second.summary.added == 1);
    CHECK(second.summary.skipped == 4);
    CHECK(second.clips_in_db == 5);
    REQUIRE(second.not_added.size() == 4);
    CHECK_THAT(second.not_added[0], Contains("16_11.amc: "));
    CHECK(Database(db).clips().size() == 5);

    // Nothing new: the file is left as it was (no commit).
    const auto bytes = database_disk_bytes(db);
    const workflow::ImportOutcome again = workflow::import_clips(db, files, workflow::ImportOptions{}, false);
    CHECK(again.summary.added == 0);
    CHECK(again.clips_in_db == 5);
    CHECK(database_disk_bytes(db) == bytes);

    // force: a new database with only the given clips.
    const workflow::ImportOutcome fresh = workflow::import_clips(db, {files[0]}, workflow::ImportOptions{}, true);
    CHECK(fresh.existed);
    CHECK(fresh.summary.added == 1);
    CHECK(fresh.clips_in_db == 1);
    CHECK(Database(db).clips().size() == 1);
}

TEST_CASE("workflow: import_clips puts the readers' warnings and the failed files in the outcome",
          "[workflow][shared]") {
    const auto pfnn = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(pfnn);
    TempDir dir("workflow_import_warn");
    const auto db = dir / "pfnn.h5";
    workflow::ImportOptions options;
    options.frame_rate = 60.0;
    const workflow::ImportOutcome o = workflow::import_clips(db, {pfnn / "16_13_60fps.bvh"}, options, false);
    CHECK(o.summary.added == 1);
    // The 60 Hz given against the header's 1/15 s, then the short file, in the file's order.
    REQUIRE(o.messages.size() >= 2);
    CHECK(o.messages[0].kind == workflow::ImportMessage::Kind::Warning);
    CHECK_THAT(o.messages[0].text, Contains("16_13_60fps.bvh") && Contains("60 Hz") && Contains("(15 Hz)"));
    CHECK(o.messages[1].kind == workflow::ImportMessage::Kind::Warning);
    CHECK_THAT(o.messages[1].text, Contains("16_13_60fps.bvh") && Contains("declares 223 frames but 222"));

    // keep_going: a file that cannot be read is an Error message, the others are stored.
    const auto bad = dir / "broken.bvh";
    std::ofstream(bad) << "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n";
    options.keep_going = true;
    const workflow::ImportOutcome k =
        workflow::import_clips(dir / "kept.h5", {bad, pfnn / "16_13_60fps.bvh"}, options, false);
    CHECK(k.summary.failed == 1);
    CHECK(k.summary.added == 1);
    CHECK(k.clips_in_db == 1);
    const auto error = std::find_if(k.messages.begin(), k.messages.end(), [](const workflow::ImportMessage& m) {
        return m.kind == workflow::ImportMessage::Kind::Error;
    });
    REQUIRE(error != k.messages.end());
    CHECK_THAT(error->text, Contains("broken.bvh"));

    // Without keep_going the broken file stops the import and nothing is stored.
    options.keep_going = false;
    CHECK_THROWS_AS(workflow::import_clips(dir / "stopped.h5", {bad}, options, false), ParseError);
    CHECK_FALSE(std::filesystem::exists(dir / "stopped.h5"));
}

TEST_CASE("workflow: import_clips refuses no clip files and a file that is not a database", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("workflow_import_refuse");
    std::filesystem::create_directories(dir / "empty");
    CHECK_THROWS_AS(workflow::import_clips(dir / "x.h5", {dir / "empty"}, workflow::ImportOptions{}, false), InvalidArgument);
    CHECK_THROWS_WITH(workflow::import_clips(dir / "x.h5", {dir / "empty"}, workflow::ImportOptions{}, false),
                      Contains("no .bvh or .amc files"));
    const auto clip = walk_files().front();
    const auto text = dir / "notes.h5";
    std::ofstream(text) << "not a database\n";
    CHECK_THROWS_WITH(workflow::import_clips(text, {clip}, workflow::ImportOptions{}, false),
                      Contains("notes.h5") && Contains("import appends to a mocapdb database") && !Contains("--"));
    try {
        workflow::import_clips(text, {clip}, workflow::ImportOptions{}, false);
        FAIL("a file that is not a database was appended to");
    } catch (const Remediable& e) {
        CHECK(e.remedy() == Remedy::ReplaceFile);  // the CLI adds --force, Python force=True
    }
    const workflow::ImportOutcome forced = workflow::import_clips(text, {clip}, workflow::ImportOptions{}, true);
    CHECK(forced.clips_in_db == 1);
}
