// Interpolation and synthesis metrics against values computed by hand.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/gp_metrics.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;

TEST_CASE("MSE, SMSE and MSLL by hand", "[gp][metrics]") {
    MatX truth(2, 3), mean(2, 3), var(2, 3);
    truth << 1, 2, 3, 0, 0, 4;
    mean << 1.5, 2, 2, 1, 0, 4;
    var << 0.5, 0.5, 0.5, 1, 2, 1;
    const VecX tm = (VecX(2) << 2, 1).finished(), tv = (VecX(2) << 1, 4).finished();
    const InterpolationScores s = interpolation_scores(truth, mean, var, tm, tv);
    // errors²: 0.25 0 1 | 1 0 0 → MSE 2.25/6
    CHECK(s.mse == Approx(2.25 / 6));
    // SMSE: output 0: mean err² 1.25/3 over var(1,2,3) = 2/3; output 1: 1/3 over var(0,0,4) = 32/9
    REQUIRE(s.smse);
    CHECK(*s.smse == Approx(0.5 * ((1.25 / 3) / (2.0 / 3) + (1.0 / 3) / (32.0 / 9))));
    double sll = 0;
    for (int i = 0; i < 2; ++i)
        for (int t = 0; t < 3; ++t) {
            const double e = truth(i, t) - mean(i, t), dv = truth(i, t) - tm[i];
            sll += 0.5 * std::log(2 * kPi * var(i, t)) + e * e / (2 * var(i, t)) - 0.5 * std::log(2 * kPi * tv[i]) -
                   dv * dv / (2 * tv[i]);
        }
    CHECK(s.msll == Approx(sll / 6));
    CHECK(s.points == 6);
    // A perfect, confident prediction has a very negative MSLL; predicting the training moments gives 0.
    const InterpolationScores trivial =
        interpolation_scores(truth, tm.replicate(1, 3), tv.replicate(1, 3), tm, tv);
    CHECK(trivial.msll == Approx(0.0).margin(1e-12));
    CHECK_THROWS_AS(interpolation_scores(truth, mean, -var, tm, tv), InvalidArgument);
    CHECK_THROWS_AS(interpolation_scores(truth.leftCols(1), mean.leftCols(1), var.leftCols(1), tm, tv), InvalidArgument);
}

TEST_CASE("cross-correlation, Pearson, MCC and MLC", "[gp][metrics]") {
    const VecX a = (VecX(3) << 1, 2, 3).finished(), b = (VecX(3) << 0, 1, 0).finished();
    // Σ a[m] b[m+lag]: lag −1: a1 b0 + a2 b1 = 3; lag 0: 2; lag 1: a0 b1 = 1 → max 3
    CHECK(max_cross_correlation(a, b) == Approx(3.0));
    CHECK(pearson(a, a).value() == Approx(1.0));
    CHECK(pearson(a, -a).value() == Approx(-1.0));
    // A motion against itself: MLC 1; MCC = mean over outputs of Σ x² with x normalized to [0, 1].
    MatX m(2, 5);
    m << 0, 1, 2, 3, 4, 5, 3, 1, 3, 5;
    CHECK(mean_linear_correlation(m, m).value() == Approx(1.0));
    const double e0 = 0 + 1.0 / 16 + 4.0 / 16 + 9.0 / 16 + 1, e1 = 1 + 0.25 + 0 + 0.25 + 1;
    CHECK(mean_cross_correlation(m, m) == Approx(0.5 * (e0 + e1)));
    // Scale and offset do not matter (normalization), a time shift does not reduce MCC much.
    CHECK(mean_cross_correlation(3.0 * m.array() + 7.0, m) == Approx(mean_cross_correlation(m, m)));
    CHECK(mean_linear_correlation(-m, m).value() == Approx(-1.0));
    const SynthesisScores s = synthesis_scores({m, -m}, {m});
    REQUIRE(s.mlc.size() == 1);
    REQUIRE(s.mlc[0]);
    CHECK(s.mlc[0]->mean == Approx(0.0).margin(1e-12));
    CHECK(s.mlc[0]->std == Approx(1.0));
    const MeanStd ms = mean_std({1, 2, 3, 4});
    CHECK(ms.mean == 2.5);
    CHECK(ms.std == Approx(std::sqrt(1.25)));
}

TEST_CASE("scores undefined for their input are empty, not NaN", "[gp][metrics]") {
    // SMSE divides by the variance of each output's test values: constant outputs are skipped, and with
    // every output constant there is no SMSE (MSE and MSLL still exist).
    MatX truth(2, 3), mean(2, 3);
    truth << 1, 1, 1, 2, 4, 6;
    mean << 1, 2, 1, 2, 5, 6;
    const MatX var = MatX::Constant(2, 3, 0.5);
    const VecX tm = VecX::Zero(2), tv = VecX::Ones(2);
    const InterpolationScores one = interpolation_scores(truth, mean, var, tm, tv);
    REQUIRE(one.smse);
    CHECK(*one.smse == Approx((1.0 / 3) / (8.0 / 3)));  // output 1 alone: err² 0 1 0 over var(2, 4, 6)
    truth.row(1).setConstant(3.0);
    const InterpolationScores none = interpolation_scores(truth, mean, var, tm, tv);
    CHECK_FALSE(none.smse.has_value());
    CHECK(std::isfinite(none.mse));
    CHECK(std::isfinite(none.msll));

    // Pearson of a constant sequence (either side) has no value.
    const VecX a = (VecX(3) << 1, 2, 4).finished();
    CHECK_FALSE(pearson(a, VecX::Constant(3, 2.0)).has_value());
    CHECK_FALSE(pearson(VecX::Constant(3, -1.0), a).has_value());
    CHECK(pearson(a, 2.0 * a.array() + 1.0).value() == Approx(1.0));

    // MLC skips outputs constant in either motion; with all of them constant it has no value, and the
    // summary over generated motions of a real one is empty when one MLC is.
    MatX m(2, 4), flat(2, 4);
    m << 0, 1, 2, 3, 3, 1, 0, 2;
    flat << 1, 1, 1, 1, 0, 0, 0, 0;
    MatX half = m;
    half.row(0).setConstant(5.0);
    CHECK(mean_linear_correlation(half, m).value() == Approx(1.0));  // row 1 alone
    CHECK_FALSE(mean_linear_correlation(flat, m).has_value());
    const SynthesisScores s = synthesis_scores({m, flat}, {m});
    REQUIRE(s.mlc.size() == 1);
    CHECK_FALSE(s.mlc[0].has_value());
    REQUIRE(s.mcc.size() == 1);  // MCC is defined for a constant motion

    // mean_std_of_all: every value present gives mean_std, any missing gives nothing.
    const std::optional<MeanStd> all = mean_std_of_all({1.0, 3.0});
    REQUIRE(all);
    CHECK(all->mean == 2.0);
    CHECK(all->std == 1.0);
    CHECK_FALSE(mean_std_of_all({1.0, std::nullopt, 3.0}).has_value());
}
