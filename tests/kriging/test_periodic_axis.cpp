// Periodic control parameters (trend.hpp ControlScaling, issue #15): a bearing's distances are chords on
// a circle, so kriging does not treat 179 and -179 degrees as a full turn apart.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/types.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"

using namespace mocapdb;
using namespace mocapdb::kriging;

TEST_CASE("periodic axis: circular mean and spread, chord distances, c and c + period coincide", "[kriging]") {
    // Bearings in degrees around 0 across the seam, and a linear axis beside them.
    Eigen::MatrixXd c(4, 2);
    c << 350.0, 1.0, 10.0, 2.0, 340.0, 3.0, 20.0, 4.0;
    Eigen::VectorXd periods(2);
    periods << 360.0, 0.0;
    const ControlScaling s = ControlScaling::from_data(c, periods);
    CHECK(std::abs(wrap_to_half_period(s.offset(0), 360.0)) < 1e-9);  // circular mean 0, not 180
    CHECK(s.scale(0) == Approx(std::sqrt((100.0 + 100.0 + 400.0 + 400.0) / 4.0)));
    CHECK(s.scale(1) == Approx(std::sqrt(1.25)));
    REQUIRE(s.embedded_dimension() == 3);
    const Eigen::MatrixXd x = s.apply(c);
    REQUIRE(x.cols() == 3);
    // 350 and 10 degrees are 20 degrees apart (chord ~ 20 / scale), not 340.
    const double d = (x.row(0).head(2) - x.row(1).head(2)).norm();
    const double chord = 360.0 / (kPi * s.scale(0)) * std::sin(kPi * 20.0 / 360.0);
    CHECK(d == Approx(chord).epsilon(1e-12));
    CHECK(d == Approx(20.0 / s.scale(0)).epsilon(0.01));
    // One point, and the same point a period later.
    Eigen::VectorXd p;
    s.apply_point(Eigen::Vector2d(350.0, 1.0), p);
    CHECK((p.transpose() - x.row(0)).norm() < 1e-12);
    Eigen::VectorXd q;
    s.apply_point(Eigen::Vector2d(350.0 + 720.0, 1.0), q);
    CHECK((p - q).norm() < 1e-12);
    CHECK(wrap_to_half_period(190.0, 360.0) == Approx(-170.0));
    CHECK(wrap_to_half_period(-180.0, 360.0) == Approx(-180.0));

    Eigen::VectorXd bad(2);
    bad << -1.0, 0.0;
    CHECK_THROWS_AS(ControlScaling::from_data(c, bad), InvalidArgument);
    CHECK_THROWS_AS(ControlScaling::from_data(c, Eigen::VectorXd::Zero(3)), InvalidArgument);
}

TEST_CASE("periodic axis: kriging across the seam predicts from the neighbours on the other side", "[kriging]") {
    // Twelve bearings over the whole circle, a value smooth on the circle; predict near +-180 degrees.
    const int n = 12;
    Eigen::MatrixXd c(n, 1);
    Eigen::MatrixXd v(n, 1);
    for (int i = 0; i < n; ++i) {
        c(i, 0) = -165.0 + 30.0 * i;  // -165 .. 165
        v(i, 0) = std::cos(c(i, 0) * kPi / 180.0);
    }
    const VariogramModel model = VariogramModel::from_paper_p(1.5, 0.0, 1.0, 2.0);
    const auto predict = [&](const ControlScaling& s, double bearing) {
        const Kriging k = Kriging::build(s.apply(c), model);
        Eigen::VectorXd q;
        s.apply_point(Eigen::VectorXd::Constant(1, bearing), q);
        return k.Interpolator::weights(q).dot(v.col(0));
    };
    const ControlScaling periodic = ControlScaling::from_data(c, Eigen::VectorXd::Constant(1, 360.0));
    const ControlScaling linear = ControlScaling::from_data(c);
    for (const double b : {179.0, -179.0, 180.0}) {
        const double truth = std::cos(b * kPi / 180.0);
        INFO("bearing " << b << ": periodic " << predict(periodic, b) << ", linear " << predict(linear, b) << ", truth " << truth);
        CHECK(std::abs(predict(periodic, b) - truth) < 0.02);
        // A linear axis sees only the samples on one side of the seam and extrapolates.
        CHECK(std::abs(predict(linear, b) - truth) > 2.0 * std::abs(predict(periodic, b) - truth));
    }
    // The periodic prediction is the same a turn later.
    CHECK(predict(periodic, 179.0 + 360.0) == Approx(predict(periodic, 179.0)).margin(1e-9));
}
