// `mocapdb eval DB --set NAME` and the twins of `set create` (issue #38 item 5) end to end: a clip
// imported twice and overlapping windows are reported at set create (stderr, --json); eval --set runs on
// gait cycles of subject 16's walks and on the demo database, with every key present and numbers finite.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "mini_json.hpp"
#include "mocapdb/io/text_file.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

// Every number finite; null only under the keys that may be n/a.
void check_numbers(const Json& j, const std::string& where, const std::string& key = "") {
    INFO(where);
    if (j.kind == Json::Null) {
        CHECK((key == "rho_pose_pearson" || key == "hit_rate" || key == "hit_tolerance"));
        return;
    }
    if (j.kind == Json::Number) CHECK(std::isfinite(j.number));
    for (std::size_t i = 0; i < j.items.size(); ++i) check_numbers(j.items[i], where + "[" + std::to_string(i) + "]");
    for (const auto& [k, v] : j.members) check_numbers(v, where + "." + k, k);
}

// The keys of an eval --set document, and what must hold whatever the data.
void check_evaluation(const Json& e, const std::string& set, const std::vector<std::string>& methods) {
    check_numbers(e, "eval");
    CHECK(e["set"].text == set);
    for (const char* k : {"file", "samples", "frames", "folds", "fold_labels", "inner_folds", "parameters_measured",
                          "hit_share", "parameters", "twins", "methods", "chosen", "not_evaluated"})
        CHECK(e.has(k));
    const auto folds = static_cast<std::size_t>(e["folds"].number);
    CHECK(e["fold_labels"].items.size() == folds);
    REQUIRE(e["methods"].items.size() == methods.size());
    for (std::size_t q = 0; q < methods.size(); ++q) {
        const Json& m = e["methods"][q];
        INFO(methods[q]);
        CHECK(m["name"].text == methods[q]);
        CHECK(m["pose_mean_cm"].number > 0.0);
        CHECK(m["pose_max_cm"].number >= m["pose_mean_cm"].number);
        CHECK(m["motion_mean_cm"].number > 0.0);
        CHECK(m["sample_pose_mean_cm"].items.size() == folds);
    }
    const Json& c = e["chosen"];
    double picked = 0.0;
    for (const auto& [name, count] : c["picks"].members) picked += count.number;
    CHECK(picked == static_cast<double>(folds));
    CHECK(c["fold_picks"].items.size() == folds);
    CHECK(c["sample_pose_mean_cm"].items.size() == folds);
    CHECK(c["pose_mean_cm"].number > 0.0);
    CHECK(c.has("best_single"));
    CHECK(c.has("diff_se_cm"));
    CHECK_THAT(e["not_evaluated"][0].text, Contains("MOHGP"));
}

}  // namespace

TEST_CASE("set create reports twins, eval --set on subject 16's gait cycles", "[cli][eval][twins][shared]") {
    const auto cmu = datasets_dir() / "cmu-asfamc";
    MOCAPDB_REQUIRE_SHARED(cmu);
    TempDir dir("eval-set-cli");
    std::filesystem::copy_file(cmu / "16.asf", dir / "16.asf");
    std::string files;
    for (int t = 11; t <= 15; ++t) {
        const std::string amc = "16_" + std::to_string(t) + ".amc";
        std::filesystem::copy_file(cmu / amc, dir / amc);
        files += " " + quoted((dir / amc).string());
    }
    // The same frames in a second file (a byte-identical copy is skipped by import: same sha256).
    std::ofstream(dir / "16_95.amc") << "# 16_15 exported again\n" << mocapdb::read_text_file(cmu / "16_15.amc");
    files += " " + quoted((dir / "16_95.amc").string());
    const std::string db = quoted((dir / "walks.h5").string());
    CommandResult r = run_cli("import" + files + " -o " + db);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);

    r = run_cli("set create " + db + " --name whole --clips '16_*' --segment none --extract speed turn --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, Contains("warning: set 'whole': samples 16_15:0-") && Contains(", 16_95:0-") &&
                          Contains("show the same frames"));
    Json j = parse_json(r.out);
    REQUIRE(j["twins"].items.size() == 1);
    CHECK(j["twins"][0]["samples"].items.size() == 2);
    CHECK_THAT(j["twins"][0]["labels"][1].text, Contains("16_95"));

    // Windows of one clip overlapping by half: one group of twins.
    r = run_cli("set create " + db + " --name windows --clips 16_11 --segment window:60:30 --extract speed --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, Contains("overlap (the same frames of one clip)"));
    j = parse_json(r.out);
    REQUIRE(j["twins"].items.size() == 1);
    CHECK(static_cast<double>(j["twins"][0]["samples"].items.size()) == j["samples"].number);

    // Without twins, no warning.
    r = run_cli("set create " + db + " --name plain --clips 16_11 16_12 16_13 --segment none --extract speed");
    CHECK(r.exit_code == 0);
    CHECK(r.err.find("warning") == std::string::npos);

    r = run_cli("set create " + db + " --name cycles --clips '16_*' --extract speed turn");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, Contains("show the same frames"));
    r = run_cli("align " + db + " --set cycles --frames 30");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const std::string svg = (dir / "loo.svg").string();
    r = run_cli("eval " + db + " --set cycles --json --max-folds 8 --inner-folds 5 --svg " + quoted(svg));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json e = parse_json(r.out);
    check_evaluation(e, "cycles", {"kriging", "rbf", "trend"});
    CHECK(e["folds"].number == 8);
    CHECK(e["parameters_measured"].boolean);
    CHECK(e["twins"].items.size() >= 1);  // the cycles of 16_15 and 16_95
    for (const Json& m : e["methods"].items) {
        CHECK(m["hit_rate"].number >= 0.0);
        CHECK(m["hit_rate"].number <= 1.0);
    }
    CHECK(e["parameters"][0]["hit_tolerance"].number > 0.0);
    CHECK_THAT(mocapdb::read_text_file(svg), Contains("<svg") && Contains("chosen"));

    r = run_cli("eval " + db + " --set cycles --max-folds 4 --inner-folds 3");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("chosen - best single") && Contains("\nkriging ") && Contains("\nchosen ") &&
                          Contains("MOHGP: not evaluated") && Contains("twins: "));

    // The two forms do not mix; a set that is not there is named.
    r = run_cli("eval " + db);
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.err, Contains("--set"));
    r = run_cli("eval " + db + " --set nosuch");
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.err, Contains("nosuch"));
    r = run_cli("eval " + db + " --set cycles --data " + quoted(dir.path().string()));
    CHECK(r.exit_code != 0);
}

TEST_CASE("eval --set on the demo database: CSV parameters and a stored model", "[cli][eval]") {
    TempDir dir("eval-set-demo");
    CommandResult r = run_cli("demo --quick --out " + quoted((dir / "demo").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("eval " + quoted((dir / "demo" / "demo.h5").string()) +
                " --set reaches --json --max-folds 6 --inner-folds 4");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json e = parse_json(r.out);
    check_evaluation(e, "reaches", {"kriging", "rbf", "trend", "tucker"});
    CHECK_FALSE(e["parameters_measured"].boolean);
    CHECK(e["methods"][0]["hit_rate"].kind == Json::Null);  // CSV parameters: not measured back
    CHECK(e["methods"][3]["ranks"].items.size() == 3);
}
