// ACL reference tables (issue 14 item 4): the library's aggregation and interpolation give what the
// peer tool ../shared/reference/acl/compare.py prints for the same inputs and clips, and a malformed
// table is an error naming the file, the line and what was expected.
#include <catch2/catch.hpp>

#include <fnmatch.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/acl_reference.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::eval;
using namespace mocapdb::test;

namespace {

const char* const kPython = "/usr/bin/python3";

std::vector<std::string> clips_matching(const AclTable& table, const std::string& pattern) {
    std::set<std::string> names;
    for (const AclClipRow& r : table.rows)
        if (pattern.empty() || ::fnmatch(pattern.c_str(), r.clip.c_str(), 0) == 0) names.insert(r.clip);
    return {names.begin(), names.end()};
}

double plain(std::string digits) {  // "12,345" -> 12345
    digits.erase(std::remove(digits.begin(), digits.end(), ','), digits.end());
    return std::stod(digits);
}

// compare.py's verdict at one error: nullopt for "outside", else (ACL bytes, times smaller), as printed.
struct Printed {
    bool outside = false;
    double acl_bytes = 0.0;
    double smaller = 0.0;
};

Printed printed_verdict(const std::string& out, const std::string& label) {
    const std::regex inside("at your " + label + " error [^:]*: ACL ([0-9,]+) bytes, yours [0-9,]+: ([0-9.]+)x smaller");
    const std::regex outside("at your " + label + " error [^:]*: outside ACL's measured range");
    std::smatch m;
    Printed p;
    if (std::regex_search(out, m, inside)) {
        p.acl_bytes = plain(m[1].str());
        p.smaller = std::stod(m[2].str());
    } else {
        REQUIRE(std::regex_search(out, outside));
        p.outside = true;
    }
    return p;
}

}  // namespace

TEST_CASE("ACL reference: bytes at our error equal compare.py's on the shared tables", "[eval][acl][shared]") {
    const auto dir = reference_dir() / "acl";
    MOCAPDB_REQUIRE_SHARED(dir / "compare.py");
    if (!std::filesystem::exists(kPython)) {
        WARN("SKIPPED: " << kPython << " not found (the peer tool is a Python script)");
        return;
    }
    struct Case {
        const char* table;
        const char* pattern;
        double bytes, max_cm, rmse_cm;
    };
    const Case cases[] = {
        {"cmu-asfamc.csv", "16_*", 2500000, 0.98, 0.3},
        {"cmu-asfamc.csv", "", 1521224, 0.99999, 0.271},
        {"cmu-asfamc.csv", "0[25]_*", 400000, 0.1, 0.0275},
        {"cmu-walkrun-pfnn.csv", "", 95457, 0.99991, 0.308},
        {"cmu-walkrun-pfnn.csv", "*_0[13]_60fps", 20000, 0.5, 0.16},
        {"cmu-walkrun-pfnn.csv", "", 50000, 5.0, 0.003},  // above and below ACL's measured range
        {"cmu-asfamc.csv", "", 3000000, 0.01, 0.0033},    // E = 0.01: both below (lower bounds)
    };
    for (const Case& c : cases) {
        INFO(c.table << " clips '" << c.pattern << "' bytes " << c.bytes << " max " << c.max_cm << " rmse " << c.rmse_cm);
        const AclTable table = read_acl_table(dir / c.table);
        const std::vector<std::string> clips = clips_matching(table, c.pattern);
        REQUIRE(!clips.empty());
        const AclCollection acl = aggregate_acl(table, clips);
        CHECK(acl.complete());
        CHECK(acl.settings.size() == 4);
        const AclComparison mine = compare_with_acl(acl, c.bytes, c.max_cm, c.rmse_cm);

        char numbers[160];
        std::snprintf(numbers, sizeof numbers, " --bytes %.17g --max-cm %.17g --rmse-cm %.17g", c.bytes, c.max_cm, c.rmse_cm);
        const CommandResult r = run_command(std::string(kPython) + " " + quoted((dir / "compare.py").string()) + " " +
                                            quoted((dir / c.table).string()) + numbers +
                                            (*c.pattern ? " --clips " + quoted(c.pattern) : std::string()));
        INFO(r.output);
        REQUIRE(r.exit_code == 0);
        // The per-setting totals it prints: precision, bytes, max, RMSE (4 decimals), clip count.
        const std::regex setting(R"(\n\s+([0-9.]+)\s+([0-9,]+)\s+max ([0-9.]+)\s+rmse ([0-9.]+)\s+\((\d+)\))");
        std::size_t k = 0;
        for (std::sregex_iterator it(r.out.begin(), r.out.end(), setting), end; it != end; ++it, ++k) {
            REQUIRE(k < acl.settings.size());
            const AclSetting& s = acl.settings[k];
            CHECK(s.precision_cm == Approx(std::stod((*it)[1].str())));
            CHECK(static_cast<double>(s.bytes) == plain((*it)[2].str()));
            CHECK(s.max_cm == Approx(std::stod((*it)[3].str())).margin(5.1e-5));
            CHECK(s.rmse_cm == Approx(std::stod((*it)[4].str())).margin(5.1e-5));
            CHECK(static_cast<double>(s.clips) == std::stod((*it)[5].str()));
            CHECK(s.clips == clips.size());
        }
        CHECK(k == acl.settings.size());
        const Printed at_max = printed_verdict(r.out, "max");
        const Printed at_rmse = printed_verdict(r.out, "rmse");
        // compare.py gives no figure outside ACL's range; below it we give ACL's most precise setting
        // as a flagged lower bound (AclComparison), otherwise the same figures.
        CHECK(at_max.outside == (!mine.bytes_at_max.has_value() || mine.max_lower_bound));
        CHECK(at_rmse.outside == (!mine.bytes_at_rmse.has_value() || mine.rmse_lower_bound));
        const AclSetting& finest = acl.settings.front();  // by precision: the smallest errors
        if (mine.max_lower_bound) {
            CHECK(c.max_cm < finest.max_cm);
            CHECK(*mine.bytes_at_max == static_cast<double>(finest.bytes));
        } else if (mine.bytes_at_max) {
            CHECK(*mine.bytes_at_max == Approx(at_max.acl_bytes).margin(0.5 + 1e-6));
            CHECK(*mine.smaller_at_max == Approx(at_max.smaller).margin(0.005 + 1e-9));
        }
        if (mine.rmse_lower_bound) {
            CHECK(c.rmse_cm < finest.rmse_cm);
            CHECK(*mine.bytes_at_rmse == static_cast<double>(finest.bytes));
        } else if (mine.bytes_at_rmse) {
            CHECK(*mine.bytes_at_rmse == Approx(at_rmse.acl_bytes).margin(0.5 + 1e-6));
            CHECK(*mine.smaller_at_rmse == Approx(at_rmse.smaller).margin(0.005 + 1e-9));
        }
    }
}

TEST_CASE("ACL reference: interpolation is log-linear between bracketing settings, none outside", "[eval][acl]") {
    const std::vector<std::pair<double, double>> pts{{1.0, 1000.0}, {0.1, 10000.0}, {0.01, 100000.0}};
    CHECK(*bytes_at_error(pts, 0.1) == Approx(10000.0));
    CHECK(*bytes_at_error(pts, std::sqrt(0.1)) == Approx(std::sqrt(1000.0 * 10000.0)));  // midpoint in log
    CHECK(*bytes_at_error(pts, 0.01) == Approx(100000.0));
    CHECK_FALSE(bytes_at_error(pts, 1.0001));
    CHECK_FALSE(bytes_at_error(pts, 0.0099));
    CHECK_FALSE(bytes_at_error(pts, 0.0));
    CHECK_FALSE(bytes_at_error(pts, std::nan("")));
    CHECK_FALSE(bytes_at_error({}, 0.5));

    // Clips asked for that the table lacks make the collection incomplete, and are named.
    AclTable t;
    t.rows.push_back({"d", "a", 0.1, 10, 2, 100, 500, 0.2, 0.05, 2});
    t.rows.push_back({"d", "a", 1.0, 10, 2, 100, 200, 1.5, 0.4, 3});
    const AclCollection acl = aggregate_acl(t, {"a", "b"});
    CHECK_FALSE(acl.complete());
    REQUIRE(acl.missing.size() == 1);
    CHECK(acl.missing.front() == "b");
    CHECK(aggregate_acl(t, {"a"}).complete());
    const AclComparison c = compare_with_acl(aggregate_acl(t, {"a"}), 100.0, 0.2, 0.4);
    CHECK(*c.bytes_at_max == Approx(500.0));
    CHECK(*c.smaller_at_max == Approx(5.0));
    CHECK(*c.bytes_at_rmse == Approx(200.0));
    CHECK_FALSE(c.max_lower_bound);
    CHECK_FALSE(c.rmse_lower_bound);

    // Below ACL's most precise setting (error 0.2, 500 bytes, its largest): those bytes as a flagged
    // lower bound; above its coarsest: none.
    const AclComparison below = compare_with_acl(aggregate_acl(t, {"a"}), 100.0, 0.05, 0.01);
    CHECK(below.max_lower_bound);
    CHECK(below.rmse_lower_bound);
    CHECK(*below.bytes_at_max == 500.0);
    CHECK(*below.smaller_at_max == Approx(5.0));
    CHECK(*below.bytes_at_rmse == 500.0);
    const AclComparison above = compare_with_acl(aggregate_acl(t, {"a"}), 100.0, 2.0, 0.5);
    CHECK_FALSE(above.bytes_at_max);
    CHECK_FALSE(above.max_lower_bound);
    CHECK_FALSE(above.bytes_at_rmse);
    // No bound when the most precise setting is not the largest (its bytes would not bound ACL's).
    AclTable odd = t;
    odd.rows[0].acl_bytes = 100;
    const AclComparison none = compare_with_acl(aggregate_acl(odd, {"a"}), 100.0, 0.05, 0.01);
    CHECK_FALSE(none.bytes_at_max);
    CHECK_FALSE(none.max_lower_bound);
}

TEST_CASE("ACL reference: a malformed table is an error naming the file, line and what was expected", "[eval][acl]") {
    TempDir dir("acl-bad");
    const std::string header =
        "dataset,clip,precision_cm,status,joints,end_sites,acl_tracks,channels,frames,fps,raw_f32_bytes,acl_bytes,"
        "ratio_f32,max_cm,p99_cm,rmse_cm,acl_metric_max_cm,preprocess_s,compress_s,decompress_us_per_pose,"
        "worst_joint_at_frame,warnings\n";
    const std::string good =
        "x,02_01,0.1,ok,31,7,38,96,343,120,131712,23597,5.5817,0.117126,0.0842066,0.0358568,0.144653,0.01,0.06,1.1,"
        "\"ltoes_end@234\",\"a, quoted \"\"cell\"\"\"\n";
    const std::string raw = "x,02_01,raw,ok,31,7,38,96,343,120,131712,131712,1,0,0,0,0,0,0,0.5,\"\",\"\"\n";
    struct Bad {
        std::string text;
        std::string where;
        std::string what;
    };
    const Bad bads[] = {
        {header + good + "x,02_02,0.1,ok,31,7,38,96,abc,120,131712,23597,5.5,0.1,0.08,0.03,0.1,0.01,0.06,1.1,\"\",\"\"\n",
         ":3:9:", "column 'frames': expected a whole number, found 'abc'"},
        {header + good + "x,02_02,0.1,ok,31,7\n", ":3:", "expected 22 comma-separated cells (as in the header), found 6"},
        {header + raw + good + "x,02_02,0.1,ok,31,7,38,96,343,120,1,2,5.5,-0.1,0.08,0.03,0.1,0.01,0.06,1.1,\"\",\"\"\n",
         ":4:14:", "column 'max_cm': expected a number >= 0, found '-0.1'"},
        {header + "x,02_02,0.1,ok,31,7,38,96,343,120,1,2,5.5,0.1,0.08,0.03,0.1,0.01,0.06,1.1,\"open,\n", ":2:",
         "expected a closing quote"},
        {"clip,precision,bytes\n02_01,0.1,5\n", ":1:", "expected a header naming column 'precision_cm'"},
        {"", ":1:", "expected a header row"},
    };
    for (const Bad& b : bads) {
        const auto file = dir / "bad.csv";
        std::ofstream(file) << b.text;
        INFO(b.text);
        try {
            read_acl_table(file);
            FAIL("no error");
        } catch (const ParseError& e) {
            const std::string what = e.what();
            INFO(what);
            CHECK(what.find(file.string() + b.where) == 0);
            CHECK(what.find(b.what) != std::string::npos);
            CHECK(what.find('\n') == std::string::npos);
        }
    }
    // The good rows read, the raw container is skipped, quoted cells with commas and quotes are cells.
    const auto file = dir / "good.csv";
    std::ofstream(file) << header << raw << good;
    const AclTable t = read_acl_table(file);
    REQUIRE(t.rows.size() == 1);
    CHECK(t.skipped_rows == 1);
    CHECK(t.rows[0].clip == "02_01");
    CHECK(t.rows[0].acl_bytes == 23597);
    CHECK(t.rows[0].line == 3);
    CHECK_THROWS_AS(read_acl_table(dir / "absent.csv"), IoError);
}
