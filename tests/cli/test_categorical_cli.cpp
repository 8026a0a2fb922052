// Categorical parameters through the CLI (issue #38 item 3): `set create --category` beside
// `--extract`, `set show` listing the levels, `synth --param` in the named and positional forms with the
// JSON's parameters[] (requested, measured per parameter) and `measured` object (every applicable
// extractor), and the errors for an unknown level and a regex that misses a clip.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "mini_json.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/io/bvh.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

TEST_CASE("set create --category and synth --param name=level", "[cli][synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const TempDir dir("categorical-cli");
    const std::string db = quoted((dir.path() / "gaits.h5").string());
    std::string files;
    for (int t : {11, 12, 13, 14, 15, 16, 40, 41, 42, 45, 46})
        files += " " + quoted((datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")).string());
    const std::vector<std::string> steps{
        "import" + files + " -o " + db,
        "set create " + db +
            " --name gaits --clips '16_*' --segment gait:1 --extract turn --category 'gait=^16_([14])'",
        "align " + db + " --set gaits --frames 40",
        "compress " + db + " --set gaits --max-error-cm 1",
    };
    for (const std::string& s : steps) {
        const CommandResult c = run_cli(s);
        INFO("mocapdb " << s << "\n" << c.output);
        REQUIRE(c.exit_code == 0);
    }
    // The levels are stored as format-v4.md §6 specifies them.
    CommandResult r = run_cli("validate " + db);
    INFO(r.output);
    CHECK(r.exit_code == 0);
    r = run_cli("set show " + db + " gaits --json");
    REQUIRE(r.exit_code == 0);
    const Json show = parse_json(r.out);
    REQUIRE(show["parameters"].items.size() == 2);
    CHECK(show["parameters"][1]["name"].text == "gait");
    REQUIRE(show["parameters"][1]["levels"].items.size() == 2);
    CHECK(show["parameters"][1]["levels"][1].text == "4");
    r = run_cli("set show " + db + " gaits");
    CHECK_THAT(r.out, Contains("categorical: gait, levels 1, 4"));

    // Named, in any order: the JSON keeps the request per parameter and measures every extractor.
    const std::string out = (dir.path() / "run.bvh").string();
    r = run_cli("synth " + db + " --set gaits --param gait=4,turn=0.1 -o " + quoted(out) + " --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    const Json& params = j["parameters"];
    REQUIRE(params.items.size() == 2);
    CHECK(params[0]["name"].text == "turn");
    CHECK(params[0]["kind"].text == "numeric");
    CHECK(params[0]["requested"].number == 0.1);
    CHECK(params[1]["kind"].text == "categorical");
    CHECK(params[1]["requested"].text == "4");
    CHECK_THROWS(params[1]["measured"]);  // a category is not measured
    const Json& measured = j["measured"];
    for (const char* n : {"dx", "dz", "turn", "speed"}) CHECK(measured[n].kind == Json::Number);
    CHECK(params[0]["measured"].number == measured["turn"].number);
    CHECK(j["measured_units"]["speed"].text == "cm/s");
    // The measurements are those of the written motion.
    const Clip clip = read_bvh(out);
    const double speed = extract_parameters(clip, 0, clip.frame_count(), {ParameterExtractor::parse("speed")})(0);
    CHECK(measured["speed"].number == Approx(speed).epsilon(0.02));

    // The positional form, and the text output shows request and measurement side by side.
    r = run_cli("synth " + db + " --set gaits --param 0.1,1 -o " + quoted((dir.path() / "walk.bvh").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("requested") && Contains("measured:") && Contains("speed = "));
    const Json walk = parse_json(run_cli("synth " + db + " --set gaits --param turn=0.1,gait=1 -o " +
                                         quoted((dir.path() / "walk2.bvh").string()) + " --json")
                                     .out);
    INFO("speed: walk " << walk["measured"]["speed"].number << ", run " << measured["speed"].number);
    CHECK(measured["speed"].number > 1.3 * walk["measured"]["speed"].number);

    // Errors: an unknown level lists the known ones; query takes the same forms.
    r = run_cli("synth " + db + " --set gaits --param gait=skip,turn=0 -o " + quoted((dir.path() / "x.bvh").string()));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("--param") && Contains("no level 'skip'") && Contains("its levels: 1, 4"));
    r = run_cli("query " + db + " --set gaits --param turn=0,gait=1 --frame 3 --json");
    CHECK(r.exit_code == 0);
    r = run_cli("set create " + db + " --name bad --clips '16_*' --segment none --category 'gait=^16_(1)'");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("does not match clip '16_40'"));
}
