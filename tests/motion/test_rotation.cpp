#include <catch2/catch.hpp>
#include <random>

#include "mocapdb/motion/rotation.hpp"

using namespace mocapdb;

namespace {
const EulerOrder kOrders[] = {EulerOrder::XYZ, EulerOrder::XZY, EulerOrder::YXZ,
                              EulerOrder::YZX, EulerOrder::ZXY, EulerOrder::ZYX};

double matrix_distance(const Mat3& a, const Mat3& b) { return (a - b).cwiseAbs().maxCoeff(); }
}  // namespace

TEST_CASE("elemental rotations are right-handed", "[rotation]") {
    CHECK((axis_rotation(Axis::Z, kPi / 2) * Vec3::UnitX() - Vec3::UnitY()).norm() < 1e-15);
    CHECK((axis_rotation(Axis::X, kPi / 2) * Vec3::UnitY() - Vec3::UnitZ()).norm() < 1e-15);
    CHECK((axis_rotation(Axis::Y, kPi / 2) * Vec3::UnitZ() - Vec3::UnitX()).norm() < 1e-15);
}

TEST_CASE("Euler order names and composition follow BVH (first listed is outermost)", "[rotation]") {
    for (EulerOrder o : kOrders) CHECK(euler_order_from_string(to_string(o)) == o);
    CHECK(euler_order_from_string("zxy") == EulerOrder::ZXY);
    CHECK_FALSE(euler_order_from_string("XXY"));
    CHECK_FALSE(euler_order_from_string("XYQ"));
    CHECK_FALSE(euler_order_from_string("XY"));
    const Vec3 a(0.3, -0.7, 1.1);
    const Mat3 expected = axis_rotation(Axis::Z, a[0]) * axis_rotation(Axis::X, a[1]) * axis_rotation(Axis::Y, a[2]);
    CHECK(matrix_distance(euler_to_matrix(a, EulerOrder::ZXY), expected) < 1e-15);
}

TEST_CASE("matrix -> Euler -> matrix is exact for all six orders", "[rotation]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(-kPi, kPi);
    for (EulerOrder o : kOrders) {
        for (int i = 0; i < 2000; ++i) {
            const Vec3 a(angle(rng), angle(rng) / 2, angle(rng));
            const Mat3 r = euler_to_matrix(a, o);
            const Vec3 back = matrix_to_euler(r, o);
            INFO(to_string(o) << " angles " << a.transpose() << " back " << back.transpose());
            REQUIRE(matrix_distance(euler_to_matrix(back, o), r) < 1e-12);
            REQUIRE((back - a).cwiseAbs().maxCoeff() < 1e-9);  // principal range: unique
            REQUIRE(angle_between(euler_to_quat(a, o), Quat(r)) < 1e-12);
        }
    }
}

TEST_CASE("Euler decomposition survives gimbal lock", "[rotation]") {
    for (EulerOrder o : kOrders) {
        for (double b : {kPi / 2, -kPi / 2}) {
            const Vec3 a(0.4, b, -0.9);
            const Mat3 r = euler_to_matrix(a, o);
            const Vec3 back = matrix_to_euler(r, o);
            INFO(to_string(o));
            CHECK(matrix_distance(euler_to_matrix(back, o), r) < 1e-9);
        }
    }
}

TEST_CASE("Euler solution nearest a neighbour removes 360-degree jumps and flips", "[rotation]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> angle(-3 * kPi, 3 * kPi);
    std::uniform_real_distribution<double> middle(-1.4, 1.4);
    std::uniform_real_distribution<double> noise(-0.05, 0.05);
    for (EulerOrder o : kOrders) {
        for (int i = 0; i < 1000; ++i) {
            // Any triple (even far outside the principal range) is recovered from a nearby neighbour.
            const Vec3 a(angle(rng), middle(rng) + 2 * kPi * std::round(angle(rng) / (2 * kPi)), angle(rng));
            const Vec3 near = a + Vec3(noise(rng), noise(rng), noise(rng));
            const Vec3 back = matrix_to_euler_near(euler_to_matrix(a, o), o, near);
            INFO(to_string(o) << " a " << a.transpose() << " back " << back.transpose());
            REQUIRE((back - a).cwiseAbs().maxCoeff() < 1e-9);
        }
        // The second solution family (a+π, π−b, c+π) is chosen when the neighbour is there.
        const Vec3 a(0.2, 0.3, -0.4);
        const Vec3 other(a[0] + kPi, kPi - a[1], a[2] + kPi);
        const Vec3 back = matrix_to_euler_near(euler_to_matrix(a, o), o, other);
        CHECK((back - other).cwiseAbs().maxCoeff() < 1e-9);
    }
}

TEST_CASE("exp and log maps are inverse and the log follows its neighbour", "[rotation]") {
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0.0, 1.0);
    for (int i = 0; i < 2000; ++i) {
        Vec3 v(n(rng), n(rng), n(rng));
        v *= (kPi * 0.999) / std::max(1.0, v.norm());  // principal range
        REQUIRE((log_map(exp_map(v)) - v).norm() < 1e-12);
    }
    CHECK(log_map(Quat::Identity()).norm() == 0.0);
    CHECK((log_map(exp_map(Vec3(1e-14, 0, 0))) - Vec3(1e-14, 0, 0)).norm() < 1e-28);

    // A rotation spinning about a fixed axis through 0..4π: the continuous track is angle·axis.
    const Vec3 axis = Vec3(1, 2, -0.5).normalized();
    Vec3 prev = Vec3::Zero();
    for (int k = 0; k <= 400; ++k) {
        const double angle = 4 * kPi * k / 400.0;
        const Vec3 v = log_map_near(Quat(Eigen::AngleAxisd(angle, axis)), prev);
        INFO("angle " << angle << " v " << v.transpose());
        REQUIRE((v - angle * axis).norm() < 1e-9);
        prev = v;
    }
    // The identity next to a large neighbour: the equivalent 2π·u nearest it lies along the neighbour.
    const Vec3 near = 2 * kPi * axis + Vec3(0.01, 0, 0);
    CHECK((log_map_near(Quat::Identity(), near) - 2 * kPi * near.normalized()).norm() < 1e-12);
}

TEST_CASE("angle_between measures the relative rotation", "[rotation]") {
    const Quat a(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
    const Quat b(Eigen::AngleAxisd(1.0, Vec3::UnitY()));
    CHECK(angle_between(a, b) == Approx(0.7).margin(1e-14));
    Quat neg = b;
    neg.coeffs() = -neg.coeffs();
    CHECK(angle_between(a, neg) == Approx(0.7).margin(1e-14));
}

TEST_CASE("swing-twist log is exact and follows a root spinning through many turns", "[rotation]") {
    std::mt19937 rng(5);
    std::normal_distribution<double> n(0.0, 1.0);
    for (int i = 0; i < 2000; ++i) {
        const Quat q = Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
        const Vec3 v = swing_twist_log(q, Vec3::Zero());
        REQUIRE(angle_between(swing_twist_exp(v), q) < 1e-12);
        REQUIRE(std::abs(v.y()) <= kPi + 1e-12);
    }
    // Three full turns about +Y with a wobbling 0.02–0.3 rad tilt: every step stays small, the twist
    // accumulates to 6π, and a plain exponential map would have jumped at each 2π shell.
    Vec3 prev = swing_twist_log(Quat::Identity(), Vec3::Zero());
    double worst_step = 0;
    const int steps = 3000;
    for (int k = 1; k <= steps; ++k) {
        const double yaw = 6 * kPi * k / steps;
        const double tilt = 0.02 + 0.28 * std::abs(std::sin(0.01 * k));
        const Quat q = Quat(Eigen::AngleAxisd(tilt, Vec3(std::cos(0.003 * k), 0, std::sin(0.003 * k)))) *
                       Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY()));
        const Vec3 v = swing_twist_log(q, prev);
        REQUIRE(angle_between(swing_twist_exp(v), q) < 1e-12);
        worst_step = std::max(worst_step, (v - prev).norm());
        prev = v;
    }
    CHECK(worst_step < 0.05);
    CHECK(prev.y() == Approx(6 * kPi).margin(1e-9));
}
