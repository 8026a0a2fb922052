// mocapdb gp: fit / interpolate / sample / experiment through the CLI, JSON parsed, errors checked.
#include <catch2/catch.hpp>

#include "mini_json.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using mocapdb::test::parse_json;
using mocapdb::test::quoted;
using mocapdb::test::run_cli;

namespace {

std::string walk_clips() {
    const auto dir = mocapdb::test::datasets_dir() / "cmu-asfamc";
    std::string s;
    for (const char* n : {"02_01", "02_02", "35_01"}) s += " " + quoted((dir / (std::string(n) + ".amc")).string());
    return s;
}

}  // namespace

TEST_CASE("gp fit, interpolate and sample on CMU walks", "[gp][cli][shared]") {
    MOCAPDB_REQUIRE_CLI();
    MOCAPDB_REQUIRE_SHARED(mocapdb::test::datasets_dir() / "cmu-asfamc" / "35_01.amc");
    const std::string common = " --clips" + walk_clips() + " --joints lfemur,ltibia --frames 20 --max-iterations 60";

    auto r = run_cli("gp fit" + common + " --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    auto j = parse_json(r.out);
    CHECK(j["model"].text == "mohgp");
    CHECK(j["children"].items.size() == 3);
    CHECK(j["frames"].number == 20);
    CHECK(j["dofs"].items.size() >= 4);
    CHECK(j["status"].text != "numerical_failure");
    CHECK(j["parameters"].has("parent.q0.log_lengthscale"));
    CHECK(j["noise_variance"].items.size() == j["dofs"].items.size());

    r = run_cli("gp fit" + common + " --mo-baseline --json");
    REQUIRE(r.exit_code == 0);
    CHECK(parse_json(r.out)["model"].text == "moa");
    CHECK_FALSE(parse_json(r.out)["parameters"].has("parent.q0.log_lengthscale"));

    mocapdb::test::TempDir tmp("gp_cli");
    r = run_cli("gp interpolate" + common + " --child 02_01 --observed 6 --json -o " + quoted((tmp / "i.bvh").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    j = parse_json(r.out);
    CHECK(j["child"].text == "02_01");
    CHECK(j["observed_frames"].items.size() == 6);
    CHECK(j["predicted_values"].number == 14.0 * static_cast<double>(j["dofs"].items.size()));
    CHECK(j["smse"].number > 0.0);
    CHECK(std::isfinite(j["msll"].number));
    CHECK(j["mean"].items.size() == j["dofs"].items.size());
    CHECK(std::filesystem::exists(tmp / "i.bvh"));
    CHECK(mocapdb::read_clip(tmp / "i.bvh").frame_count() == 20);
    // No overwrite without --force.
    r = run_cli("gp interpolate" + common + " --child 02_01 --observed 6 -o " + quoted((tmp / "i.bvh").string()));
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("exists") != std::string::npos);

    r = run_cli("gp sample" + common + " --n 2 -o " + quoted((tmp / "s").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    for (const char* f : {"sample_001.bvh", "sample_002.bvh", "trend.bvh"}) {
        REQUIRE(std::filesystem::exists(tmp / "s" / f));
        CHECK(mocapdb::read_clip(tmp / "s" / f).frame_count() == 20);
    }

    // Errors: one line on stderr, non-zero exit.
    r = run_cli("gp fit --frames 20");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("no children") != std::string::npos);
    r = run_cli("gp interpolate" + common + " --child 07_09");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("no child '07_09'") != std::string::npos);
}

TEST_CASE("gp experiment --artificial prints the thesis's table as JSON", "[gp][cli]") {
    MOCAPDB_REQUIRE_CLI();
    const auto r = run_cli("gp experiment --artificial --tests 1 --runs 1 --kernel rbf --max-iterations 40 --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const auto j = parse_json(r.out);
    REQUIRE(j["tests"].items.size() == 1);
    const auto& t = j["tests"][0];
    CHECK(t["noise"].number == 0.001);
    CHECK(t["outputs"].number == 3);
    CHECK(t["children"].number == 5);
    CHECK(t["mohgp"]["smse"]["mean"].number > 0.0);
    CHECK(t["moa"]["msll"].has("std"));
}

TEST_CASE("gp fit on a database set: the set's samples are the children", "[gp][cli][shared]") {
    MOCAPDB_REQUIRE_CLI();
    const auto dir = mocapdb::test::datasets_dir() / "cmu-asfamc";
    MOCAPDB_REQUIRE_SHARED(dir / "16_16.amc");
    mocapdb::test::TempDir tmp("gp_cli_db");
    const std::string db = quoted((tmp / "walks.h5").string());
    auto r = run_cli("import " + quoted((dir / "16_15.amc").string()) + " " + quoted((dir / "16_16.amc").string()) + " " +
                     quoted((dir / "16_21.amc").string()) + " -o " + db);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("set create " + db + " --name walks --clips 16_15 16_16 16_21");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("gp fit " + db + " --set walks --joints lfemur --frames 15 --max-iterations 30 --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const auto j = parse_json(r.out);
    REQUIRE(j["children"].items.size() == 3);
    CHECK(j["children"][0].text.rfind("16_15:", 0) == 0);
    CHECK(j["frames"].number == 15);
    r = run_cli("gp fit " + db + " --set nosuchset");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("nosuchset") != std::string::npos);
}

TEST_CASE("gp --layers 3: subjects from the CMU names form the middle layer", "[gp][cli][shared][layers]") {
    MOCAPDB_REQUIRE_CLI();
    const auto dir = mocapdb::test::datasets_dir() / "cmu-asfamc";
    MOCAPDB_REQUIRE_SHARED(dir / "16_16.amc");
    std::string clips;
    for (const char* n : {"02_01", "02_02", "16_15", "16_16", "35_01"}) clips += " " + quoted((dir / (std::string(n) + ".amc")).string());
    const std::string common = " --clips" + clips + " --joints lfemur,ltibia --frames 16 --max-iterations 40 --layers 3";

    auto r = run_cli("gp fit" + common + " --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    auto j = parse_json(r.out);
    CHECK(j["model"].text == "mohgp3");
    REQUIRE(j["groups"].items.size() == 5);
    const double expected_groups[] = {0, 0, 1, 1, 2};  // 02, 02, 16, 16, 35
    for (std::size_t i = 0; i < 5; ++i) CHECK(j["groups"][i].number == expected_groups[i]);
    CHECK(j["parameters"].has("group.q0.log_lengthscale"));
    CHECK(j["parameters"].has("parent.q0.log_lengthscale"));
    CHECK(j["status"].text != "numerical_failure");

    // Interpolating 16_16 leaves groups of sizes 2, 1, 1 for training (the coupled size classes).
    r = run_cli("gp interpolate" + common + " --child 16_16 --observed 5 --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    j = parse_json(r.out);
    CHECK(j["model"].text == "mohgp3");
    CHECK(j["smse"].number > 0.0);
    CHECK(std::isfinite(j["msll"].number));

    mocapdb::test::TempDir tmp("gp_cli3");
    r = run_cli("gp sample" + common + " --n 2 -o " + quoted((tmp / "s").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("groups (three layers): 0 = {02_01, 02_02} 1 = {16_15, 16_16} 2 = {35_01}") != std::string::npos);
    CHECK(mocapdb::read_clip(tmp / "s" / "sample_002.bvh").frame_count() == 16);
    r = run_cli("gp sample" + common + " --n 1 --subject 16 -o " + quoted((tmp / "s16").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(mocapdb::read_clip(tmp / "s16" / "sample_001.bvh").frame_count() == 16);
    r = run_cli("gp sample" + common + " --n 1 --subject 99 -o " + quoted((tmp / "s99").string()));
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("no child of that subject (subjects: 02, 16, 35)") != std::string::npos);

    r = run_cli("gp experiment" + common + " --child 16_16 --observed-list 5 --runs 1 --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    j = parse_json(r.out);
    CHECK(j["layers"].number == 3);
    CHECK(j["interpolation"][0]["mohgp"]["smse"]["mean"].number > 0.0);

    // Explicit groups override the names; wrong counts and --artificial are refused.
    r = run_cli("gp fit" + common + " --groups 0,1,0,1,0 --json");
    REQUIRE(r.exit_code == 0);
    CHECK(parse_json(r.out)["groups"][1].number == 1);
    r = run_cli("gp fit" + common + " --groups 0,1");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("--groups: 2 values for 5 children") != std::string::npos);
    r = run_cli("gp fit" + common + " --groups 0,2,0,2,0");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("group 1 has no child") != std::string::npos);
    r = run_cli("gp experiment --artificial --layers 3");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("two-layer") != std::string::npos);
    r = run_cli("gp fit" + common + " --layers 4");
    CHECK(r.exit_code != 0);
}
