// Procedural walking measured by the project's own extractors and contact detection.
#include <catch2/catch.hpp>

#include <sstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/dataset/segmentation.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/procedural/walk.hpp"
#include "procedural_checks.hpp"

using namespace mocapdb;
using namespace mocapdb::procedural;
using namespace mocapdb::test;

namespace {
std::vector<WalkParams> sample_walks() {
    std::vector<WalkParams> out;
    for (double speed : {0.6, 1.3, 1.8})
        for (double turn : {-90.0, 0.0, 45.0}) out.push_back({speed, turn, 0.0});
    out.push_back({1.1, 20.0, 1.5});  // a long stride for the speed
    return out;
}
}  // namespace

TEST_CASE("walk: the speed and turn extractors measure the requested speed and turn", "[procedural]") {
    const std::vector<ParameterExtractor> ex = {ParameterExtractor::parse("speed"), ParameterExtractor::parse("turn"),
                                                ParameterExtractor::parse("displacement")};
    double worst_speed = 0.0, worst_turn = 0.0;
    for (const WalkParams& p : sample_walks()) {
        const WalkMotion m = generate_walk(p);
        const VecX v = extract_parameters(m.clip, 0, m.clip.frame_count(), ex);
        INFO("speed " << p.speed_m_s << " m/s, turn " << p.turn_deg << " deg: measured " << v[0] << " cm/s, "
                      << v[1] * 180.0 / kPi << " deg, displacement (" << v[2] << ", " << v[3] << ") cm");
        worst_speed = std::max(worst_speed, std::abs(v[0] - 100.0 * p.speed_m_s));
        worst_turn = std::max(worst_turn, std::abs(v[1] - p.turn_deg * kPi / 180.0));
        CHECK(v[0] == Approx(100.0 * p.speed_m_s).margin(1e-6));
        CHECK(v[1] == Approx(p.turn_deg * kPi / 180.0).margin(1e-9));
        // The displacement is the chord of the arc walked: forward, and to the side the turn goes.
        const double duration = m.clip.duration();
        const double omega = p.turn_deg * kPi / 180.0 / duration;
        const double chord = std::abs(omega) < 1e-12 ? m.progression_cm_s * duration
                                                     : 2.0 * m.progression_cm_s / std::abs(omega) * std::sin(std::abs(omega) * duration / 2.0);
        CHECK(std::hypot(v[2], v[3]) == Approx(chord).margin(6.0));  // the pelvis sways about the path (≤ 2.3 cm each end)
        if (p.turn_deg > 0) CHECK(v[2] > 0.0);
        if (p.turn_deg < 0) CHECK(v[2] < 0.0);
        // Progression is slower than the path speed only by the sway.
        CHECK(m.progression_cm_s < 100.0 * p.speed_m_s);
        CHECK(m.progression_cm_s > 0.99 * 100.0 * p.speed_m_s);
    }
    INFO("largest errors: speed " << worst_speed << " cm/s, turn " << worst_turn << " rad");
    CHECK(worst_speed < 1e-6);
}

TEST_CASE("walk: planted feet do not slide during the contacts the detector finds", "[procedural]") {
    FootContactOptions contacts;
    contacts.feet = humanoid_feet();
    double worst = 0.0;
    for (const WalkParams& p : sample_walks()) {
        const WalkMotion m = generate_walk(p);
        std::size_t runs = 0;
        const double slide = max_contact_slide(m.clip, contacts, &runs);
        INFO("speed " << p.speed_m_s << " turn " << p.turn_deg << ": " << runs << " contact runs, slide " << slide << " cm");
        CHECK(runs >= 5);  // 3 cycles: about 3 contacts per foot
        CHECK(slide < 1.5);  // measured ≤ 1.16 cm (slow walks: heel roll-in and slow lift-off near the floor)
        worst = std::max(worst, slide);
        // The ball of the foot rests at 1 cm above the floor when planted.
        const auto toe = joint_track(m.clip, HumanoidNames::left_toe);
        double lowest = 1e9;
        for (const Vec3& q : toe) lowest = std::min(lowest, q.y());
        CHECK(lowest == Approx(1.0).margin(1e-6));  // the ball rests at its height above the floor
    }
    INFO("largest slide during detected contacts: " << worst << " cm");
    CHECK(worst < 1.5);
}

TEST_CASE("walk: gait cycles are found and last one generated period", "[procedural]") {
    const WalkMotion m = generate_walk({1.3, 30.0, 0.0});
    GaitCycleOptions o;
    o.feet = humanoid_feet();
    const auto cycles = gait_cycles(m.clip, "walk", o);
    INFO("cycle " << m.cycle_s << " s, stride " << m.stride_m << " m, " << cycles.size() << " cycles found");
    REQUIRE(cycles.size() >= 2);
    for (const SampleRef& c : cycles)
        CHECK(static_cast<double>(c.end - 1 - c.begin) / m.clip.frame_rate == Approx(m.cycle_s).margin(2.0 / m.clip.frame_rate));
    CHECK(m.stride_m == Approx(1.32).margin(0.02));
    CHECK(m.cycle_s == Approx(1.32 / 1.3).margin(0.01));
}

TEST_CASE("walk: continuous, above the floor, deterministic, bad parameters refused", "[procedural]") {
    for (const WalkParams& p : sample_walks()) {
        const WalkMotion m = generate_walk(p);
        const Continuity c = continuity(m.clip);
        INFO("speed " << p.speed_m_s << " turn " << p.turn_deg << ": rotation step " << c.max_rotation_step_deg
                      << " deg, channel step " << c.max_channel_step_deg << " deg, root step " << c.max_root_step_cm << " cm");
        CHECK(c.max_rotation_step_deg < 20.0);  // no jumps; the swing knee is faster than a human's (≤ 16.4 deg/frame at 1.8 m/s)
        CHECK(c.max_channel_step_deg < 20.0);
        CHECK(c.max_root_step_cm < 100.0 * p.speed_m_s / m.clip.frame_rate * 1.3);
        GlobalPose pose;
        for (std::size_t f = 0; f < m.clip.frame_count(); ++f) {
            forward_kinematics(*m.clip.skeleton, m.clip.frame(f), pose);
            for (const Vec3& q : pose.positions) REQUIRE(q.y() > -0.5);
            // Head stays high: no collapsing crouch.
            REQUIRE(pose.positions[*m.clip.skeleton->find("Head_end")].y() > 140.0);  // measured ≥ 144.5 cm at 1.8 m/s: fast strides lower the pelvis
        }
    }
    const WalkMotion a = generate_walk({1.2, 10.0, 0.0}), b = generate_walk({1.2, 10.0, 0.0});
    CHECK(a.clip.channels == b.clip.channels);
    CHECK_THROWS_AS(generate_walk({0.1, 0.0, 0.0}), InvalidArgument);
    CHECK_THROWS_AS(generate_walk({1.0, 400.0, 0.0}), InvalidArgument);
    CHECK_THROWS_AS(generate_walk({1.0, 0.0, 3.0}), InvalidArgument);
    WalkOptions o;
    o.cycles = 0;
    CHECK_THROWS_AS(generate_walk({1.0, 0.0, 0.0}, o), InvalidArgument);
}

TEST_CASE("walk: BVH written and read back measures the same", "[procedural]") {
    const WalkMotion m = generate_walk({1.5, -40.0, 0.0});
    std::ostringstream text;
    write_bvh(text, m.clip);
    const Clip back = parse_bvh(text.str(), "walk.bvh");
    REQUIRE(back.skeleton->same_structure(*m.clip.skeleton));
    CHECK((back.channels - m.clip.channels).cwiseAbs().maxCoeff() < 1e-5);
    const std::vector<ParameterExtractor> ex = {ParameterExtractor::parse("speed"), ParameterExtractor::parse("turn")};
    const VecX v = extract_parameters(back, 0, back.frame_count(), ex);
    CHECK(v[0] == Approx(150.0).margin(1e-3));
    CHECK(v[1] == Approx(-40.0 * kPi / 180.0).margin(1e-6));
}
