// The predictor synthesis blends the samples with (synthesis/predictor_choice.hpp): the cross-validated
// choice scores every candidate and picks the lowest, averages it with those within one paired standard
// error, keeps a curved response off the trend, leaves twins out with their sample, chooses on a bounded
// subset of a big set; a model built with a predictor blends with that interpolator's weights (poses and
// timing; the average with the mean of its members') and keeps the kriging kernel's rho.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/rbf.hpp"
#include "mocapdb/kriging/trend_interpolator.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"
#include "shared_clips.hpp"

using namespace mocapdb;
using namespace mocapdb::synthesis;

namespace {

// N points on a line in [0, 3] and S values per point: a smooth curve plus i.i.d. noise of `noise` SD.
struct CurveData {
    MatX xc;
    MatX values;
};

CurveData curve(Eigen::Index n, double noise, unsigned seed) {
    CurveData d;
    d.xc.resize(n, 1);
    d.values.resize(n, 4);
    std::mt19937 gen(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    for (Eigen::Index i = 0; i < n; ++i) {
        const double x = 3.0 * static_cast<double>(i) / static_cast<double>(n - 1);
        d.xc(i, 0) = x;
        for (Eigen::Index s = 0; s < 4; ++s)
            d.values(i, s) = std::sin(2.0 * x + static_cast<double>(s)) * 10.0 + noise * g(gen);
    }
    d.xc = kriging::ControlScaling::from_data(d.xc).apply(d.xc);
    return d;
}

PredictorChoice choose(const CurveData& d, const std::vector<std::vector<std::size_t>>& twins = {},
                       PredictorChoiceOptions o = {}) {
    const SynthesisOptions so;
    const KernelFit fit = fit_coefficient_kernel(d.xc, d.values, so, "test");
    return choose_predictor(d.xc, d.values, fit.variogram, so.kriging, twins, o);
}

double cv_of(const PredictorChoice& c, Predictor p) {
    for (const PredictorScore& s : c.scores)
        if (s.predictor == p) return s.cv_rms;
    FAIL("no score for " << to_string(p));
    return 0.0;
}

}  // namespace

TEST_CASE("predictor choice: every candidate scored, the lowest chosen, a curve is not left to the trend",
          "[synthesis][predictor]") {
    const CurveData d = curve(25, 0.0, 1);
    PredictorChoiceOptions alone;
    alone.average_within_se = 0.0;  // the lowest alone
    const PredictorChoice c = choose(d, {}, alone);
    REQUIRE(c.scores.size() == all_predictors().size());
    CHECK(c.folds == 15);
    CHECK(c.samples == 25);
    for (const PredictorScore& s : c.scores) CHECK(cv_of(c, c.chosen) <= s.cv_rms);
    CHECK(c.chosen != Predictor::Trend);
    CHECK(cv_of(c, Predictor::Trend) > 3.0 * cv_of(c, c.chosen));  // a sine over 6 rad is far from a line
    CHECK_THAT(describe(c), Catch::Contains("15 folds of 25 samples"));
    CHECK(c.members() == std::vector<Predictor>{c.chosen});
    // Deterministic: the same inputs give the same choice and scores.
    const PredictorChoice again = choose(d);
    CHECK(again.chosen == c.chosen);
    CHECK(cv_of(again, Predictor::Rbf) == cv_of(c, Predictor::Rbf));
}

TEST_CASE("predictor choice: candidates within one paired standard error of the lowest are averaged",
          "[synthesis][predictor]") {
    const CurveData d = curve(25, 0.3, 5);
    const PredictorChoice c = choose(d);
    std::size_t lowest = 0;
    for (std::size_t p = 0; p < c.scores.size(); ++p)
        if (c.scores[p].cv_rms < c.scores[lowest].cv_rms) lowest = p;
    CHECK(c.scores[lowest].cv_se == 0.0);
    double weights = 0.0;
    for (const PredictorScore& s : c.scores) {
        INFO(to_string(s.predictor) << " cv " << s.cv_rms << " se " << s.cv_se << " weight " << s.weight);
        CHECK(s.cv_se >= 0.0);
        // Averaged exactly when within one SE of the lowest (the lowest always is).
        const bool within = s.cv_rms - c.scores[lowest].cv_rms <= s.cv_se;
        CHECK((s.weight > 0.0) == within);
        weights += s.weight;
    }
    CHECK(weights == Approx(1.0));
    CHECK((c.chosen == Predictor::Average) == (c.members().size() >= 2));
    CHECK(c.scores[2].weight == 0.0);  // the trend misses the sine by far more than its SE
    // Any allowance that covers every excess averages all three, equally; none keeps the lowest alone.
    PredictorChoiceOptions all;
    all.average_within_se = 1e9;
    const PredictorChoice every = choose(d, {}, all);
    CHECK(every.chosen == Predictor::Average);
    CHECK(every.members() == all_predictors());
    for (const PredictorScore& s : every.scores) CHECK(s.weight == Approx(1.0 / 3.0));
    CHECK_THAT(describe(every), Catch::StartsWith("average of kriging, rbf, trend (cv "));
    PredictorChoiceOptions none;
    none.average_within_se = 0.0;
    const PredictorChoice one = choose(d, {}, none);
    CHECK(one.chosen == all_predictors()[lowest]);
    CHECK(one.members().size() == 1);
    none.average_within_se = -1.0;
    CHECK_THROWS_AS(choose(d, {}, none), InvalidArgument);
    none.average_within_se = 0.0;
    none.candidates = {Predictor::Kriging, Predictor::Average};
    CHECK_THROWS_AS(choose(d, {}, none), InvalidArgument);
    // The posture metric drops the root's floor position and heading from every frame.
    MatX rows = MatX::Constant(2, 3 * 7, 1.0);
    const MatX posture = posture_values(rows, 7);
    CHECK(posture.sum() == Approx(2.0 * 3.0 * 4.0));
    CHECK(posture(1, 7 + 4) == 0.0);
    CHECK_THROWS_AS(posture_values(rows, 4), InvalidArgument);
}

TEST_CASE("predictor choice: pure noise about a constant favours the trend over interpolating it",
          "[synthesis][predictor]") {
    CurveData d = curve(30, 0.0, 2);
    std::mt19937 gen(7);
    std::normal_distribution<double> g(0.0, 1.0);
    for (Eigen::Index i = 0; i < d.values.size(); ++i) d.values.data()[i] = g(gen);
    const PredictorChoice c = choose(d);
    CHECK(cv_of(c, Predictor::Trend) < cv_of(c, Predictor::Rbf));  // RBF reproduces the noise of neighbours
    CHECK(c.chosen != Predictor::Rbf);
    CHECK(c.members().front() != Predictor::Rbf);
}

TEST_CASE("predictor choice: a sample's twins leave with it, a big set chooses on a bounded subset",
          "[synthesis][predictor]") {
    // Every sample twice (the same values at the same point, e.g. a clip imported twice).
    const CurveData base = curve(12, 0.5, 3);
    CurveData d;
    d.xc.resize(24, 1);
    d.values.resize(24, 4);
    std::vector<std::vector<std::size_t>> twins(24);
    for (Eigen::Index i = 0; i < 12; ++i) {
        d.xc.row(2 * i) = d.xc.row(2 * i + 1) = base.xc.row(i);
        d.values.row(2 * i) = d.values.row(2 * i + 1) = base.values.row(i);
        twins[static_cast<std::size_t>(2 * i)] = {static_cast<std::size_t>(2 * i + 1)};
        twins[static_cast<std::size_t>(2 * i + 1)] = {static_cast<std::size_t>(2 * i)};
    }
    const PredictorChoice leaked = choose(d);
    const PredictorChoice honest = choose(d, twins);
    // With its twin in training an interpolator reproduces the held-out sample: a leak of the error.
    CHECK(cv_of(leaked, Predictor::Rbf) < 1e-6);
    CHECK(cv_of(honest, Predictor::Rbf) > 0.1);
    CHECK(cv_of(honest, Predictor::Kriging) > cv_of(leaked, Predictor::Kriging));
    CHECK_THROWS_AS(choose(d, std::vector<std::vector<std::size_t>>(3)), InvalidArgument);

    PredictorChoiceOptions small;
    small.max_samples = 10;
    small.folds = 4;
    const PredictorChoice subset = choose(curve(40, 0.1, 4), {}, small);
    CHECK(subset.samples == 10);
    CHECK(subset.folds == 4);
    small.candidates = {Predictor::Kriging, Predictor::Trend};
    const PredictorChoice two = choose(curve(40, 0.1, 4), {}, small);
    REQUIRE(two.scores.size() == 2);
    CHECK(two.chosen != Predictor::Rbf);
    CHECK(two.scores[0].cv_rms == cv_of(subset, Predictor::Kriging));  // the same folds
    PredictorChoiceOptions bad;
    bad.folds = 0;
    CHECK_THROWS_AS(choose(base, {}, bad), InvalidArgument);
}

TEST_CASE("a model built with a predictor blends with its weights, poses and timing, rho stays kriging's",
          "[synthesis][predictor][shared]") {
    const test::Subject16Set w = test::subject16_set({11, 12, 13, 14, 15, 16, 17, 18}, 16);
    const auto skeleton = w.clips.front().skeleton;
    const VecX weight = compression::position_error_weights(*skeleton);
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, weight, {20, 10, 8}, tensor::TuckerMethod::Hosvd);
    const MotionModel kriged(sm, w.aligned, w.set, skeleton, 120.0);
    const MatX xc = kriged.scaling().apply(w.set.parameters);
    const VecX c = 0.5 * (w.set.parameters.row(1) + w.set.parameters.row(4)).transpose();
    VecX cn;
    kriged.scaling().apply_point(c, cn);
    for (const Predictor p : {Predictor::Rbf, Predictor::Trend}) {
        SynthesisOptions o;
        o.predictor = p;
        const MotionModel model(sm, w.aligned, w.set, skeleton, 120.0, o);
        CHECK(model.report().predictor == p);
        VecX expected(8);
        if (p == Predictor::Rbf)
            expected = kriging::RbfInterpolator::build(xc).weights(cn);
        else
            expected = kriging::TrendInterpolator::build(xc).weights(cn);
        Workspace ws;
        VecX got(8), u(model.coefficient_size());
        model.weights(c, got, ws);
        CHECK((got - expected).norm() < 1e-12);
        model.coefficients(c, u, ws);
        CHECK((u - sm.tucker.U[2].transpose() * expected).norm() < 1e-9);
        // The timing blends the samples' increments with the same weights.
        const MatX inc = w.aligned.inverse_warp_increments();  // T - 1 by N
        const Timing tm = model.timing(c);
        const VecX blended = inc * expected;
        REQUIRE(tm.clamped == 0);  // between two samples: no increment hits a clamp
        CHECK((tm.increments - blended).norm() < 1e-9);
        CHECK(model.reliability(c) == kriged.reliability(c));
        // Batched poses agree with single ones.
        BatchWorkspace bws;
        MatX batch(model.dofs(), 1);
        model.poses(c.transpose(), 3.0, batch, bws);
        CHECK((batch.col(0) - model.pose(c, 3.0)).norm() < 1e-9);
    }
    // The average blends with the mean of its members' weights (kriging's own, with the others').
    SynthesisOptions o;
    PredictorChoice choice;
    choice.chosen = Predictor::Average;
    choice.scores = {{Predictor::Kriging, 1.0, 0.0, 0.5}, {Predictor::Rbf, 1.1, 0.2, 0.5}, {Predictor::Trend, 3.0, 0.5, 0.0}};
    use_predictor_choice(choice, o);
    REQUIRE(o.averaged == std::vector<Predictor>{Predictor::Kriging, Predictor::Rbf});
    const MotionModel averaged(sm, w.aligned, w.set, skeleton, 120.0, o);
    CHECK(averaged.report().predictor == Predictor::Average);
    Workspace ws;
    VecX got(8), kriged_w(8);
    averaged.weights(c, got, ws);
    kriged.weights(c, kriged_w, ws);
    const VecX expected = 0.5 * (kriged_w + kriging::RbfInterpolator::build(xc).weights(cn));
    CHECK((got - expected).norm() < 1e-12);
    CHECK(averaged.reliability(c) == kriged.reliability(c));
    BatchWorkspace bws;
    MatX batch(averaged.dofs(), 2);
    averaged.poses(MatX(c.transpose()).replicate(2, 1), 3.0, batch, bws);
    CHECK((batch.col(1) - averaged.pose(c, 3.0)).norm() < 1e-9);
    CHECK((averaged.timing(c).increments - w.aligned.inverse_warp_increments() * expected).norm() < 1e-9);
    o.averaged = {Predictor::Kriging};
    CHECK_THROWS_AS(MotionModel(sm, w.aligned, w.set, skeleton, 120.0, o), InvalidArgument);
    o.averaged = {Predictor::Rbf, Predictor::Rbf};
    CHECK_THROWS_AS(MotionModel(sm, w.aligned, w.set, skeleton, 120.0, o), InvalidArgument);
}
