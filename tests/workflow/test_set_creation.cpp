// The set-creation step in-process (workflow/set_creation.hpp, issue #17): the same set as the CLI's
// `set create`, without spawning it; its errors; nothing stored when it fails.
#include <catch2/catch.hpp>

#include <fstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/import_files.hpp"
#include "mocapdb/workflow/set_creation.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

TEST_CASE("workflow: create_set builds and stores a set of subject 16's walks", "[workflow][shared]") {
    const auto amc = datasets_dir() / "cmu-asfamc";
    MOCAPDB_REQUIRE_SHARED(amc);
    TempDir dir("workflow_set");
    const auto db_path = dir / "walks.h5";
    {
        DatabaseWriter w(db_path, DatabaseWriter::Mode::OpenOrCreate);
        std::vector<std::filesystem::path> files;
        for (int t = 11; t <= 20; ++t) files.push_back(amc / ("16_" + std::to_string(t) + ".amc"));
        files.push_back(amc / "16_33.amc");  // a walk that stops: no gait cycle
        workflow::import_files(w, files, workflow::ImportOptions{});
        w.commit();
    }

    workflow::SetRequest r;
    r.name = "walks";
    r.clips = {"16_1*", "16_20", "16_33"};
    r.extract = {"turn", "speed", "bearing"};
    int calls = 0;
    r.progress = [&](const Progress&) { ++calls; };
    const workflow::SetOutcome o = workflow::create_set(db_path, r);
    CHECK(o.clips == 11);
    CHECK(o.segmentation == Segmentation::GaitCycles);  // auto: most clips have a gait cycle
    CHECK(o.auto_segmentation);
    CHECK(o.skipped == std::vector<std::string>{"16_33"});
    CHECK(calls >= 11);
    CHECK(o.set.parameter_names == std::vector<std::string>{"turn", "speed", "bearing"});
    REQUIRE(o.set.parameter_periods.size() == 3);
    CHECK(o.set.parameter_periods(2) == Approx(2.0 * kPi));
    const MotionSet stored = Database(db_path).load_set("walks");
    CHECK(stored.samples.size() == o.set.samples.size());
    CHECK(stored.parameters == o.set.parameters);

    // A CSV's parameters and a periodic column.
    const auto csv = dir / "heading.csv";
    std::ofstream(csv) << "sample,heading[deg]\n16_11,350\n16_12,10\n16_13,20\n";
    workflow::SetRequest c;
    c.name = "around";
    c.clips = {"16_11", "16_12", "16_13"};
    c.segment = "none";
    c.params_csv = csv;
    c.periodic = {{"heading", 360.0}};
    const workflow::SetOutcome around = workflow::create_set(db_path, c);
    CHECK(around.set.parameter_units == std::vector<std::string>{"deg"});
    CHECK(around.set.parameter_periods(0) == 360.0);

    // Errors, and nothing stored by a failed step.
    const auto size = database_disk_bytes(db_path);
    CHECK_THROWS_WITH(workflow::create_set(db_path, r), Contains("set 'walks' exists"));
    workflow::SetRequest bad = c;
    bad.name = "bad";
    bad.periodic = {{"bearing", 360.0}};
    CHECK_THROWS_WITH(workflow::create_set(db_path, bad), Contains("no parameter 'bearing'"));
    bad.periodic.clear();
    bad.clips = {"zz*"};
    CHECK_THROWS_WITH(workflow::create_set(db_path, bad), Contains("no clip matches 'zz*'") && Contains("walks.h5"));
    CHECK(database_disk_bytes(db_path) == size);
    CHECK_FALSE(Database(db_path).has_set("bad"));
}
