// Parameter grids, the files they are written to, and the CLI round trip
// generate → import → set create --params → align.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "mini_json.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/procedural/parametric_set.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::procedural;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

TEST_CASE("grid axes parse and enumerate", "[procedural]") {
    const GridAxis a = parse_grid_axis("speed=0.8:1.6:5");
    CHECK(a.name == "speed");
    CHECK(a.count == 5);
    CHECK(a.value(0) == 0.8);
    CHECK(a.value(4) == Approx(1.6));
    CHECK(a.value(2) == Approx(1.2));
    const GridAxis b = parse_grid_axis("turn=-30");
    CHECK(b.count == 1);
    CHECK(b.value(0) == -30.0);
    CHECK_THROWS_AS(parse_grid_axis("speed"), InvalidArgument);
    CHECK_THROWS_AS(parse_grid_axis("speed=1:2"), InvalidArgument);
    CHECK_THROWS_AS(parse_grid_axis("speed=1:2:0"), InvalidArgument);
    CHECK_THROWS_AS(parse_grid_axis("speed=a:2:3"), InvalidArgument);
    CHECK_THROWS_AS(parse_grid_axis("speed=1:2:2.5"), InvalidArgument);
    WalkGrid w;
    CHECK_THROWS_WITH(apply_grid_specs(w, {"height=1:2:3"}), Contains("speed (m/s), turn (deg), stride (m)"));
}

TEST_CASE("walk and reach sets: one clip per grid point, parameters of the varying axes", "[procedural]") {
    WalkGrid w;
    apply_grid_specs(w, {"speed=1.0:1.4:2", "turn=-30:30:3"});
    w.options.cycles = 2;
    const ParametricSet walks = generate_walk_set(w);
    REQUIRE(walks.clips.size() == 6);
    CHECK(walks.parameter_names == std::vector<std::string>{"speed", "turn"});
    CHECK(walks.parameter_units == std::vector<std::string>{"cm/s", "rad"});
    CHECK(walks.clips[0].name == "walk_s100_t-030");
    CHECK(walks.clips[5].name == "walk_s140_t+030");
    CHECK(walks.parameters(5, 0) == Approx(140.0));
    CHECK(walks.parameters(5, 1) == Approx(kPi / 6.0));

    ReachGrid r;
    apply_grid_specs(r, {"angle=-60:60:3", "height=80:140:2"});
    const ParametricSet reaches = generate_reach_set(r);
    REQUIRE(reaches.clips.size() == 6);
    CHECK(reaches.parameter_names == std::vector<std::string>{"angle", "height"});  // distance is constant
    CHECK(reaches.clips[1].name == "reach_a-060_h140_d55");
    CHECK(reaches.parameters(1, 1) == 140.0);
    // Out-of-reach grid points are refused with the point named.
    apply_grid_specs(r, {"height=199", "distance=95"});
    CHECK_THROWS_WITH(generate_reach_set(r), Contains("height 199"));
}

TEST_CASE("write_parametric_set: BVH files that read back, params.csv, no silent overwrite", "[procedural]") {
    TempDir dir("procedural-set");
    WalkGrid w;
    apply_grid_specs(w, {"speed=1.2", "turn=-20:20:2"});
    w.options.cycles = 1;
    const ParametricSet set = generate_walk_set(w);
    const auto paths = write_parametric_set(dir.path() / "walks", set);
    REQUIRE(paths.size() == 3);
    for (std::size_t i = 0; i < 2; ++i) {
        const Clip back = read_bvh(paths[i]);
        CHECK(paths[i].stem() == set.clips[i].name);
        CHECK(back.skeleton->same_structure(*set.clips[i].skeleton));
        CHECK((back.channels - set.clips[i].channels).cwiseAbs().maxCoeff() < 1e-5);
    }
    const std::string csv = read_text_file(paths[2]);
    CHECK(csv.rfind("sample,turn[rad]\n", 0) == 0);  // speed is constant: only turn varies
    CHECK_THAT(csv, Contains("walk_s120_t-020,-0.3490658503988659"));
    CHECK_THROWS_AS(write_parametric_set(dir.path() / "walks", set), IoError);
    CHECK_NOTHROW(write_parametric_set(dir.path() / "walks", set, true));
}

TEST_CASE("CLI: generate, import, set create with params.csv and with extractors, align", "[procedural][cli]") {
    if (cli_path().empty()) {
        WARN("SKIPPED: the mocapdb CLI is not built");
        return;
    }
    TempDir dir("procedural-cli");
    const std::string out = quoted((dir / "walks").string());
    CommandResult r = run_cli("generate walk --out " + out + " --grid speed=1.0:1.6:2 turn=-40:40:3 --cycles 2");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("walk_s160_t+040"));
    r = run_cli("generate walk --out " + out + " --grid speed=1.0:1.6:2 turn=-40:40:3 --cycles 2");
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.err, Contains("exists; pass --force"));

    const std::string db = quoted((dir / "gen.h5").string());
    r = run_cli("import " + out + " -o " + db);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("set create " + db + " --name walks --clips 'walk_*' --params " + quoted((dir / "walks" / "params.csv").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("6 samples"));
    // Whole clips, as the CSV describes them (by default the walks would be cut into gait cycles).
    r = run_cli("set create " + db + " --name measured --clips 'walk_*' --segment none --extract speed turn");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    // The CSV's values are the extractors' measurements.
    const Json given = parse_json(run_cli("set show " + db + " walks --json").out);
    const Json measured = parse_json(run_cli("set show " + db + " measured --json").out);
    REQUIRE(given["samples"].items.size() == 6);
    REQUIRE(measured["samples"].items.size() == 6);
    for (std::size_t i = 0; i < 6; ++i) {
        CHECK(given["samples"][i]["label"].text == measured["samples"][i]["label"].text);
        CHECK(given["samples"][i]["values"][0].number == Approx(measured["samples"][i]["values"][0].number).margin(1e-4));
        CHECK(given["samples"][i]["values"][1].number == Approx(measured["samples"][i]["values"][1].number).margin(1e-6));
    }
    r = run_cli("align " + db + " --set walks --frames 60 --method dtw");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("generate reach --out " + quoted((dir / "reach").string()) + " --grid angle=0:60:2 height=100 --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    CHECK(j["kind"].text == "reach");
    CHECK(j["clips"].items.size() == 2);
}
