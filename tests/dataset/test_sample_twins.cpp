// Twin detection (dataset/sample_twins.hpp, issue #38 item 5): overlapping frame ranges of one clip, and
// the same frames in two clips (moved elsewhere on the floor: compared in their canonical placement),
// on subject 16's walks; near misses are not twins.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/sample_twins.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "shared_data.hpp"

using namespace mocapdb;

namespace {

Clip walk(const std::string& trial) { return read_clip(test::datasets_dir() / "cmu-asfamc" / (trial + ".amc")); }

// The clip with its root translated by (dx, dy, dz) cm in every frame (CMU roots: TX TY TZ first).
Clip moved(Clip c, double dx, double dy, double dz) {
    c.channels.col(0).array() += dx;
    c.channels.col(1).array() += dy;
    c.channels.col(2).array() += dz;
    return c;
}

}  // namespace

TEST_CASE("twins: overlapping samples of one clip and the same frames in two clips", "[dataset][twins][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    std::map<std::string, Clip> clips;
    clips["16_15"] = walk("16_15");
    clips["16_16"] = walk("16_16");
    clips["copy"] = moved(clips["16_15"], 100.0, 0.0, 50.0);  // elsewhere on the floor: the same motion
    clips["raised"] = moved(clips["16_15"], 0.0, 0.5, 0.0);   // every joint 0.5 cm higher: within 1 cm
    clips["lifted"] = moved(clips["16_15"], 0.0, 2.0, 0.0);   // 2 cm higher: not a twin
    REQUIRE(clips["16_15"].frame_count() >= 400);
    {  // the precondition of `moved`: channels 0-2 translate the root
        const MatX a = joint_positions(slice(clips["16_15"], 0, 1)), b = joint_positions(slice(clips["copy"], 0, 1));
        REQUIRE((b.block<3, 1>(0, 0) - a.block<3, 1>(0, 0) - Vec3(100.0, 0.0, 50.0)).norm() < 1e-9);
    }
    MotionSet set;
    set.name = "walks";
    set.samples = {
        {"16_15", 0, 200},    // 0
        {"16_15", 150, 350},  // 1: shares 50 frames with 0 (25 %): twin
        {"16_15", 349, 400},  // 2: shares one boundary frame with 1 (as consecutive gait cycles do): not
        {"16_16", 0, 200},    // 3: another walk of the same length: not
        {"copy", 0, 200},     // 4: sample 0's frames moved on the floor: twin of 0
        {"raised", 0, 200},   // 5: twin of 0 and 4
        {"lifted", 0, 200},   // 6: not
        {"copy", 300, 351},   // 7: sample 2's length, other frames: not
        {"16_16", 200, 290},  // 8: a length no other sample has: never loaded
    };
    std::vector<std::size_t> loaded;
    const SampleTwins t = find_sample_twins(set, [&](std::size_t i) {
        loaded.push_back(i);
        const SampleRef& s = set.samples[i];
        return slice(clips.at(s.clip), s.begin, s.end);
    });
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (const TwinPair& p : t.pairs) pairs.emplace_back(p.a, p.b);
    CHECK(pairs == std::vector<std::pair<std::size_t, std::size_t>>{{0, 1}, {0, 4}, {0, 5}, {4, 5}});
    REQUIRE(t.pairs.size() == 4);
    CHECK(t.pairs[0].same_clip);
    CHECK(t.pairs[0].shared_frames == 50);
    CHECK_FALSE(t.pairs[1].same_clip);
    CHECK(t.pairs[1].max_distance_cm < 1e-6);
    CHECK(t.pairs[2].max_distance_cm == Approx(0.5).margin(1e-6));
    CHECK(t.groups == std::vector<std::vector<std::size_t>>{{0, 1, 4, 5}});
    const auto partners = t.partners(set.samples.size());
    CHECK(partners[0] == std::vector<std::size_t>{1, 4, 5});
    CHECK(partners[1] == std::vector<std::size_t>{0});
    CHECK(partners[2].empty());
    CHECK(partners[6].empty());
    // Only samples whose length a sample of another clip shares are read.
    CHECK(std::find(loaded.begin(), loaded.end(), std::size_t{8}) == loaded.end());
    CHECK(std::find(loaded.begin(), loaded.end(), std::size_t{3}) != loaded.end());

    TwinOptions strict;
    strict.tolerance_cm = 0.1;
    const SampleTwins s = find_sample_twins(set, [&](std::size_t i) {
        const SampleRef& r = set.samples[i];
        return slice(clips.at(r.clip), r.begin, r.end);
    }, strict);
    CHECK(s.groups == std::vector<std::vector<std::size_t>>{{0, 1, 4}});

    TwinOptions bad;
    bad.tolerance_cm = 0.0;
    CHECK_THROWS_AS(find_sample_twins(set, [&](std::size_t) { return clips["16_15"]; }, bad), InvalidArgument);
}
