// Procedural reaching: IK exactness at contact, planted feet, timing that depends on the target,
// continuity, determinism, BVH round trip.
#include <catch2/catch.hpp>

#include <sstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/procedural/reach.hpp"
#include "procedural_checks.hpp"

using namespace mocapdb;
using namespace mocapdb::procedural;
using namespace mocapdb::test;

namespace {
std::vector<ReachParams> sample_targets() {
    std::vector<ReachParams> out;
    for (double angle : {-120.0, -60.0, 0.0, 45.0, 90.0})
        for (double height : {60.0, 110.0, 165.0})
            for (double distance : {40.0, 60.0}) out.push_back({angle, height, distance, 0.0});
    out.push_back({20.0, 100.0, 55.0, 30.0});  // a swivelled elbow
    return out;
}
}  // namespace

TEST_CASE("reach: the right hand's end site is on the target from contact to release (library FK)", "[procedural]") {
    double worst = 0.0, worst_before = 1e9;
    for (const ReachParams& p : sample_targets()) {
        const ReachMotion m = generate_reach(p);
        INFO("angle " << p.angle_deg << " height " << p.height_cm << " distance " << p.distance_cm);
        REQUIRE(m.target.isApprox(reach_target(p)));
        REQUIRE(m.contact_frame > m.reach_begin);
        REQUIRE(m.release_frame > m.contact_frame);
        REQUIRE(m.release_frame + 2 < m.clip.frame_count());
        const auto hand = joint_track(m.clip, HumanoidNames::right_hand_end);
        for (std::size_t f = m.contact_frame; f <= m.release_frame; ++f) worst = std::max(worst, (hand[f] - m.target).norm());
        // Before contact and after the return the hand is elsewhere.
        worst_before = std::min(worst_before, (hand[m.reach_begin] - m.target).norm());
        REQUIRE((hand.back() - m.target).norm() > 10.0);
        // Nothing below the floor.
        GlobalPose pose;
        for (std::size_t f = 0; f < m.clip.frame_count(); f += 5) {
            forward_kinematics(*m.clip.skeleton, m.clip.frame(f), pose);
            for (const Vec3& q : pose.positions) REQUIRE(q.y() > -0.5);
        }
    }
    INFO("largest hand-target distance during contact: " << worst << " cm");
    CHECK(worst < 1e-6);
    CHECK(worst_before > 10.0);
}

TEST_CASE("reach: feet stay planted while the body turns, bends and crouches", "[procedural]") {
    for (const ReachParams& p : {ReachParams{-120, 60, 60, 0}, ReachParams{90, 60, 60, 0}, ReachParams{0, 180, 45, 0}}) {
        const ReachMotion m = generate_reach(p);
        INFO("angle " << p.angle_deg << " height " << p.height_cm << " lean " << m.lean);
        for (const char* joint : {"LeftFoot", "RightFoot", "LeftToeBase", "RightToeBase", "LeftToeBase_end"}) {
            const auto track = joint_track(m.clip, joint);
            double drift = 0.0;
            for (const Vec3& q : track) drift = std::max(drift, (q - track.front()).norm());
            INFO(joint << " drifts " << drift << " cm");
            CHECK(drift < 1e-6);
        }
    }
    // Low targets make the body bend; targets at the side make it turn.
    CHECK(generate_reach({0, 45, 60, 0}).lean > 0.3);
    CHECK(generate_reach({0, 120, 45, 0}).lean == 0.0);
    CHECK(generate_reach({90, 120, 55, 0}).body_turn > 1.0);
    CHECK(generate_reach({-90, 120, 55, 0}).body_turn < -1.0);
}

TEST_CASE("reach: the duration grows with the hand's travel and the body's turn", "[procedural]") {
    const ReachMotion near = generate_reach({0, 110, 35, 0});
    const ReachMotion far = generate_reach({0, 110, 70, 0});
    const ReachMotion side = generate_reach({-110, 110, 70, 0});
    INFO("reach seconds: near " << near.reach_seconds << ", far " << far.reach_seconds << ", side " << side.reach_seconds);
    CHECK(far.reach_seconds > near.reach_seconds);
    CHECK(side.reach_seconds > far.reach_seconds + 0.2);
    CHECK(side.clip.frame_count() > far.clip.frame_count());
    CHECK(near.reach_seconds > 0.3);
    CHECK(side.reach_seconds < 2.0);
    // Frame counts follow the rate.
    ReachOptions slow;
    slow.frame_rate = 30.0;
    const ReachMotion m30 = generate_reach({0, 110, 70, 0}, slow);
    CHECK(static_cast<double>(m30.contact_frame - m30.reach_begin) ==
          Approx(static_cast<double>(far.contact_frame - far.reach_begin) / 2.0).margin(1.0));
}

TEST_CASE("reach: continuous motion, no joint-angle jumps between frames", "[procedural]") {
    for (const ReachParams& p : sample_targets()) {
        const ReachMotion m = generate_reach(p);
        const Continuity c = continuity(m.clip);
        INFO("angle " << p.angle_deg << " height " << p.height_cm << " distance " << p.distance_cm << ": rotation step "
                      << c.max_rotation_step_deg << " deg, channel step " << c.max_channel_step_deg << " deg, root step "
                      << c.max_root_step_cm << " cm");
        CHECK(c.max_rotation_step_deg < 10.0);  // 60 Hz: under 600 deg/s (measured ≤ 8.2)
        CHECK(c.max_channel_step_deg < 15.0);   // no Euler flips (those jump by ~180 deg)
        CHECK(c.max_root_step_cm < 2.0);
    }
}

TEST_CASE("reach: deterministic, and out-of-range targets are refused", "[procedural]") {
    const ReachMotion a = generate_reach({30, 90, 50, 0});
    const ReachMotion b = generate_reach({30, 90, 50, 0});
    CHECK(a.clip.channels == b.clip.channels);
    CHECK_THROWS_AS(generate_reach({170, 100, 50, 0}), InvalidArgument);
    CHECK_THROWS_AS(generate_reach({0, 10, 50, 0}), InvalidArgument);
    CHECK_THROWS_AS(generate_reach({0, 100, 200, 0}), InvalidArgument);
    CHECK_THROWS_AS(generate_reach({0, 199, 95, 0}), InvalidArgument);  // above and far: out of reach
    CHECK_THROWS_WITH(generate_reach({0, 199, 95, 0}), Catch::Matchers::Contains("out of reach"));
    // Low and far at the side needs a step, which the generator does not take.
    CHECK_THROWS_WITH(generate_reach({-120, 50, 65, 0}), Catch::Matchers::Contains("out of reach"));
}

TEST_CASE("reach: BVH written and read back gives the same skeleton and motion", "[procedural]") {
    const ReachMotion m = generate_reach({-45, 130, 60, 0});
    std::ostringstream text;
    write_bvh(text, m.clip);
    const Clip back = parse_bvh(text.str(), "reach.bvh");
    REQUIRE(back.skeleton->same_structure(*m.clip.skeleton));
    REQUIRE(back.frame_count() == m.clip.frame_count());
    CHECK(back.frame_rate == Approx(m.clip.frame_rate).epsilon(1e-12));
    // 9 significant digits: channels within 1e-8 relative, the hand within 1e-4 cm of the target.
    CHECK((back.channels - m.clip.channels).cwiseAbs().maxCoeff() < 1e-5);
    const auto hand = joint_track(back, HumanoidNames::right_hand_end);
    CHECK((hand[m.contact_frame] - m.target).norm() < 1e-4);
}
