// The built-in humanoid skeleton and the analytic two-bone IK.
#include <catch2/catch.hpp>

#include <random>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/procedural/two_bone_ik.hpp"

using namespace mocapdb;
using namespace mocapdb::procedural;

TEST_CASE("humanoid: a valid skeleton, 170 cm tall, Y up, facing +Z, with feet the detector finds", "[procedural]") {
    const auto s = humanoid_skeleton();
    REQUIRE(s);
    CHECK(s->forward().isApprox(Vec3::UnitZ()));
    CHECK(s->joint(0).name == "Hips");
    CHECK(s->joint(0).channels.size() == 6);
    std::size_t joints = 0, ends = 0;
    for (const Joint& j : s->joints()) {
        if (j.end_site) {
            ++ends;
            CHECK(j.name == s->joint(static_cast<std::size_t>(j.parent)).name + "_end");
        } else {
            ++joints;
        }
    }
    CHECK(joints == 22);  // hips, 3 spine, neck, head, 2 × (clavicle, arm, forearm, hand), 2 × (upleg, leg, foot, toe)
    CHECK(ends == 5);     // head, 2 hands, 2 toes
    CHECK(s->channel_count() == 6 + 3 * (joints - 1));
    CHECK(default_feet(*s) == humanoid_feet());

    // Rest pose: all channels zero.
    std::vector<double> row(s->channel_count(), 0.0);
    row[1] = 95.0;  // Yposition: the hips stand 95 cm above the floor
    GlobalPose pose;
    forward_kinematics(*s, row.data(), pose);
    const auto at = [&](const char* name) { return pose.positions[*s->find(name)]; };
    double lowest = 1e9, highest = -1e9;
    for (const Vec3& p : pose.positions) lowest = std::min(lowest, p.y()), highest = std::max(highest, p.y());
    INFO("rest height " << highest - lowest << " cm, lowest point " << lowest);
    CHECK(highest - lowest == Approx(170.0).margin(1.0));
    CHECK(at("Head_end").y() == Approx(170.0).margin(0.5));
    CHECK(lowest >= 0.0);
    CHECK(lowest <= 1.0);
    // Left is +X when facing +Z; arms along ±X; toes point forward; proportions.
    CHECK(at("LeftHand_end").x() > 80.0);
    CHECK(at("RightHand_end").x() < -80.0);
    CHECK((at("LeftHand_end") - at("RightHand_end")).norm() == Approx(176.0).margin(8.0));  // arm span ≈ height
    CHECK(at("LeftToeBase_end").z() > at("LeftFoot").z() + 15.0);
    CHECK(at("LeftUpLeg").y() == Approx(91.0));
    CHECK(at("LeftArm").y() == Approx(140.0));
}

TEST_CASE("two-bone IK: the end lands on reachable targets, bones keep their lengths, the bend follows the pole",
          "[procedural]") {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double l1 = 28.0, l2 = 25.0;
    int reachable = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 root(u(rng) * 50, u(rng) * 50, u(rng) * 50);
        const Vec3 target = root + Vec3(u(rng), u(rng), u(rng)) * 40.0;
        const Vec3 pole(u(rng), u(rng), u(rng));
        if ((target - root).norm() < 1e-3) continue;
        const TwoBoneSolution s = solve_two_bone(root, l1, l2, target, pole);
        REQUIRE((s.middle - root).norm() == Approx(l1).epsilon(1e-12));
        REQUIRE((s.end - s.middle).norm() == Approx(l2).epsilon(1e-12));
        const double d = (target - root).norm();
        if (d > std::abs(l1 - l2) + 1e-6 && d < l1 + l2 - 1e-6) {
            ++reachable;
            REQUIRE(s.reached);
            REQUIRE((s.end - target).norm() < 1e-9);
            // The middle joint lies on the pole's side of the root → target line.
            const Vec3 n = (target - root).normalized();
            const Vec3 off = s.middle - root - (s.middle - root).dot(n) * n;
            const Vec3 pole_perp = pole - pole.dot(n) * n;
            if (pole_perp.norm() > 1e-3) REQUIRE(off.dot(pole_perp) > 0.0);
            REQUIRE(s.bend > 0.0);
        } else {
            REQUIRE_FALSE(s.reached);
            REQUIRE((s.end - root).normalized().dot((target - root).normalized()) == Approx(1.0));
        }
    }
    CHECK(reachable > 1000);
    // Limited extension keeps the chain bent.
    const TwoBoneSolution far = solve_two_bone(Vec3::Zero(), l1, l2, Vec3(100, 0, 0), Vec3(0, -1, 0), 0.99);
    CHECK_FALSE(far.reached);
    CHECK(far.end.x() == Approx(0.99 * (l1 + l2)));
    CHECK(far.middle.y() < 0.0);
    CHECK_THROWS_AS(solve_two_bone(Vec3::Zero(), 0.0, l2, Vec3(1, 0, 0), Vec3(0, 1, 0)), InvalidArgument);
    CHECK_THROWS_AS(solve_two_bone(Vec3::Zero(), l1, l2, Vec3::Zero(), Vec3(0, 1, 0)), InvalidArgument);
}

TEST_CASE("frame_rotation maps the rest frame onto the given one", "[procedural]") {
    const Vec3 d0(-1, 0, 0), h0(0, 1, 0);
    const Vec3 d = Vec3(1, 2, 3).normalized();
    const Vec3 h = d.cross(Vec3(0, 0, 1)).normalized();
    const Quat q = frame_rotation(d0, h0, d, h);
    CHECK((q * d0 - d).norm() < 1e-12);
    CHECK((q * h0 - h).norm() < 1e-12);
}
