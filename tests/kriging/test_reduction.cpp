// Greedy sample reduction (paper 5.2) against a brute-force greedy loop that rebuilds the kriging system
// without each candidate at every step.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/reduction.hpp"

using namespace mocapdb::kriging;

namespace {
Eigen::MatrixXd red_points(Eigen::Index n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ud(0.0, 10.0);
    Eigen::MatrixXd m(n, 2);
    for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = ud(rng);
    return m;
}

Eigen::MatrixXd rows(const Eigen::MatrixXd& m, const std::vector<Eigen::Index>& idx) {
    Eigen::MatrixXd out(static_cast<Eigen::Index>(idx.size()), m.cols());
    for (std::size_t k = 0; k < idx.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = m.row(idx[k]);
    return out;
}
}  // namespace

TEST_CASE("Greedy reduction equals the brute-force greedy loop", "[kriging][reduction]") {
    const Eigen::MatrixXd pts = red_points(30, 31);
    const VariogramModel model = VariogramModel::stable(1.5, 0.0, 1.0, 4.0);
    for (TrendFit tf : {TrendFit::OLS, TrendFit::GLS}) {
        ReductionOptions ro;
        ro.tau = 0.8;
        ro.kriging.trend_fit = tf;
        ro.kriging.reliability = ReliabilityVariance::Paper;  // what reduce_samples uses
        const ReductionResult r = reduce_samples(pts, model, ro);
        // Brute force: at each step rebuild without every candidate and evaluate rho at its point.
        std::vector<Eigen::Index> alive;
        for (Eigen::Index i = 0; i < 30; ++i) alive.push_back(i);
        std::vector<Eigen::Index> order;
        std::vector<double> curve;
        while (alive.size() > 4) {
            double best = -1.0;
            std::size_t best_k = 0;
            for (std::size_t k = 0; k < alive.size(); ++k) {
                std::vector<Eigen::Index> others = alive;
                others.erase(others.begin() + static_cast<std::ptrdiff_t>(k));
                const Kriging kr = Kriging::build(rows(pts, others), model, ro.kriging);
                const double rho = kr.estimate(pts.row(alive[k]).transpose()).reliability;
                if (rho > best) {
                    best = rho;
                    best_k = k;
                }
            }
            curve.push_back(best);
            if (best < ro.tau) break;
            order.push_back(alive[best_k]);
            alive.erase(alive.begin() + static_cast<std::ptrdiff_t>(best_k));
        }
        INFO("fit " << to_string(tf) << ": removed " << r.removed.size() << " brute force " << order.size());
        REQUIRE(r.removed.size() == order.size());
        CHECK(r.removed == order);
        REQUIRE(r.max_reliability.size() == curve.size());
        for (std::size_t k = 0; k < curve.size(); ++k) CHECK(std::abs(r.max_reliability[k] - curve[k]) <= 1e-8);
        CHECK(r.stopped_on_threshold);
        CHECK(r.max_reliability.back() < ro.tau);
        for (double v : r.removed_reliability) CHECK(v >= ro.tau);
        CHECK(r.kept.size() + r.removed.size() == 30);
    }
}

TEST_CASE("Reduction removes duplicates first and respects min_samples", "[kriging][reduction][robustness]") {
    Eigen::MatrixXd pts = red_points(12, 32);
    pts.row(7) = pts.row(3);
    const VariogramModel model = VariogramModel::spherical(0.0, 1.0, 5.0);
    ReductionOptions ro;
    ro.tau = 0.0;  // remove as long as allowed
    ro.min_samples = 5;
    const ReductionResult r = reduce_samples(pts, model, ro);
    REQUIRE(!r.removed.empty());
    CHECK(r.removed.front() == 7);
    CHECK(r.removed_reliability.front() == 1.0);
    CHECK(r.kept.size() == 5);
    CHECK(!r.stopped_on_threshold);
    ro.tau = 1.5;
    CHECK_THROWS_AS(reduce_samples(pts, model, ro), mocapdb::InvalidArgument);
}
