// Issue #16, found 2: two writers at once lost one writer's work and both reported success. Now a
// second session waits for the first (or gives up with a clear message); nothing is lost.
#include <catch2/catch.hpp>

#include <fstream>

#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

TEST_CASE("two concurrent imports of disjoint folders store every clip", "[store][shared][cli]") {
    const auto source = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(source);
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("writers");
    std::filesystem::create_directories(dir / "a");
    std::filesystem::create_directories(dir / "b");
    std::size_t total = 0;
    for (const auto& e : std::filesystem::directory_iterator(source)) {
        if (e.path().extension() != ".bvh") continue;
        std::filesystem::copy_file(e.path(), dir / (total % 2 ? "b" : "a") / e.path().filename());
        ++total;
    }
    REQUIRE(total >= 30);
    const auto db = dir / "db.h5";
    // Two real processes started together, each importing its own half into the same new file.
    const std::string cli = quoted(cli_path());
    const std::string one = cli + " import " + quoted((dir / "a").string()) + " --fps 60 -o " + quoted(db.string());
    const std::string two = cli + " import " + quoted((dir / "b").string()) + " --fps 60 -o " + quoted(db.string());
    const CommandResult r = run_command("(" + one + " > " + quoted((dir / "a.log").string()) + " 2>&1; echo $? > " +
                                        quoted((dir / "a.rc").string()) + ") & " + two + " > " +
                                        quoted((dir / "b.log").string()) + " 2>&1; echo $? > " +
                                        quoted((dir / "b.rc").string()) + "; wait");
    auto read = [&](const char* name) {
        std::ifstream in(dir / name);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    INFO(read("a.log") << read("b.log"));
    CHECK(read("a.rc") == "0\n");
    CHECK(read("b.rc") == "0\n");
    const Database d(db);
    CHECK(d.clips().size() == total);
    // The lock file stays beside the database (removing it would race); no temporary files are left.
    CHECK(std::filesystem::exists(dir / "db.h5.lock"));
    for (const auto& e : std::filesystem::directory_iterator(dir.path()))
        CHECK(e.path().filename().string().find(".tmp-mocapdb-") == std::string::npos);
}

TEST_CASE("a second writer gives up after its wait with a clear message, readers go on", "[store]") {
    TempDir dir("writers2");
    const auto db = dir / "db.h5";
    {
        DatabaseWriter w(db, DatabaseWriter::Mode::Create);
        w.add_clip(synthetic_clip(20, 2, 1), synthetic_source("first.bvh", "1"));
        w.commit();
    }
    DatabaseWriter holder(db);  // a session in progress
    holder.add_clip(synthetic_clip(20, 2, 2), synthetic_source("second.bvh", "2"));
    CHECK_THROWS_WITH(DatabaseWriter(db, DatabaseWriter::Mode::OpenOrCreate, 0.2),
                      Contains("db.h5") && Contains("another mocapdb session is writing this database") &&
                          Contains("nothing was changed"));
    // Creating anew waits too: it would otherwise replace the other session's work.
    CHECK_THROWS_AS(DatabaseWriter(db, DatabaseWriter::Mode::Create, 0.0), StoreError);
    {
        const Database reader(db);  // the published file, readable meanwhile
        CHECK(reader.clips().size() == 1);
    }
    holder.commit();
    // Once the first session has committed, the next one starts from its result.
    DatabaseWriter next(db, DatabaseWriter::Mode::OpenOrCreate, 0.0);
    CHECK(next.view().clips().size() == 2);
}
