// Issue #36 item 2: a failure inside a worker thread is the caller's error, as on one thread: the CLI
// exits 1 with one line, the library throws, and the database folder is left exactly as it was (no
// temporary file, lock or half-written segment). The failure is a natural one: a bound below what
// the float32 skeleton can reach (PackingFailed: even the source rows miss it), hit by every clip,
// so on 2 threads the second worker fails too (before issue #36: std::terminate, rc 134, and
// DB.h5.tmp-mocapdb-* left behind).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

std::size_t line_count(const std::string& text) {
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) +
           (!text.empty() && text.back() != '\n' ? 1 : 0);
}

}  // namespace

TEST_CASE("a clip that cannot pack on a worker thread: rc 1, one line, the database folder as before",
          "[store][packed][threads][shared][cli]") {
    const auto folder = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(folder);
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("worker_failure");
    const std::string db = (dir / "db.h5").string();
    std::string files;
    for (const char* stem : {"16_39_60fps", "09_01_60fps", "16_35_60fps", "35_17_60fps", "02_03_60fps", "16_37_60fps"})
        files += " " + quoted((folder / (std::string(stem) + ".bvh")).string());
    const CommandResult imported = run_cli("import" + files + " --fps 60 -o " + quoted(db));
    INFO(imported.output);
    REQUIRE(imported.exit_code == 0);

    // Once without a packed tier, once replacing one: either way the file and its folder stay as they were.
    for (const bool replacing : {false, true}) {
        if (replacing) {
            const CommandResult packed = run_cli("pack " + quoted(db) + " --max-error-cm 1");
            INFO(packed.output);
            REQUIRE(packed.exit_code == 0);
        }
        const std::string before = folder_listing(dir.path());
        INFO("before:\n" << before);
        std::string first_message;
        for (const int threads : {1, 2}) {
            INFO(threads << " threads" << (replacing ? ", replacing a tier" : ""));
            const CommandResult failed = run_cli("pack " + quoted(db) + " --max-error-cm 1e-9 --force --threads " +
                                                 std::to_string(threads));
            INFO(failed.output);
            CHECK(failed.exit_code == 1);
            CHECK(line_count(failed.err) == 1);
            CHECK(failed.err.find("mocapdb: error: pack: clip '") == 0);
            CHECK(failed.err.find("' window 0 frame ") != std::string::npos);
            CHECK(failed.err.find(": even its source rows are ") != std::string::npos);
            CHECK(failed.err.find("over 1e-09 cm") != std::string::npos);
            // The same line whatever the thread count (the failure of the first clip that failed).
            if (first_message.empty()) first_message = failed.err;
            CHECK(failed.err == first_message);
            CHECK(folder_listing(dir.path()) == before);
        }
        const Database view(db);
        CHECK(view.packed().has_value() == replacing);
        if (replacing) CHECK(view.packed()->max_error_cm == 1.0);
    }

    // The library call (what Python's mocapdb.pack runs): PackingFailed, nothing left behind.
    const std::string before = folder_listing(dir.path());
    workflow::PackDatabaseOptions options;
    options.max_error_cm = 1e-9;
    options.threads = 2;
    options.replace = true;
    CHECK_THROWS_AS(workflow::pack_database(db, options), packing::PackingFailed);
    CHECK(folder_listing(dir.path()) == before);
}
