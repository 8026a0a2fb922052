// Motion sets and alignment through the CLI on subject 16's walks (issue acceptance 3 and 4 end to end).
#include <catch2/catch.hpp>
#include <fstream>

#include "shared_data.hpp"
#include "test_support.hpp"
#include "mini_json.hpp"
#include "mocapdb/store/database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {
std::string walk_files() {
    std::string files;
    for (int t = 11; t <= 34; ++t) files += " " + quoted((datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")).string());
    return files + " " + quoted((datasets_dir() / "cmu-asfamc" / "16_47.amc").string());
}
}  // namespace

TEST_CASE("set create/show/list and align on subject 16's walks", "[cli][set][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("sets");
    const std::string db = quoted((dir / "walks.h5").string());
    CommandResult r = run_cli("import" + walk_files() + " -o " + db);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);

    // By default locomotion is cut into gait cycles (16_33 stops after one step: it has none).
    r = run_cli("set create " + db + " --name cycles --clips '16_1[1-9]' '16_2?' '16_3[0-4]' 16_47 --extract turn speed");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.output, Contains("(gait cycles, chosen because most clips have a gait cycle"));
    CHECK_THAT(r.output, Contains("clip '16_33' yields no sample (auto) and is left out"));
    r = run_cli("set show " + db + " cycles --json");
    REQUIRE(r.exit_code == 0);
    CHECK(parse_json(r.out)["samples"].items.size() > 25);
    r = run_cli("set create " + db + " --name middle --clips '16_1[1-9]' '16_2?' '16_3[0-4]' 16_47 --segment gait:1 --extract turn speed");
    CHECK_THAT(r.output, Contains("24 samples (gait cycles) from 25 clips"));

    r = run_cli("set create " + db + " --name walks --clips '16_1[1-9]' '16_2?' '16_3[0-4]' 16_47 --segment none --extract turn speed");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.output, Contains("25 samples (whole clips) from 25 clips"));
    // Issue #15: the dropout clips are named at creation and listed by set show, never silently repaired.
    CHECK_THAT(r.out, Contains("repaired solver dropouts in 4 clips (21 joint runs of up to 7 frames): 16_15, 16_23, "
                               "16_28, 16_33"));
    r = run_cli("set show " + db + " walks");
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("16_15                lhumerus, lradius, lwrist 0-1; lhand, lfingers, lthumb 0-6\n"));
    CHECK_THAT(r.out, Contains("16_33                lhand, lfingers, lthumb 0-1\n"));

    r = run_cli("set show " + db + " walks --json");
    REQUIRE(r.exit_code == 0);
    const Json set = parse_json(r.out);
    REQUIRE(set["samples"].items.size() == 25);
    CHECK(set["parameters"][0]["name"].text == "turn");
    CHECK(set["parameters"][1]["unit"].text == "cm/s");
    CHECK(set["samples"][0]["label"].text == "16_11");
    CHECK(set["aligned"].boolean == false);
    CHECK(set["dropouts_checked"].boolean == true);
    REQUIRE(set["repairs"].items.size() == 21);
    CHECK(set["repairs"][0]["clip"].text == "16_15");
    CHECK(set["repairs"][0]["joint"].text == "lhumerus");
    CHECK(set["repairs"][0]["begin"].number == 0);
    CHECK(set["repairs"][0]["end"].number == 2);

    // A second set of the same name needs --force; a pattern that matches nothing is an error.
    r = run_cli("set create " + db + " --name walks --clips 16_11 --extract turn");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Contains("exists") && Contains("--force"));
    r = run_cli("set create " + db + " --name other --clips 'zz*' --extract turn");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Contains("no clip matches 'zz*'"));

    // Parameters from a CSV: every sample needs a row.
    const std::string csv = (dir / "params.csv").string();
    std::ofstream(csv) << "sample,target[cm]\n16_11,10\n16_12,20\n";
    r = run_cli("set create " + db + " --name two --clips 16_11 16_12 --params " + quoted(csv));
    INFO(r.output);
    CHECK(r.exit_code == 0);
    r = run_cli("set create " + db + " --name three --clips 16_11 16_12 16_13 --params " + quoted(csv));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Contains("params.csv") && Contains("no row for sample '16_13'"));
    // #15: periodic parameters: a CSV column marked with --periodic (bearing extracted is periodic by itself).
    std::ofstream(dir / "bearing.csv") << "sample,heading[deg]\n16_11,350\n16_12,10\n16_13,20\n";
    r = run_cli("set create " + db + " --name around --clips 16_11 16_12 16_13 --params " +
                quoted((dir / "bearing.csv").string()) + " --periodic heading=360");
    INFO(r.output);
    CHECK(r.exit_code == 0);
    r = run_cli("set show " + db + " around");
    CHECK_THAT(r.out, Contains("periodic: heading, period 360 deg"));
    r = run_cli("set show " + db + " around --json");
    CHECK(parse_json(r.out)["parameters"][0]["period"].number == 360.0);
    r = run_cli("set create " + db + " --name x --clips 16_11 16_12 --params " + quoted(csv) + " --periodic bearing=360");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("no parameter 'bearing' to make periodic (its parameters: target)"));
    r = run_cli("set create " + db + " --name x --clips 16_11 16_12 --params " + quoted(csv) + " --periodic target=");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("--periodic 'target=': expected NAME=PERIOD"));
    r = run_cli("set create " + db + " --name x --clips 16_11 16_12 --segment none --extract bearing");
    CHECK(r.exit_code == 0);
    r = run_cli("set show " + db + " x");
    CHECK_THAT(r.out, Contains("periodic: bearing, period 6.28319 rad"));

    // #16: a set of one sample, or of samples that all share one parameter vector, is refused at creation.
    r = run_cli("set create " + db + " --name one --clips 16_11 --segment none --extract turn speed");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("motion set 'one': 1 sample; a set needs at least 2"));
    std::ofstream(dir / "same.csv") << "sample,target[cm]\n16_11,10\n16_12,10\n16_13,10\n";
    r = run_cli("set create " + db + " --name same --clips 16_11 16_12 16_13 --params " + quoted((dir / "same.csv").string()));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("every sample has the same parameters"));

    // #16: a runaway --frames is refused before the file grows (it took 1 GB before).
    const auto size_before = database_disk_bytes(dir / "walks.h5");
    r = run_cli("align " + db + " --set walks --frames 100000");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("100000 aligned frames") && Contains("use at most"));
    CHECK(database_disk_bytes(dir / "walks.h5") == size_before);

    r = run_cli("align " + db + " --set walks --frames 80");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.output, Contains("90 dofs x 80 frames x 25 samples"));

    r = run_cli("set list " + db + " --json");
    REQUIRE(r.exit_code == 0);
    const Json list = parse_json(r.out);
    REQUIRE(list.items.size() == 6);  // around, cycles, middle, walks, two, x

    // The stored tensor and parameters read back through the library.
    const Database database(dir.path() / "walks.h5");
    const auto aligned = database.load_aligned("walks");
    REQUIRE(aligned);
    CHECK(aligned->frames() == 80);
    CHECK(aligned->samples() == 25);
    CHECK((aligned->inverse_warp_increments().array() > 0).all());
    CHECK(database.load_set("two").parameters(1, 0) == 20.0);
    CHECK(run_cli("validate " + db).exit_code == 0);
}
