// mocapdb demo (issue #6, the main job): the procedural default and --data on real CMU walks. Each run
// must print the rate-distortion table and write synth_*.bvh files that our reader loads with the
// frame counts report.json gives, two SVG documents, and a report.json of finite numbers whose
// syntheses inside the sampled region are more reliable than the one outside and measure close to
// what was requested.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "mini_json.hpp"
#include "mocapdb/io/bvh.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every number in the document is finite and no value is null (the writer turns NaN into null).
void require_finite(const Json& v, const std::string& where) {
    INFO(where);
    REQUIRE(v.kind != Json::Null);
    if (v.kind == Json::Number) REQUIRE(std::isfinite(v.number));
    for (std::size_t i = 0; i < v.items.size(); ++i) require_finite(v.items[i], where + "[" + std::to_string(i) + "]");
    for (const auto& [k, m] : v.members) require_finite(m, where + "." + k);
}

void require_svg(const std::filesystem::path& p) {
    INFO(p.string());
    REQUIRE(std::filesystem::exists(p));
    const std::string text = slurp(p);
    REQUIRE(text.rfind("<svg", 0) == 0);
    const auto close = text.rfind("</svg>");
    REQUIRE(close != std::string::npos);
    CHECK(text.find_first_not_of(" \n", close + 6) == std::string::npos);
}

struct DemoRun {
    Json report;
    std::string out;
};

// Runs the demo, checks what every run must hold, returns report.json.
// rho_order: check that every synthesis between the samples is more reliable than the one outside.
DemoRun run_demo(const std::filesystem::path& out, const std::string& arguments, bool rho_order = true) {
    const CommandResult r = run_cli("demo --out " + quoted(out.string()) + " " + arguments);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    // The compression table (as `mocapdb report`) and one line per synthesis on stdout.
    CHECK_THAT(r.out, Contains("method") && Contains("ratio") && Contains("max_cm") && Contains("tucker ") &&
                          Contains("zfp") && Contains("deflate") && Contains("== synthesis") && Contains("rho "));
    for (const char* f : {"demo.h5", "report.json", "README.txt"}) CHECK(std::filesystem::exists(out / f));
    require_svg(out / "reliability.svg");
    require_svg(out / "rate_distortion.svg");
    CHECK_THAT(slurp(out / "reliability.svg"), Contains("<circle"));

    DemoRun d{JsonParser(slurp(out / "report.json")).parse(), r.out};
    require_finite(d.report, "report");
    const Json& rows = d.report["rate_distortion"]["rows"];
    REQUIRE(rows.items.size() >= 5);
    bool tucker_at_target = false;
    for (const Json& row : rows.items)
        if (row["method"].text == "tucker" && row["target_cm"].number == 1.0 && row["target_met"].boolean) {
            CHECK(row["max_cm"].number <= 1.0 + 1e-9);
            CHECK(row["ratio"].number > 1.0);
            tucker_at_target = true;
        }
    CHECK(tucker_at_target);
    CHECK(d.report["compress"]["max_cm"].number <= 1.0 + 1e-9);

    // Every synthesized file reloads with the frames the report gives; rho in [0, 1].
    const Json& motions = d.report["synthesis"]["motions"];
    REQUIRE(motions.items.size() >= 3);
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(out))
        if (e.path().filename().string().rfind("synth_", 0) == 0) ++files;
    CHECK(files == motions.items.size());
    double worst_inside = 1.0, outside = -1.0;
    for (const Json& m : motions.items) {
        INFO(m["file"].text);
        const Clip clip = read_bvh(out / m["file"].text);
        CHECK(static_cast<double>(clip.frame_count()) == m["frames"].number);
        CHECK(clip.frame_count() >= 10);
        const double rho = m["reliability"].number;
        CHECK(rho >= 0.0);
        CHECK(rho <= 1.0);
        if (m["inside"].boolean) worst_inside = std::min(worst_inside, rho);
        else outside = rho;
        REQUIRE(m.has("measured"));
        CHECK(m["measured"].items.size() == m["requested"].items.size());
    }
    REQUIRE(outside >= 0.0);  // the demo always synthesizes one motion outside the samples
    if (rho_order) CHECK(worst_inside > outside);
    // Issue #15: the request outside the samples (one sampled range beyond them: 2.8 standard
    // deviations for 5 evenly spaced values, more for fewer) is flagged: rho <= 0.5 and the warning synth
    // gives it (the set's calibrated variance or distance, else rho below 0.5) under its synthesis line.
    CHECK(outside <= 0.5);
    const std::size_t at = r.out.find("_outside.bvh");
    REQUIRE(at != std::string::npos);
    const std::string after = r.out.substr(at, 1500);  // its lines: requested, measured, rho, warnings
    const bool flagged = after.find("SD beyond the samples") != std::string::npos ||
                         after.find("of the sill") != std::string::npos ||
                         after.find("< 0.5: the parameters are far") != std::string::npos;
    CHECK(flagged);
    return d;
}

}  // namespace

TEST_CASE("demo: procedural reaches, through the whole pipeline", "[cli][demo]") {
    TempDir dir("demo-cli");
    const std::filesystem::path out = dir / "out";
    // rho falls outside the samples here too (it used to stay at 1: a p = 2 variogram of the raw values with
    // a range four times the samples' spread; issue #15).
    const DemoRun d = run_demo(out, "--quick");
    CHECK(d.report["mode"].text == "procedural-reach");
    CHECK(std::filesystem::exists(out / "samples" / "params.csv"));
    const Json& params = d.report["set"]["parameters"];
    REQUIRE(params.items.size() == 2);
    CHECK(params[0]["name"].text == "angle");
    CHECK(params[1]["name"].text == "height");
    // Between the sampled targets (cell centres of a 30 deg x 40 cm grid), the hand reaches near the
    // requested target: bearing within 5 degrees and height within 5 cm.
    for (const Json& m : d.report["synthesis"]["motions"].items) {
        if (!m["inside"].boolean) continue;
        INFO(m["file"].text);
        CHECK(std::abs(m["measured"][0].number - m["requested"][0].number) < 5.0);
        CHECK(std::abs(m["measured"][1].number - m["requested"][1].number) < 5.0);
    }
    // A second run refuses to replace the outputs without --force.
    const CommandResult again = run_cli("demo --quick --out " + quoted(out.string()));
    CHECK(again.exit_code != 0);
    CHECK_THAT(again.err, Contains("--force"));
}

TEST_CASE("demo: procedural walks", "[cli][demo]") {
    TempDir dir("demo-cli-walk");
    const DemoRun d = run_demo(dir / "out", "--quick --motion walk");
    CHECK(d.report["mode"].text == "procedural-walk");
    // Parameters speed [cm/s], turn [rad] from params.csv, measured back by the speed and turn extractors:
    // between the samples within 5 % and 0.05 rad.
    REQUIRE(d.report["set"]["parameters"][0]["name"].text == "speed");
    for (const Json& m : d.report["synthesis"]["motions"].items) {
        if (!m["inside"].boolean) continue;
        INFO(m["file"].text);
        CHECK(std::abs(m["measured"][0].number / m["requested"][0].number - 1.0) < 0.05);
        CHECK(std::abs(m["measured"][1].number - m["requested"][1].number) < 0.05);
    }
}

TEST_CASE("demo --data: six of subject 16's walks (ASF/AMC)", "[cli][demo][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("demo-cli-data");
    const std::filesystem::path data = dir / "clips";
    std::filesystem::create_directories(data);
    const std::filesystem::path cmu = datasets_dir() / "cmu-asfamc";
    std::filesystem::create_symlink(cmu / "16.asf", data / "16.asf");
    for (const char* t : {"16_11", "16_13", "16_15", "16_16", "16_21", "16_22"})
        std::filesystem::create_symlink(cmu / (std::string(t) + ".amc"), data / (std::string(t) + ".amc"));
    // No rho ordering (open, issue #15): with 6 samples and a 3-term linear trend the prediction variance
    // of the residual variogram exceeds the bounded sill between the samples too (measured 2026-12-02:
    // rho 0 inside and outside), so rho carries no information on so few samples.
    const DemoRun d = run_demo(dir / "out", "--quick --data " + quoted(data.string()), false);
    CHECK(d.report["mode"].text == "data");
    CHECK(d.report["set"]["samples"].number >= 6.0);  // gait cycles by default: one or more per walk
    CHECK(d.report["set"]["parameter_source"].text == "extract:turn,speed");
    // Between the samples (6 walks only) the measured turn is within 0.05 rad and the speed within 12 %
    // of the request (measured on 2026-11-22: 0.00 rad and 7.3 % at worst).
    for (const Json& m : d.report["synthesis"]["motions"].items) {
        if (!m["inside"].boolean) continue;
        INFO(m["file"].text);
        CHECK(std::abs(m["measured"][0].number - m["requested"][0].number) < 0.05);
        CHECK(std::abs(m["measured"][1].number / m["requested"][1].number - 1.0) < 0.12);
    }
}
