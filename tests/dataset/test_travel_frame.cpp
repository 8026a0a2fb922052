// Canonicalization by the initial direction of travel and the forward-foot phase check (issue #15).
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/phase_check.hpp"
#include "mocapdb/dataset/travel_frame.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "shared_clips.hpp"

using namespace mocapdb;

namespace {

constexpr double kDegree = kPi / 180.0;

std::vector<std::string> walks16() {
    std::vector<std::string> out;
    for (int t = 11; t <= 34; ++t) out.push_back("16_" + std::to_string(t));
    out.push_back("16_47");
    return out;
}

// Direction (rad about +Y, 0 = +Z) of the canonical root displacement from frame 0 to `frame`.
double canonical_direction(const Clip& clip, const Canonicalization& c, std::size_t frame) {
    const Vec3 a = c.apply(motion_root_transform(*clip.skeleton, clip.frame(0)).position);
    const Vec3 b = c.apply(motion_root_transform(*clip.skeleton, clip.frame(frame)).position);
    return std::atan2(b.x() - a.x(), b.z() - a.z());
}

double spread(const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end());
}

}  // namespace

TEST_CASE("travel frame: walks16 start along +Z whatever their phase", "[align][travel][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto clips = test::read_shared_clips("cmu-asfamc", walks16());
    // Measured over the first 40 cm (inside the 75 cm that define the frame, so the step's sway shows).
    std::vector<double> by_travel, by_heading;
    for (const Clip& c : clips) {
        const TravelFrame t = travel_canonicalization(c);
        REQUIRE(t.by_travel);
        CHECK(t.travel_cm >= 75.0);
        std::size_t f = 1;
        while (f + 1 < c.frame_count() &&
               (motion_root_transform(*c.skeleton, c.frame(f)).position - motion_root_transform(*c.skeleton, c.frame(0)).position)
                       .cwiseProduct(Vec3(1, 0, 1)).norm() < 40.0)
            ++f;
        by_travel.push_back(canonical_direction(c, t.canonical, f));
        by_heading.push_back(canonical_direction(c, canonicalization_of(c), f));
        CHECK(t.canonical.translation == canonicalization_of(c).translation);
    }
    INFO("initial travel direction spread: first-frame heading " << spread(by_heading) / kDegree << " deg, travel frame "
                                                                 << spread(by_travel) / kDegree << " deg");
    // Measured so: 20.5 degrees by the first frame's heading, 8.0 in the travel frame.
    CHECK(spread(by_heading) > 15.0 * kDegree);
    CHECK(spread(by_travel) < 10.0 * kDegree);
    CHECK(spread(by_travel) < 0.5 * spread(by_heading));
}

TEST_CASE("travel frame: a sample that stays in place keeps its first frame's heading", "[align][travel][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    Clip c = test::read_shared_clips("cmu-asfamc", {"16_11"}).front();
    const Skeleton& s = *c.skeleton;
    for (const ChannelType t : {ChannelType::Xposition, ChannelType::Zposition}) {
        const int col = s.channel_column(0, t);
        c.channels.col(col).setConstant(c.channels(0, col));
    }
    const TravelFrame t = travel_canonicalization(c);
    CHECK(!t.by_travel);
    CHECK(t.travel_cm < 1e-9);
    CHECK(t.canonical.yaw == canonicalization_of(c).yaw);
}

TEST_CASE("phase check: whole walks agree on the forward foot mid-clip, not at the ends", "[align][phase][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto clips = test::read_shared_clips("cmu-asfamc", walks16());
    AlignOptions o;
    o.frames = 40;
    const AlignedSet a = align_samples(clips, o);
    const PhaseCheck p = check_phase(clips, a);
    REQUIRE(p.share.size() == 40);
    CHECK(p.feet == std::vector<std::string>{"ltoes", "rtoes"});
    INFO("share at frame 0: " << p.share[0] << ", mean " << p.mean << ", min " << p.min);
    CHECK(p.share[0] < 0.8);  // both ends pinned: mixed phases (issue #15: 60 %)
    CHECK(p.share[20] > 0.9);
    CHECK(p.min == p.share.minCoeff());
    const auto low = p.below(0.8);
    REQUIRE(!low.empty());
    CHECK(low.front().first == 0);
    for (const auto& [first, last] : low) CHECK(first <= last);
}
