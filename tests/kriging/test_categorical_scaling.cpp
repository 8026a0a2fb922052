// Categorical axes of ControlScaling (kriging/trend.hpp): a level index becomes indicator coordinates,
// never standardized; levels differ by a fixed distance of 2; the linear trend over the embedding is a
// mean per level with shared numeric slopes; a coordinate that is not a level index is refused.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/trend.hpp"

using namespace mocapdb;
using namespace mocapdb::kriging;

TEST_CASE("kriging: a categorical axis embeds as level indicators 2 apart", "[kriging]") {
    Eigen::MatrixXd c(6, 2);  // (speed, level of 3)
    c << 100, 0, 120, 0, 300, 1, 320, 1, 200, 2, 210, 2;
    const ControlScaling s = ControlScaling::from_data(c, Eigen::VectorXd(), {0, 3});
    CHECK(s.has_categorical_axis());
    CHECK(s.offset(1) == 0.0);  // the level index is not centred ...
    CHECK(s.scale(1) == 1.0);   // ... nor scaled
    CHECK(s.scale(0) > 1.0);    // the numeric axis is
    REQUIRE(s.embedded_dimension() == 1 + 3);
    const Eigen::MatrixXd x = s.apply(c);
    REQUIRE(x.cols() == 4);
    // Same level: only the numeric axis separates them; different levels: 2 more along the indicators.
    CHECK((x.row(0) - x.row(1)).norm() == Approx(std::abs(x(0, 0) - x(1, 0))));
    CHECK((x.row(0).tail(3) - x.row(2).tail(3)).norm() == Approx(2.0));
    CHECK((x.row(2).tail(3) - x.row(4).tail(3)).norm() == Approx(2.0));
    // The point path gives the batch's coordinates.
    Eigen::VectorXd p;
    s.apply_point(c.row(3).transpose(), p);
    CHECK((p.transpose() - x.row(3)).norm() == Approx(0.0).margin(1e-15));

    // Not a level index: refused (levels are never interpolated).
    Eigen::VectorXd half(2);
    half << 150, 0.5;
    CHECK_THROWS_AS(s.apply_point(half, p), InvalidArgument);
    half << 150, 3;
    CHECK_THROWS_AS(s.apply_point(half, p), InvalidArgument);
    // A categorical axis cannot be periodic, nor have one level.
    Eigen::VectorXd periods(2);
    periods << 0, 6.0;
    CHECK_THROWS_AS(ControlScaling::from_data(c, periods, {0, 3}).apply(c), InvalidArgument);
    CHECK_THROWS_AS(ControlScaling::from_data(c, Eigen::VectorXd(), {0, 1}).apply(c), InvalidArgument);
}

TEST_CASE("kriging: the linear trend over a categorical embedding is a mean per level", "[kriging]") {
    // y = level mean + 0.5 speed, the levels' means far apart: the OLS trend reproduces it exactly
    // (residuals 0), which one hyperplane in the raw level index could not (the means are not linear in it).
    Eigen::MatrixXd c(9, 2);
    c << 100, 0, 120, 0, 140, 0, 300, 1, 320, 1, 340, 1, 200, 2, 210, 2, 230, 2;
    const double mean[3] = {10.0, -40.0, 25.0};
    Eigen::VectorXd y(9);
    for (Eigen::Index i = 0; i < 9; ++i) y(i) = mean[static_cast<int>(c(i, 1))] + 0.5 * c(i, 0);
    const ControlScaling s = ControlScaling::from_data(c, Eigen::VectorXd(), {0, 3});
    const TrendBasis basis = TrendBasis::build(s.apply(c), TrendKind::Linear);
    CHECK(basis.rank() == 3);  // the numeric axis + 2 of the 3 indicators (they sum to a constant)
    const OlsTrend fit = fit_trend_ols(basis, y);
    CHECK(fit.residuals.norm() == Approx(0.0).margin(1e-9));

    const TrendBasis raw = TrendBasis::build(ControlScaling::from_data(c).apply(c), TrendKind::Linear);
    CHECK(fit_trend_ols(raw, y).residuals.norm() > 10.0);
}
