// Motion sets and alignment through the CLI on subject 16's walks (issue acceptance 3 and 4 end to end).
#include <catch2/catch.hpp>
#include <fstream>

#include "cli_support.hpp"
#include "kriging/mini_json.hpp"
#include "mocapdb/store/database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {
std::string walk_files() {
    std::string files;
    for (int t = 11; t <= 34; ++t) files += " " + shell_quote((datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")).string());
    return files + " " + shell_quote((datasets_dir() / "cmu-asfamc" / "16_47.amc").string());
}
}  // namespace

TEST_CASE("set create/show/list and align on subject 16's walks", "[cli][set][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    ScratchDir dir("sets");
    const std::string db = shell_quote(dir / "walks.h5");
    CliResult r = mocapdb_cli("import" + walk_files() + " -o " + db);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);

    r = mocapdb_cli("set create " + db + " --name walks --clips '16_1[1-9]' '16_2?' '16_3[0-4]' 16_47 --extract turn speed");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("25 samples"));

    r = mocapdb_cli("set show " + db + " walks --json");
    REQUIRE(r.exit_code == 0);
    const Json set = parse_json(r.out);
    REQUIRE(set["samples"].items.size() == 25);
    CHECK(set["parameters"][0]["name"].text == "turn");
    CHECK(set["parameters"][1]["unit"].text == "cm/s");
    CHECK(set["samples"][0]["label"].text == "16_11");
    CHECK(set["aligned"].boolean == false);

    // A second set of the same name needs --force; a pattern that matches nothing is an error.
    r = mocapdb_cli("set create " + db + " --name walks --clips 16_11 --extract turn");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("exists") && Contains("--force"));
    r = mocapdb_cli("set create " + db + " --name other --clips 'zz*' --extract turn");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("no clip matches 'zz*'"));

    // Parameters from a CSV: every sample needs a row.
    const std::string csv = dir / "params.csv";
    std::ofstream(csv) << "sample,target[cm]\n16_11,10\n16_12,20\n";
    r = mocapdb_cli("set create " + db + " --name two --clips 16_11 16_12 --params " + shell_quote(csv));
    INFO(r.out << r.err);
    CHECK(r.exit_code == 0);
    r = mocapdb_cli("set create " + db + " --name three --clips 16_11 16_12 16_13 --params " + shell_quote(csv));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("params.csv") && Contains("no row for sample '16_13'"));

    r = mocapdb_cli("align " + db + " --set walks --frames 80");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("90 dofs x 80 frames x 25 samples"));

    r = mocapdb_cli("set list " + db + " --json");
    REQUIRE(r.exit_code == 0);
    const Json list = parse_json(r.out);
    REQUIRE(list.items.size() == 2);

    // The stored tensor and parameters read back through the library.
    const Database database(dir.path() / "walks.h5");
    const auto aligned = database.load_aligned("walks");
    REQUIRE(aligned);
    CHECK(aligned->frames() == 80);
    CHECK(aligned->samples() == 25);
    CHECK((aligned->inverse_warp_increments().array() > 0).all());
    CHECK(database.load_set("two").parameters(1, 0) == 20.0);
    CHECK(mocapdb_cli("validate " + db).exit_code == 0);
}
