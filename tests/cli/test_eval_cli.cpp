// mocapdb eval (issue #7) smoke test: a reduced run on subject 16's walks writes REPORT.md with every
// section, a results.json that parses and holds only finite numbers, and the CSV and SVG files the
// report links to. Release builds run --quick (the CI smoke run); sanitized builds the hidden --tiny
// sizing (same code paths, fewer clips, folds and grid points).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "mini_json.hpp"
#include "mocapdb/io/text_file.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

// Counts numbers; fails on null (the writer turns NaN/inf into null) or a non-finite number.
void check_finite(const Json& j, const std::string& where, long& numbers) {
    INFO(where);
    REQUIRE(j.kind != Json::Null);
    if (j.kind == Json::Number) {
        REQUIRE(std::isfinite(j.number));
        ++numbers;
    }
    for (std::size_t i = 0; i < j.items.size(); ++i) check_finite(j.items[i], where + "[" + std::to_string(i) + "]", numbers);
    for (const auto& [k, v] : j.members) check_finite(v, where + "." + k, numbers);
}

}  // namespace

TEST_CASE("eval writes the report with every section and finite numbers", "[cli][eval][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("eval-cli");
    const std::filesystem::path out = dir / "eval";
#ifdef MOCAPDB_SANITIZED_BUILD
    const std::string mode = " --tiny";
#else
    const std::string mode = " --quick";
#endif
    const CommandResult r = run_cli("eval --data " + quoted(datasets_dir().string()) + " --out " + quoted(out.string()) + mode);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);

    const std::string report = read_text_file(out / "REPORT.md");
    for (const char* header : {"# mocapdb evaluation report", "## Data", "## 1. Leave-one-out whole-motion prediction",
                               "## 2. Constraint accuracy", "## 3. Reliability against error", "## 4. Sample reduction",
                               "## 5. Foot skating", "## 6. Compression", "## 7. Runtime", "## Where our kriging loses",
                               "## Caveats"})
        CHECK_THAT(report, Contains(std::string("\n") + header + "\n") || Contains(std::string(header) + "\n"));
    // The header states command, date, machine and build.
    CHECK_THAT(report, Contains("| command | `mocapdb eval --data"));
    CHECK(std::regex_search(report, std::regex(R"(\| date \| 20\d\d-\d\d-\d\d \d\d:\d\d:\d\d UTC \|)")));
    CHECK_THAT(report, Contains("| machine | "));
    CHECK_THAT(report, Contains(" cores, "));
    // Every method appears in the leave-one-out table.
    for (const char* m : {"per-pose kriging", "per-element kriging", "tucker-1cm", "tucker-3cm", "tucker-R3=N/3", "naive kriging", "rbf",
                          "nn-blend k=3"})
        CHECK_THAT(report, Contains(std::string("| ") + m));
    CHECK_THAT(report, Contains("In all: a baseline beats every kriging variant in "));
    CHECK(report.find("n/a") == std::string::npos);

    const Json j = parse_json(read_text_file(out / "results.json"));
    long numbers = 0;
    check_finite(j, "results", numbers);
    CHECK(numbers > 100);
    REQUIRE(j["sets"].items.size() >= 1);
    const Json& walks = j["sets"][0];
    CHECK(walks["name"].text == "walks16");
    const Json& loo = walks["loo"]["methods"];
    REQUIRE(loo.items.size() == 9);  // eight methods and the linear trend alone (issue #15)
    for (const Json& m : loo.items) {
        INFO(m["method"].text);
        // A prediction of a motion it has not seen is never exact, and never absurd for walks (cm).
        CHECK(m["mean_cm"].number > 0.0);
        CHECK(m["mean_cm"].number < 100.0);
        CHECK(m["max_cm"].number >= m["mean_cm"].number);
    }
    const Json& regions = walks["constraint"]["methods"][0]["regions"];
    REQUIRE(regions.items.size() == 4);  // rho >= 0.9, 0.8, 0.7 and the whole grid
    // Nested regions: a lower threshold never has fewer points.
    CHECK(regions[0]["points"].number <= regions[1]["points"].number);
    CHECK(regions[1]["points"].number <= regions[2]["points"].number);
    CHECK(regions[2]["points"].number <= regions[3]["points"].number);
    CHECK(walks["reduction"]["kept_at_tau"].number >= 2);
    CHECK(walks["reduction"]["kept_at_tau"].number <= walks["samples"].number);
    CHECK(j["runtime"]["rows"].items.size() >= 8);

    for (const char* f : {"loo_walks16.csv", "loo_frames_walks16.csv", "loo_walks16.svg", "loo_motion_walks16.svg", "constraint_walks16.csv",
                          "reliability_walks16.svg", "reduction_walks16.csv", "reduction_walks16.svg",
                          "compression_walks16.csv", "compression_walks16.svg", "runtime.csv", "runtime.svg", "runtime_build.svg"}) {
        INFO(f);
        CHECK(std::filesystem::file_size(out / f) > 100);
        CHECK_THAT(report, Contains(f));
    }
    CHECK_THAT(read_text_file(out / "loo_walks16.svg"), Contains("<svg"));
}

TEST_CASE("eval refuses a data folder without the CMU clips", "[cli][eval]") {
    TempDir dir("eval-cli-bad");
    const CommandResult r = run_cli("eval --data " + quoted(dir.path().string()) + " --out " + quoted((dir / "out").string()) + " --quick");
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.err, Contains("cmu-asfamc"));
}
