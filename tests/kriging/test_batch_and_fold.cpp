// The batch path (gamma block + one matrix product per block of queries) and the folded predictor
// (sample values folded into the operator, kriging_predictor.hpp) against the per-query weights.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "random_points.hpp"
#include "mocapdb/kriging/kriging_predictor.hpp"

using namespace mocapdb::kriging;
using mocapdb::kriging::test::uniform;

namespace {

// Every code path of gamma_of_squared: spherical, p = 2, 1, 1.5, 0.5 and general exponents, with and
// without a nugget.
std::vector<VariogramModel> models() {
    return {VariogramModel::spherical(0.0, 1.0, 0.8), VariogramModel::spherical(0.05, 1.0, 0.6),
            VariogramModel::stable(2.0, 0.01, 1.0, 0.5), VariogramModel::stable(1.0, 0.0, 2.0, 0.7),
            VariogramModel::stable(1.5, 0.01, 1.0, 0.5), VariogramModel::stable(0.5, 0.1, 1.0, 0.4),
            VariogramModel::stable(1.4, 0.01, 1.0, 0.5), VariogramModel::stable(0.2, 0.0, 1.0, 0.9),
            VariogramModel::stable(1.8, 0.02, 3.0, 0.3)};
}

std::vector<KrigingOptions> options() {
    std::vector<KrigingOptions> v(3);
    v[0].trend = TrendKind::None;
    v[1].trend_fit = TrendFit::OLS;
    v[2].trend_fit = TrendFit::GLS;
    return v;
}

// Control points with two exact duplicates (merged) among N = 40 in [0, 1]^4, and queries: random ones
// (more than one block of 256), the samples themselves, and points far outside.
struct Fixture {
    Eigen::MatrixXd points = uniform(40, 4, 11, 0.0, 1.0);
    Eigen::MatrixXd queries;
    Fixture() {
        points.row(7) = points.row(3);
        points.row(30) = points.row(3);
        const Eigen::MatrixXd random = uniform(600, 4, 12, -0.2, 1.2);
        const Eigen::MatrixXd far = uniform(5, 4, 13, 5.0, 50.0);
        queries.resize(random.rows() + points.rows() + far.rows(), 4);
        queries << random, points, far;
    }
};

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("Batched weights equal per-query weights", "[kriging][batch]") {
    const Fixture f;
    for (const auto& model : models()) {
        for (const auto& opt : options()) {
            const Kriging k = Kriging::build(f.points, model, opt);
            INFO(model.to_string() << ", trend " << to_string(opt.trend) << " " << to_string(opt.trend_fit));
            const Eigen::MatrixXd wb = k.weights_batch(f.queries);
            REQUIRE(wb.allFinite());
            QueryWorkspace ws;
            Eigen::VectorXd w(k.num_samples());
            double worst = 0.0;
            for (Eigen::Index q = 0; q < f.queries.rows(); ++q) {
                k.weights(f.queries.row(q).transpose(), w, ws);
                worst = std::max(worst, (wb.col(q) - w).cwiseAbs().maxCoeff());
                CHECK(std::abs(w.sum() - 1.0) < 1e-12);
            }
            CHECK(worst < 1e-12);
            // The batch estimate's weights are the same numbers.
            const KrigingBatch est = k.estimate_batch(f.queries.topRows(300));
            CHECK(max_abs(est.weights - wb.leftCols(300)) < 1e-12);
            CHECK(est.reliability.allFinite());
            // Exact interpolation at the samples (merged duplicates share their weight).
            const Eigen::MatrixXd at_samples = wb.middleCols(600, f.points.rows());
            for (Eigen::Index i = 0; i < f.points.rows(); ++i) {
                if (i == 3 || i == 7 || i == 30) {
                    CHECK(std::abs(at_samples(3, i) - 1.0 / 3.0) < 1e-10);
                } else {
                    CHECK(std::abs(at_samples(i, i) - 1.0) < 1e-10);
                }
            }
        }
    }
}

TEST_CASE("Folded predictor equals the blend of the per-query weights", "[kriging][fold]") {
    const Fixture f;
    // Values with different scales per column (R3 = 24 coefficient-like rows).
    Eigen::MatrixXd values = uniform(f.points.rows(), 24, 14, -1.0, 1.0);
    for (Eigen::Index j = 0; j < values.cols(); ++j) values.col(j) *= std::pow(10.0, static_cast<double>(j % 5) - 2.0);
    for (const auto& model : models()) {
        for (const auto& opt : options()) {
            const Kriging k = Kriging::build(f.points, model, opt);
            const KrigingPredictor kp = KrigingPredictor::build(k, values);
            INFO(model.to_string() << ", trend " << to_string(opt.trend) << " " << to_string(opt.trend_fit));
            REQUIRE(kp.output_size() == 24);
            REQUIRE(kp.num_samples() == 40);
            const Eigen::MatrixXd unfolded = values.transpose() * k.weights_batch(f.queries);  // 24 by Q
            const Eigen::MatrixXd batch = kp.predict_batch(f.queries);
            QueryWorkspace ws;
            Eigen::VectorXd s(24);
            for (Eigen::Index q = 0; q < f.queries.rows(); ++q) {
                kp.predict(f.queries.row(q).transpose(), s, ws);
                for (Eigen::Index j = 0; j < 24; ++j) {
                    // Relative to the column's scale (the size of the values blended).
                    const double scale = values.col(j).cwiseAbs().maxCoeff();
                    CHECK(std::abs(s(j) - unfolded(j, q)) <= 1e-12 * scale);
                    CHECK(std::abs(batch(j, q) - s(j)) <= 1e-12 * scale);
                }
            }
            // Exact at the samples (a merged duplicate gets the mean of its group).
            for (Eigen::Index i = 0; i < f.points.rows(); ++i) {
                kp.predict(f.points.row(i).transpose(), s, ws);
                const Eigen::VectorXd expect =
                    (i == 3 || i == 7 || i == 30)
                        ? Eigen::VectorXd((values.row(3) + values.row(7) + values.row(30)).transpose() / 3.0)
                        : Eigen::VectorXd(values.row(i).transpose());
                CHECK((s - expect).cwiseAbs().maxCoeff() <= 1e-10 * max_abs(values));
            }
        }
    }
}

TEST_CASE("Folded predictor rejects bad shapes", "[kriging][fold][errors]") {
    const Fixture f;
    const Kriging k = Kriging::build(f.points, VariogramModel::stable(1.2, 0.0, 1.0, 0.5));
    CHECK_THROWS_AS(KrigingPredictor::build(k, Eigen::MatrixXd::Ones(39, 3)), mocapdb::InvalidArgument);
    Eigen::MatrixXd bad = Eigen::MatrixXd::Ones(40, 3);
    bad(2, 1) = std::nan("");
    CHECK_THROWS_AS(KrigingPredictor::build(k, bad), mocapdb::InvalidArgument);
    CHECK_THROWS_AS(KrigingPredictor::build(Kriging(), Eigen::MatrixXd::Ones(1, 1)), mocapdb::InvalidArgument);
    const KrigingPredictor kp = KrigingPredictor::build(k, Eigen::MatrixXd::Ones(40, 3));
    QueryWorkspace ws;
    Eigen::VectorXd out(3);
    CHECK_THROWS_AS(kp.predict(Eigen::VectorXd::Zero(3), out, ws), mocapdb::InvalidArgument);
    Eigen::VectorXd wrong(2);
    CHECK_THROWS_AS(kp.predict(Eigen::VectorXd::Zero(4), wrong, ws), mocapdb::InvalidArgument);
    // Constant values are predicted as that constant everywhere (partition of unity, folded).
    kp.predict(Eigen::VectorXd::Constant(4, 3.0), out, ws);
    CHECK((out.array() - 1.0).abs().maxCoeff() < 1e-12);
}
