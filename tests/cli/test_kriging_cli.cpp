// The `variogram` and `krige` subcommands, run as a user would (exit codes, --json, errors), on the
// Meuse table and checked against the gstat reference numbers.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "kriging/csv_fixture.hpp"
#include "mini_json.hpp"
#include "test_support.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "shared_data.hpp"

using mocapdb::test::cli_path;
using mocapdb::test::parse_json;
using mocapdb::test::read_csv;
using mocapdb::test::reference_dir;
using mocapdb::test::rel_err;
using mocapdb::test::run_cli;

namespace {

std::filesystem::path scratch_dir() {
    const auto d = std::filesystem::temp_directory_path() / ("mocapdb_kriging_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
}

}  // namespace

TEST_CASE("CLI variogram --json reproduces gstat's Meuse bins", "[kriging][cli]") {
    MOCAPDB_REQUIRE_CLI();
    const auto g = reference_dir() / "gstat";
    MOCAPDB_REQUIRE_SHARED(g);
    const auto ref = read_csv(g / "meuse_variogram_bins.csv");
    const mocapdb::test::CommandResult r = run_cli("variogram --data \"" + (g / "meuse_logzinc.csv").string() +
                                "\" --coords x,y --value logzinc --bins 10 --cutoff 1600 --estimator cressie --fit sph --json");
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = parse_json(r.out);
    REQUIRE(j["bins"].items.size() == 10);
    double worst = 0.0;
    for (std::size_t u = 0; u < 10; ++u) {
        const auto np = static_cast<std::size_t>(ref.number(u, "np"));
        CHECK(static_cast<std::size_t>(j["bins"][u]["np"].number) == np);
        const double e = rel_err(j["bins"][u]["gamma"].number,
                                 mocapdb::kriging::cressie_gstat_to_three_term(ref.number(u, "gamma_cressie_gstat"), np));
        worst = std::max(worst, e);
    }
    INFO("worst rel gamma error " << worst);
    CHECK(worst <= 1e-10);
    CHECK(j["fit"]["model"].text == "sph");
    CHECK(j["fit"]["range"].number > 0.0);
    CHECK(j["fit"]["converged"].boolean);
}

TEST_CASE("CLI krige --json reproduces gstat's universal kriging and LOO", "[kriging][cli]") {
    MOCAPDB_REQUIRE_CLI();
    const auto g = reference_dir() / "gstat";
    MOCAPDB_REQUIRE_SHARED(g);
    const auto ref = read_csv(g / "meuse_kriging_fixed_models.csv");
    const auto loo_ref = read_csv(g / "meuse_uk_loo_fixed_models.csv");
    const auto rows = ref.select("model", "stable_p15");
    const auto q = scratch_dir() / "query.csv";
    {
        std::ofstream out(q);
        out << "x,y\n";
        out.precision(17);
        for (auto r : rows) out << ref.number(r, "x") << "," << ref.number(r, "y") << "\n";
    }
    const mocapdb::test::CommandResult r = run_cli("krige --data \"" + (g / "meuse_logzinc.csv").string() + "\" --coords x,y --value logzinc --query \"" +
                                q.string() + "\" --model stable:1.5 --nugget 0.05 --sill 0.55 --range 500 --trend linear --loo --json");
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = parse_json(r.out);
    REQUIRE(j["predictions"].items.size() == rows.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        worst = std::max(worst, rel_err(j["predictions"][k]["prediction"].number, ref.number(rows[k], "uk_pred")));
        worst = std::max(worst, rel_err(j["predictions"][k]["variance"].number, ref.number(rows[k], "uk_var")));
        CHECK(j["predictions"][k]["reliability"].number >= 0.0);
        CHECK(j["predictions"][k]["reliability"].number <= 1.0);
    }
    const auto loo_rows = loo_ref.select("model", "stable_p15");
    REQUIRE(j["loo"]["rows"].items.size() == loo_rows.size());
    for (std::size_t k = 0; k < loo_rows.size(); ++k) {
        worst = std::max(worst, rel_err(j["loo"]["rows"][k]["prediction"].number, loo_ref.number(loo_rows[k], "pred")));
        worst = std::max(worst, rel_err(j["loo"]["rows"][k]["variance"].number, loo_ref.number(loo_rows[k], "var")));
    }
    INFO("worst rel error vs gstat through the CLI " << worst);
    CHECK(worst <= 1e-8);
    CHECK(j["status"]["factorization"].text == "ok");

    // Text output and --fit auto also run.
    const mocapdb::test::CommandResult t = run_cli("krige --data \"" + (g / "meuse_logzinc.csv").string() + "\" --coords x,y --value logzinc --query \"" +
                                q.string() + "\" --fit auto --trend linear --normalize");
    INFO("stderr: " << t.err);
    CHECK(t.exit_code == 0);
    CHECK(t.out.find("reliability") != std::string::npos);
}

TEST_CASE("CLI reports bad tables with file and line, and bad options, with a non-zero exit", "[kriging][cli][errors]") {
    MOCAPDB_REQUIRE_CLI();
    const auto bad = scratch_dir() / "bad.csv";
    {
        std::ofstream out(bad);
        out << "x,y,v\n1,2,3\n4,oops,6\n7,8,9\n";
    }
    mocapdb::test::CommandResult r = run_cli("variogram --data \"" + bad.string() + "\" --coords x,y --value v");
    INFO("stderr: " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find(bad.string() + ":3") != std::string::npos);
    CHECK(r.err.find("oops") != std::string::npos);

    const auto ragged = scratch_dir() / "ragged.csv";
    {
        std::ofstream out(ragged);
        out << "x,y,v\n1,2,3\n4,5\n";
    }
    r = run_cli("variogram --data \"" + ragged.string() + "\" --coords x,y --value v");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find(ragged.string() + ":3") != std::string::npos);

    r = run_cli("variogram --data \"" + ragged.string() + "\" --coords x,z --value v");
    CHECK(r.exit_code != 0);
    r = run_cli("variogram --data \"" + (scratch_dir() / "missing.csv").string() + "\" --coords x,y --value v");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("missing.csv") != std::string::npos);

    const auto good = scratch_dir() / "good.csv";
    {
        std::ofstream out(good);
        out << "x,y,v\n0,0,1\n1,0,2\n0,1,3\n1,1,5\n";
    }
    r = run_cli("krige --data \"" + good.string() + "\" --coords x,y --value v --query \"" + good.string() +
                "\" --model stable:2.5 --sill 1 --range 1");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("0 < p <= 2") != std::string::npos);
    r = run_cli("krige --data \"" + good.string() + "\" --coords x,y --value v --query \"" + good.string() + "\"");
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("--model") != std::string::npos);
    // Kriging at the data points themselves reproduces them (exact interpolation through the CLI).
    r = run_cli("krige --data \"" + good.string() + "\" --coords x,y --value v --query \"" + good.string() +
                "\" --model sph --sill 1 --range 2 --json");
    REQUIRE(r.exit_code == 0);
    const auto j = parse_json(r.out);
    const double expected[] = {1, 2, 3, 5};
    for (std::size_t k = 0; k < 4; ++k) {
        CHECK(j["predictions"][k]["prediction"].number == Approx(expected[k]).margin(1e-12));
        CHECK(j["predictions"][k]["reliability"].number == Approx(1.0).margin(1e-12));
    }
}
