// Flights (foot_contacts.hpp: longest_flight) and jump samples cut around them (segmentation.hpp:
// flight_window), issue #15: phase-consistent samples for jumps.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/dataset/segmentation.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

using namespace mocapdb;

namespace {

using Contacts = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

// Two feet; frames given as strings of '1' (contact) and '0' (no contact).
Contacts contacts(const std::string& left, const std::string& right) {
    Contacts c(2, static_cast<Eigen::Index>(left.size()));
    for (std::size_t f = 0; f < left.size(); ++f) {
        c(0, static_cast<Eigen::Index>(f)) = left[f] == '1';
        c(1, static_cast<Eigen::Index>(f)) = right[f] == '1';
    }
    return c;
}

}  // namespace

TEST_CASE("the longest flight is bounded by contact on both sides", "[flight]") {
    // Frames 2-3 and 6-9 have no contact; the second is longer.
    auto f = longest_flight(contacts("1100110000111", "1000100000011"));
    REQUIRE(f);
    CHECK(f->takeoff == 5);
    CHECK(f->landing == 10);
    // One foot down is contact: no flight at all.
    CHECK_FALSE(longest_flight(contacts("1010101", "0101010")));
    // Runs of no contact at the clip's ends are not flights (the take-off or landing is not seen).
    f = longest_flight(contacts("00001000100000", "00001000100000"));
    REQUIRE(f);
    CHECK(f->takeoff == 4);
    CHECK(f->landing == 8);
    // Equally long flights: the first.
    f = longest_flight(contacts("1001001", "1001001"));
    REQUIRE(f);
    CHECK(f->takeoff == 0);
    CHECK(f->landing == 3);
}

TEST_CASE("a forward jump's window keeps its flight and the margins around it", "[flight][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    ParameterExtractor jump = ParameterExtractor::parse("jump");
    FlightWindowOptions options;
    for (const char* trial : {"13_11", "16_05", "105_39"}) {
        const Clip clip = read_clip(test::datasets_dir() / "cmu-asfamc" / (std::string(trial) + ".amc"));
        const auto whole = longest_flight(foot_contacts(clip, options.contacts));
        REQUIRE(whole);
        const std::vector<SampleRef> w = flight_window(clip, trial, options);
        REQUIRE(w.size() == 1);
        INFO(trial << ": " << clip.frame_count() << " frames, flight " << whole->takeoff << "-" << whole->landing
                   << ", window " << w[0].begin << "-" << w[0].end);
        CHECK(w[0].clip == trial);
        const auto margin = static_cast<std::size_t>(std::lround(0.5 * clip.frame_rate));
        CHECK(w[0].begin == (static_cast<std::size_t>(whole->takeoff) >= margin ? whole->takeoff - margin : 0));
        CHECK(w[0].end == std::min(clip.frame_count(), static_cast<std::size_t>(whole->landing) + margin + 1));
        // The standing before and after the jump is cut away (these clips hold seconds of it) ...
        CHECK(w[0].end - w[0].begin < clip.frame_count() / 2 + margin);
        // ... and the window holds the same jump: the same length measured on it and on the whole clip.
        const double on_clip = extract_parameters(clip, 0, clip.frame_count(), {jump})[0];
        const double on_window = extract_parameters(clip, w[0].begin, w[0].end, {jump})[0];
        CHECK(on_window == Approx(on_clip).margin(1.0));
    }
}

TEST_CASE("flight windows: none without a flight, and margins must be >= 0", "[flight][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    // A subject standing still (frame 0 of a jump clip, held for one second): both feet always down.
    Clip still = slice(read_clip(test::datasets_dir() / "cmu-asfamc" / "13_11.amc"), 0, 120);
    for (Eigen::Index f = 1; f < still.channels.rows(); ++f) still.channels.row(f) = still.channels.row(0);
    CHECK(flight_window(still, "still").empty());
    FlightWindowOptions bad;
    bad.before_seconds = -0.1;
    CHECK_THROWS_AS(flight_window(still, "still", bad), InvalidArgument);
    bad.before_seconds = 0.5;
    bad.after_seconds = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(flight_window(still, "still", bad), InvalidArgument);
    bad.after_seconds = 1e300;
    CHECK_THROWS_AS(flight_window(still, "still", bad), InvalidArgument);
}

TEST_CASE("a set measuring jump lengths takes the jump of each clip by default", "[flight][set][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const std::vector<std::string> ids = {"16_05", "16_06", "105_39"};
    const ClipLoader load = [](const std::string& id) {
        return read_clip(test::datasets_dir() / "cmu-asfamc" / (id + ".amc"));
    };
    SetBuildOptions options;
    options.name = "jumps";
    parse_segmentation("auto", options);
    options.extractors.push_back(ParameterExtractor::parse("jump"));
    Segmentation used = Segmentation::Auto;
    const MotionSet set = build_motion_set(ids, load, options, nullptr, &used);
    CHECK(used == Segmentation::Flights);
    REQUIRE(set.samples.size() == ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const Clip clip = load(ids[i]);
        const std::vector<SampleRef> w = flight_window(clip, ids[i]);
        REQUIRE(w.size() == 1);
        CHECK(set.samples[i].begin == w[0].begin);
        CHECK(set.samples[i].end == w[0].end);
    }

    // Explicit margins, and what is refused.
    parse_segmentation("flight:0.25:1", options);
    CHECK(options.segmentation == Segmentation::Flights);
    CHECK(options.flight.before_seconds == 0.25);
    CHECK(options.flight.after_seconds == 1.0);
    parse_segmentation("flight:0.3", options);
    CHECK(options.flight.before_seconds == 0.3);
    for (const char* bad : {"flight:", "flight:-1", "flight:x", "flight:0.5:nan", "flight:0.5:1:2", "flights"})
        CHECK_THROWS_AS(parse_segmentation(bad, options), InvalidArgument);
}
