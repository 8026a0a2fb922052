// Parameter extractors against the measurements published in the shared data's SOURCE.txt and the
// clip groups named there (issue acceptance: subject 16's walks separate by turn and speed).
#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <regex>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using Catch::Matchers::Contains;

namespace {

struct Measured {
    double disp_m, path_m, speed_m_s, turn_deg;
};

// The "MEASURED ROOT PARAMETERS" table of cmu-asfamc/SOURCE.txt.
std::map<std::string, Measured> measured_table() {
    std::ifstream in(test::datasets_dir() / "cmu-asfamc" / "SOURCE.txt");
    const std::regex row(R"(^\s+(\d+_\d+)\.amc .*disp=\s*([-\d.]+) path=\s*([-\d.]+) speed=\s*([-\d.]+) turn=\s*([-\d.]+))");
    std::map<std::string, Measured> out;
    std::string line;
    std::smatch m;
    while (std::getline(in, line))
        if (std::regex_search(line, m, row))
            out[m[1]] = {std::stod(m[2]), std::stod(m[3]), std::stod(m[4]), std::stod(m[5])};
    return out;
}

Clip load_amc(const std::string& trial) {
    return read_clip(test::datasets_dir() / "cmu-asfamc" / (trial + ".amc"));
}

std::vector<ParameterExtractor> extractors(std::initializer_list<const char*> specs) {
    std::vector<ParameterExtractor> out;
    for (const char* s : specs) out.push_back(ParameterExtractor::parse(s));
    return out;
}

}  // namespace

TEST_CASE("turn, speed and displacement match SOURCE.txt's measurements of subject 16's walks", "[extract][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto table = measured_table();
    REQUIRE(table.size() > 100);
    const auto ex = extractors({"turn", "speed", "displacement"});
    std::map<std::string, VecX> values;
    std::vector<std::string> walks;
    for (int t = 11; t <= 34; ++t) walks.push_back("16_" + std::to_string(t));
    walks.push_back("16_47");
    for (const std::string& trial : walks) {
        const Clip clip = load_amc(trial);
        const VecX v = extract_parameters(clip, 0, clip.frame_count(), ex);
        values[trial] = v;
        const Measured& m = table.at(trial);
        INFO(trial << ": turn " << v[0] * 180 / kPi << " deg (table " << m.turn_deg << "), speed " << v[1] / 100
                   << " m/s (table " << m.speed_m_s << "), displacement " << std::hypot(v[2], v[3]) / 100
                   << " m (table " << m.disp_m << ")");
        CHECK(std::abs(v[0] * 180 / kPi - m.turn_deg) <= 0.051);       // printed to 0.1 deg
        CHECK(std::abs(v[1] / 100 - m.speed_m_s) <= 0.011);            // printed to 0.01 m/s (and F vs F-1)
        CHECK(std::abs(std::hypot(v[2], v[3]) / 100 - m.disp_m) <= 0.0051);
    }

    // The groups named in SOURCE.txt separate cleanly on the extracted turn ...
    auto turn_deg = [&](const char* t) { return values.at(t)[0] * 180 / kPi; };
    for (const char* t : {"16_15", "16_16", "16_21", "16_22", "16_31", "16_32", "16_47", "16_33", "16_34"})
        CHECK(std::abs(turn_deg(t)) < 20);
    for (const char* t : {"16_11", "16_12", "16_23", "16_24"}) CHECK((turn_deg(t) > 20 && turn_deg(t) < 70));
    for (const char* t : {"16_13", "16_14", "16_25", "16_26"}) CHECK((turn_deg(t) < -20 && turn_deg(t) > -70));
    for (const char* t : {"16_17", "16_18", "16_27", "16_28"}) CHECK(turn_deg(t) > 70);
    for (const char* t : {"16_19", "16_20", "16_29", "16_30"}) CHECK(turn_deg(t) < -70);
    // ... and the two speeds: every walk of 16_11..16_20 is slower than every walk of 16_21..16_30.
    double slow_max = 0, fast_min = 1e9;
    for (int t = 11; t <= 20; ++t) slow_max = std::max(slow_max, values.at("16_" + std::to_string(t))[1]);
    for (int t = 21; t <= 30; ++t) fast_min = std::min(fast_min, values.at("16_" + std::to_string(t))[1]);
    INFO("slowest of the fast group " << fast_min << " cm/s, fastest of the slow group " << slow_max << " cm/s");
    CHECK(fast_min > slow_max + 20);
}

TEST_CASE("bearing: the direction of travel of subject 16's walks follows their turn", "[extract][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto ex = extractors({"turn", "bearing"});
    CHECK(ex[1].periods() == std::vector<double>{2.0 * kPi});
    CHECK(ex[0].periods() == std::vector<double>{0.0});
    for (int t = 11; t <= 34; ++t) {
        const std::string trial = "16_" + std::to_string(t);
        const Clip clip = load_amc(trial);
        const VecX v = extract_parameters(clip, 0, clip.frame_count(), ex);
        INFO(trial << ": turn " << v[0] << " rad, bearing " << v[1] << " rad");
        CHECK(std::abs(v[1]) <= kPi);
        if (std::abs(v[0]) < 0.2) {
            CHECK(std::abs(v[1]) < 0.15);  // straight walks travel straight ahead
        } else {
            // On a turn the net travel points between the start heading and the end heading.
            CHECK(v[1] / v[0] > 0.0);
            CHECK(v[1] / v[0] < 1.0);
        }
    }
    // A clip that does not travel has no direction of travel.
    Clip still = slice(load_amc("16_15"), 0, 3);
    still.channels.row(1) = still.channels.row(0);
    still.channels.row(2) = still.channels.row(0);
    CHECK_THROWS_WITH(extract_parameters(still, 0, 3, ex), Contains("too little for a bearing"));
}

TEST_CASE("jump length of forward jumps follows the clips' net travel", "[extract][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto table = measured_table();
    const auto ex = extractors({"jump"});
    std::vector<double> jump, disp;
    for (const char* trial : {"16_05", "16_06", "16_07", "16_09", "16_10", "13_11", "13_13", "13_19", "13_32"}) {
        const Clip clip = load_amc(trial);
        const double j = extract_parameters(clip, 0, clip.frame_count(), ex)[0];
        INFO(trial << ": jump " << j << " cm, net displacement " << table.at(trial).disp_m * 100 << " cm");
        // The flight is part of the clip's travel, and a standing forward jump's flight is 40-250 cm.
        CHECK(j < table.at(trial).disp_m * 100 + 15);
        CHECK((j > 40 && j < 250));
        WARN(trial << ": jump " << j << " cm, net displacement " << table.at(trial).disp_m * 100 << " cm");
        jump.push_back(j);
        disp.push_back(table.at(trial).disp_m);
    }
}

TEST_CASE("reach extracts a joint position in the root's heading frame", "[extract][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Clip clip = load_amc("16_15");
    const VecX v = extract_parameters(clip, 0, clip.frame_count(), extractors({"reach:head@0", "reach:lhand@end"}));
    REQUIRE(v.size() == 6);
    INFO("head " << v.head<3>().transpose() << " lhand " << v.tail<3>().transpose());
    CHECK(v[1] > 40);                 // the head is well above the root
    CHECK(std::abs(v[0]) < 20);       // and roughly centred
    CHECK(v[3] > 5);                  // the left hand is on the character's left (+x)
}

TEST_CASE("extractor specs and undefined quantities give clear errors", "[extract]") {
    CHECK_THROWS_WITH(ParameterExtractor::parse("twist"), Contains("unknown extractor 'twist'"));
    CHECK_THROWS_WITH(ParameterExtractor::parse("reach:head"), Contains("reach:JOINT@FRAME"));
    const auto e = ParameterExtractor::parse("reach:lhand@50%");
    CHECK(e.names() == std::vector<std::string>{"lhand_x", "lhand_y", "lhand_z"});
    CHECK(ParameterExtractor::parse("displacement").units() == std::vector<std::string>{"cm", "cm"});
}
