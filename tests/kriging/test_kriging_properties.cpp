// Properties of the kriging engine: partition of unity, exact interpolation, reliability limits,
// order invariance, robustness (duplicates, collinear points, indefinite models), and independent
// dense-solve / brute-force oracles for the weights, the variance and the closed-form leave-one-out.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/LU>
#include <Eigen/QR>
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/kriging.hpp"

using namespace mocapdb::kriging;

namespace {

Eigen::MatrixXd random_points(Eigen::Index n, Eigen::Index p, unsigned seed, double lo = 0.0, double hi = 10.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ud(lo, hi);
    Eigen::MatrixXd m(n, p);
    for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = ud(rng);
    return m;
}

std::vector<VariogramModel> test_models() {
    return {VariogramModel::spherical(0.0, 1.0, 6.0), VariogramModel::spherical(0.2, 1.0, 4.0),
            VariogramModel::stable(0.6, 0.0, 2.0, 3.0), VariogramModel::stable(1.0, 0.1, 1.0, 2.0),
            VariogramModel::stable(1.4, 0.0, 1.0, 5.0), VariogramModel::stable(2.0, 0.05, 1.0, 3.0)};
}

std::vector<KrigingOptions> test_options() {
    std::vector<KrigingOptions> v;
    for (TrendKind t : {TrendKind::None, TrendKind::Linear}) {
        for (TrendFit f : {TrendFit::OLS, TrendFit::GLS}) {
            if (t == TrendKind::None && f == TrendFit::GLS) continue;
            KrigingOptions o;
            o.trend = t;
            o.trend_fit = f;
            v.push_back(o);
        }
    }
    return v;
}

std::string describe(const KrigingOptions& o) {
    return std::string("trend ") + to_string(o.trend) + " fit " + to_string(o.trend_fit);
}

}  // namespace

TEST_CASE("Weights are a partition of unity and interpolate exactly", "[kriging][properties]") {
    const Eigen::MatrixXd pts = random_points(40, 3, 1);
    const Eigen::MatrixXd queries = random_points(25, 3, 2, -2.0, 12.0);
    for (const auto& model : test_models()) {
        for (const auto& opt : test_options()) {
            const Kriging k = Kriging::build(pts, model, opt);
            INFO(model.to_string() << " " << describe(opt) << " status " << to_string(k.status().factorization));
            const KrigingBatch q = k.estimate_batch(queries);
            const double sum_err = (q.weights.colwise().sum().array() - 1.0).abs().maxCoeff();
            INFO("max |sum w - 1| " << sum_err);
            CHECK(sum_err <= 1e-10);
            CHECK(q.variance.allFinite());
            CHECK((q.variance.array() >= 0.0).all());
            CHECK((q.reliability.array() >= 0.0).all());
            CHECK((q.reliability.array() <= 1.0).all());
            // Kernel b (paper Eq. 3) also sums to one.
            const KrigingEstimate e = k.estimate(queries.row(0).transpose());
            CHECK(std::abs(e.kernel.sum() - 1.0) <= 1e-10);

            const KrigingBatch at = k.estimate_batch(pts);
            const double interp_err = (at.weights - Eigen::MatrixXd::Identity(40, 40)).cwiseAbs().maxCoeff();
            INFO("max |W(c_i) - I| " << interp_err);
            CHECK(interp_err <= 1e-8);
            CHECK(at.variance.maxCoeff() <= 1e-8 * model.total_sill());
            CHECK(at.reliability.minCoeff() >= 1.0 - 1e-8);

            // Single-query path equals the batch path.
            QueryWorkspace ws;
            Eigen::VectorXd w(40);
            double diff = 0.0;
            for (Eigen::Index j = 0; j < queries.rows(); ++j) {
                k.weights(queries.row(j).transpose(), w, ws);
                diff = std::max(diff, (w - q.weights.col(j)).cwiseAbs().maxCoeff());
            }
            CHECK(diff <= 1e-12);
        }
    }
}

TEST_CASE("Reliability tends to 0 far from the samples", "[kriging][properties]") {
    const Eigen::MatrixXd pts = random_points(30, 2, 3);
    Eigen::MatrixXd far(3, 2);
    far << 1e6, 1e6, -1e7, 3e5, 5e8, -5e8;
    for (const auto& model : test_models()) {
        for (const auto& opt : test_options()) {
            const Kriging k = Kriging::build(pts, model, opt);
            const Eigen::VectorXd rho = k.reliability(far);
            for (Eigen::Index q = 0; q < far.rows(); ++q) {
                // Extrapolating a linear trend makes the weights large (|w| ~ distance): sigma^2 = sill * sum b
                // then carries a rounding error of order eps * sum |b|.
                const double l1 = k.estimate(far.row(q).transpose()).kernel.cwiseAbs().sum();
                INFO(model.to_string() << " " << describe(opt) << " rho far " << rho(q) << " sum|b| " << l1);
                CHECK(rho(q) <= 1e-14 * l1 + 1e-12);
            }
        }
    }
}

TEST_CASE("GLS weights and variance equal a dense solve of the variogram system", "[kriging][properties][oracle]") {
    const Eigen::Index n = 30;
    const Eigen::MatrixXd pts = random_points(n, 2, 4);
    const Eigen::MatrixXd queries = random_points(5, 2, 5);
    for (const auto& model : test_models()) {
        for (TrendKind trend : {TrendKind::None, TrendKind::Linear}) {
            KrigingOptions opt;
            opt.trend = trend;
            opt.trend_fit = TrendFit::GLS;
            const Kriging k = Kriging::build(pts, model, opt);
            const Eigen::Index kk = trend == TrendKind::None ? 1 : 3;
            Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + kk, n + kk);
            for (Eigen::Index i = 0; i < n; ++i) {
                for (Eigen::Index j = 0; j < n; ++j) a(i, j) = model((pts.row(i) - pts.row(j)).norm());
                a(i, n) = a(n, i) = 1.0;
                for (Eigen::Index c = 1; c < kk; ++c) a(i, n + c) = a(n + c, i) = pts(i, c - 1);
            }
            Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
            const KrigingBatch b = k.estimate_batch(queries);
            for (Eigen::Index q = 0; q < queries.rows(); ++q) {
                Eigen::VectorXd rhs(n + kk);
                for (Eigen::Index i = 0; i < n; ++i) rhs(i) = model((pts.row(i) - queries.row(q)).norm());
                rhs(n) = 1.0;
                for (Eigen::Index c = 1; c < kk; ++c) rhs(n + c) = queries(q, c - 1);
                const Eigen::VectorXd sol = lu.solve(rhs);
                const double werr = (sol.head(n) - b.weights.col(q)).cwiseAbs().maxCoeff();
                const double var = sol.dot(rhs);  // w^T gamma + mu^T f
                INFO(model.to_string() << " trend " << to_string(trend) << " q " << q << " weight err " << werr
                                       << " var ours " << b.variance(q) << " dense " << var);
                CHECK(werr <= 1e-9);
                CHECK(std::abs(var - b.variance(q)) <= 1e-9 * std::max(1.0, var));
            }
        }
    }
}

TEST_CASE("OLS mode equals the paper's two steps: least-squares hyperplane plus OK of residuals", "[kriging][properties][oracle]") {
    const Eigen::Index n = 35;
    const Eigen::MatrixXd pts = random_points(n, 2, 6);
    Eigen::VectorXd s(n);
    for (Eigen::Index i = 0; i < n; ++i) s(i) = 2.0 + 0.5 * pts(i, 0) - 0.3 * pts(i, 1) + std::sin(pts(i, 0) * pts(i, 1) * 0.3);
    const Eigen::MatrixXd queries = random_points(6, 2, 7, -1.0, 11.0);
    // Plain least squares with [1 x y] (independent of TrendBasis).
    Eigen::MatrixXd f(n, 3);
    f.col(0).setOnes();
    f.rightCols(2) = pts;
    const Eigen::Vector3d l = f.colPivHouseholderQr().solve(s);
    const Eigen::VectorXd r = s - f * l;
    for (const auto& model : test_models()) {
        KrigingOptions ols;
        ols.trend = TrendKind::Linear;
        ols.trend_fit = TrendFit::OLS;
        KrigingOptions ok;
        ok.trend = TrendKind::None;
        const Kriging k_ols = Kriging::build(pts, model, ols);
        const Kriging k_ok = Kriging::build(pts, model, ok);
        const Eigen::VectorXd pred = k_ols.weights_batch(queries).transpose() * s;
        const Eigen::VectorXd two_step =
            (queries * l.tail(2)).array() + l(0) + (k_ok.weights_batch(queries).transpose() * r).array();
        INFO(model.to_string() << " max diff " << (pred - two_step).cwiseAbs().maxCoeff());
        CHECK((pred - two_step).cwiseAbs().maxCoeff() <= 1e-9);
        // Paper variance uses the OK kernel in both cases.
        CHECK((k_ols.estimate_batch(queries).paper_variance - k_ok.estimate_batch(queries).paper_variance)
                  .cwiseAbs()
                  .maxCoeff() <= 1e-10);
        // The OLS variance is the prediction-error variance of its weights: 2 w^T g - w^T Gamma w.
        const KrigingBatch b = k_ols.estimate_batch(queries);
        for (Eigen::Index q = 0; q < queries.rows(); ++q) {
            Eigen::VectorXd g(n);
            Eigen::MatrixXd gm(n, n);
            for (Eigen::Index i = 0; i < n; ++i) {
                g(i) = model((pts.row(i) - queries.row(q)).norm());
                for (Eigen::Index j = 0; j < n; ++j) gm(i, j) = model((pts.row(i) - pts.row(j)).norm());
            }
            const Eigen::VectorXd w = b.weights.col(q);
            const double v = 2.0 * w.dot(g) - w.dot(gm * w);
            CHECK(std::abs(v - b.variance(q)) <= 1e-10 * std::max(1.0, v));
        }
    }
}

TEST_CASE("Linear functions are reproduced exactly with a linear trend", "[kriging][properties]") {
    const Eigen::MatrixXd pts = random_points(25, 3, 8);
    const Eigen::MatrixXd queries = random_points(10, 3, 9, -20.0, 30.0);
    const Eigen::Vector3d slope(0.7, -1.1, 0.25);
    const Eigen::VectorXd s = (pts * slope).array() + 4.0;
    const Eigen::VectorXd truth = (queries * slope).array() + 4.0;
    for (const auto& model : test_models()) {
        for (TrendFit tf : {TrendFit::OLS, TrendFit::GLS}) {
            KrigingOptions o;
            o.trend_fit = tf;
            const Kriging k = Kriging::build(pts, model, o);
            const Eigen::VectorXd pred = k.predict(queries, s).col(0);
            CHECK((pred - truth).cwiseAbs().maxCoeff() <= 1e-8 * truth.cwiseAbs().maxCoeff());
        }
    }
}

TEST_CASE("Results are invariant to the order of the samples", "[kriging][properties]") {
    const Eigen::Index n = 30;
    const Eigen::MatrixXd pts = random_points(n, 2, 10);
    Eigen::VectorXd s(n);
    for (Eigen::Index i = 0; i < n; ++i) s(i) = std::cos(pts(i, 0)) + 0.1 * pts(i, 1);
    std::vector<Eigen::Index> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), Eigen::Index{0});
    std::mt19937 rng(11);
    std::shuffle(perm.begin(), perm.end(), rng);
    Eigen::MatrixXd pp(n, 2);
    Eigen::VectorXd sp(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        pp.row(i) = pts.row(perm[static_cast<std::size_t>(i)]);
        sp(i) = s(perm[static_cast<std::size_t>(i)]);
    }
    const Eigen::MatrixXd queries = random_points(8, 2, 12);
    for (const auto& model : test_models()) {
        for (const auto& opt : test_options()) {
            const Kriging a = Kriging::build(pts, model, opt);
            const Kriging b = Kriging::build(pp, model, opt);
            const KrigingBatch ea = a.estimate_batch(queries);
            const KrigingBatch eb = b.estimate_batch(queries);
            double werr = 0.0;
            for (Eigen::Index i = 0; i < n; ++i) {
                werr = std::max(werr, (ea.weights.row(perm[static_cast<std::size_t>(i)]) - eb.weights.row(i)).cwiseAbs().maxCoeff());
            }
            INFO(model.to_string() << " " << describe(opt) << " weight diff " << werr);
            CHECK(werr <= 1e-9);
            CHECK((ea.variance - eb.variance).cwiseAbs().maxCoeff() <= 1e-10);
            CHECK((ea.reliability - eb.reliability).cwiseAbs().maxCoeff() <= 1e-10);
            const LooResult la = a.leave_one_out(s);
            const LooResult lb = b.leave_one_out(sp);
            for (Eigen::Index i = 0; i < n; ++i) {
                CHECK(std::abs(la.prediction(perm[static_cast<std::size_t>(i)], 0) - lb.prediction(i, 0)) <= 1e-9);
            }
        }
    }
}

TEST_CASE("Closed-form LOO prediction, variance and reliability equal N rebuilds", "[kriging][properties][loo]") {
    const Eigen::Index n = 25;
    const Eigen::MatrixXd pts = random_points(n, 2, 13);
    Eigen::MatrixXd s(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) {
        s(i, 0) = std::sin(pts(i, 0)) + 0.2 * pts(i, 1);
        s(i, 1) = pts(i, 0) * pts(i, 1) * 0.05;
    }
    for (const auto& model : test_models()) {
        for (const auto& opt : test_options()) {
            if (opt.trend_fit == TrendFit::OLS && opt.trend == TrendKind::Linear) continue;  // covered in fit tests
            const Kriging k = Kriging::build(pts, model, opt);
            const LooResult loo = k.leave_one_out(s);
            const Eigen::VectorXd rho = k.leave_one_out_reliability();
            double worst = 0.0;
            for (Eigen::Index i = 0; i < n; ++i) {
                Eigen::MatrixXd c(n - 1, 2);
                Eigen::MatrixXd v(n - 1, 2);
                for (Eigen::Index j = 0, r = 0; j < n; ++j) {
                    if (j == i) continue;
                    c.row(r) = pts.row(j);
                    v.row(r) = s.row(j);
                    ++r;
                }
                const Kriging ki = Kriging::build(c, model, opt);
                const KrigingEstimate e = ki.estimate(pts.row(i).transpose());
                const Eigen::RowVectorXd pred = e.weights.transpose() * v;
                worst = std::max(worst, (pred - loo.prediction.row(i)).cwiseAbs().maxCoeff());
                CHECK(std::abs(e.variance - loo.variance(i)) <= 1e-9 * std::max(1.0, e.variance));
                CHECK(std::abs(e.reliability - rho(i)) <= 1e-9);
            }
            INFO(model.to_string() << " " << describe(opt) << " worst LOO prediction diff " << worst);
            CHECK(worst <= 1e-9);
        }
    }
}

TEST_CASE("Duplicate control points are merged or regularized, never NaN", "[kriging][robustness]") {
    Eigen::MatrixXd pts = random_points(20, 2, 14);
    pts.row(5) = pts.row(2);
    pts.row(11) = pts.row(2);
    pts.row(17) = pts.row(9);
    Eigen::VectorXd s = Eigen::VectorXd::LinSpaced(20, 1.0, 3.0);
    const Eigen::MatrixXd queries = random_points(7, 2, 15);
    for (const auto& model : {VariogramModel::spherical(0.0, 1.0, 5.0), VariogramModel::stable(2.0, 0.0, 1.0, 3.0)}) {
        for (DuplicatePolicy policy : {DuplicatePolicy::Merge, DuplicatePolicy::Keep}) {
            for (const auto& base : test_options()) {
                KrigingOptions o = base;
                o.duplicates = policy;
                const Kriging k = Kriging::build(pts, model, o);
                INFO(model.to_string() << " " << describe(o) << " policy " << (policy == DuplicatePolicy::Merge ? "merge" : "keep")
                                       << " factorization " << to_string(k.status().factorization) << " jitter "
                                       << k.status().jitter);
                CHECK(k.status().duplicate_pairs == 4);
                const KrigingBatch b = k.estimate_batch(queries);
                CHECK(b.weights.allFinite());
                CHECK(b.variance.allFinite());
                CHECK(b.reliability.allFinite());
                CHECK((b.weights.colwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-8);
                const LooResult loo = k.leave_one_out(s);
                CHECK(loo.prediction.allFinite());
                CHECK(loo.zscore.allFinite());
                const Eigen::VectorXd at = k.weights(pts.row(2).transpose());
                if (policy == DuplicatePolicy::Merge) {
                    CHECK(k.status().duplicates_merged == 3);
                    CHECK(k.status().exact());
                    // Exact interpolation of the mean of the duplicates.
                    CHECK(std::abs(at.dot(s) - (s(2) + s(5) + s(11)) / 3.0) <= 1e-10);
                    CHECK(loo.variance(5) == 0.0);
                    CHECK(std::abs(loo.prediction(5, 0) - 0.5 * (s(2) + s(11))) <= 1e-12);
                } else {
                    CHECK(k.status().duplicates_merged == 0);
                    CHECK(k.status().factorization != FactorizationStatus::Ok);
                    CHECK(std::abs(at.dot(s) - (s(2) + s(5) + s(11)) / 3.0) <= 1e-4);
                }
            }
        }
    }
}

TEST_CASE("Collinear and coincident control points with a linear trend", "[kriging][robustness]") {
    const Eigen::Index n = 15;
    Eigen::MatrixXd line(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) {
        const double t = 0.7 * static_cast<double>(i) + 0.1 * std::sin(static_cast<double>(i));
        line(i, 0) = 1.0 + t;
        line(i, 1) = 2.0 - 0.5 * t;
    }
    const Eigen::VectorXd s = line.col(0).array().sin() + line.col(0).array();
    Eigen::MatrixXd queries(4, 2);
    queries << 3.0, 1.0, 0.0, 0.0, 10.0, -5.0, 2.0, 1.5;  // on and off the line
    for (const auto& model : test_models()) {
        for (TrendFit tf : {TrendFit::OLS, TrendFit::GLS}) {
            KrigingOptions o;
            o.trend_fit = tf;
            const Kriging k = Kriging::build(line, model, o);
            INFO(model.to_string() << " fit " << to_string(tf));
            CHECK(k.status().trend_rank_deficient);
            CHECK(k.status().trend_rank == 1);
            const KrigingBatch b = k.estimate_batch(queries);
            CHECK(b.weights.allFinite());
            CHECK(b.variance.allFinite());
            CHECK((b.weights.colwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-9);
            CHECK((k.weights_batch(line) - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff() <= 1e-8);
            CHECK(k.leave_one_out(s).prediction.allFinite());
        }
    }
    // Every control point identical.
    const Eigen::MatrixXd same = Eigen::MatrixXd::Constant(6, 3, 2.5);
    const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(6, 0.0, 1.0);
    for (const auto& opt : test_options()) {
        const Kriging k = Kriging::build(same, VariogramModel::stable(1.0, 0.0, 1.0, 1.0), opt);
        const Eigen::VectorXd w = k.weights(Eigen::Vector3d(0.0, 1.0, 2.0));
        CHECK(w.allFinite());
        CHECK(std::abs(w.sum() - 1.0) <= 1e-12);
        CHECK(std::abs(w.dot(v) - v.mean()) <= 1e-12);
    }
}

TEST_CASE("An indefinite model (spherical in 6-D) is regularized, never NaN", "[kriging][robustness]") {
    const Eigen::MatrixXd pts = random_points(80, 6, 16);
    const Kriging k = Kriging::build(pts, VariogramModel::spherical(0.0, 1.0, 30.0), {});
    INFO("factorization " << to_string(k.status().factorization) << " jitter " << k.status().jitter << " rcond "
                          << k.status().rcond);
    const KrigingBatch b = k.estimate_batch(random_points(10, 6, 17));
    CHECK(b.weights.allFinite());
    CHECK(b.variance.allFinite());
    CHECK((b.weights.colwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-8);
}

TEST_CASE("Bad arguments throw InvalidArgument naming the constraint", "[kriging][errors]") {
    const Eigen::MatrixXd pts = random_points(5, 2, 18);
    CHECK_THROWS_AS(Kriging::build(Eigen::MatrixXd(0, 2), VariogramModel::spherical(0, 1, 1)), mocapdb::InvalidArgument);
    CHECK_THROWS_WITH(VariogramModel::stable(2.5, 0, 1, 1), Catch::Contains("0 < p <= 2"));
    CHECK_THROWS_WITH(VariogramModel::spherical(-1, 1, 1), Catch::Contains("nugget"));
    CHECK_THROWS_WITH(VariogramModel::spherical(0, 1, 0), Catch::Contains("range"));
    CHECK_THROWS_WITH(Kriging::build(pts, VariogramModel::spherical(0, 0, 1)), Catch::Contains("nugget + sill > 0"));
    Eigen::MatrixXd bad = pts;
    bad(1, 1) = std::nan("");
    CHECK_THROWS_AS(Kriging::build(bad, VariogramModel::spherical(0, 1, 1)), mocapdb::InvalidArgument);
    const Kriging k = Kriging::build(pts, VariogramModel::spherical(0, 1, 1));
    CHECK_THROWS_AS(k.weights(Eigen::Vector3d::Zero()), mocapdb::InvalidArgument);
    CHECK_THROWS_AS(k.leave_one_out(Eigen::VectorXd::Zero(4)), mocapdb::InvalidArgument);
    CHECK_THROWS_AS(k.predict(Eigen::MatrixXd::Zero(2, 2), Eigen::VectorXd::Zero(3)), mocapdb::InvalidArgument);
}

TEST_CASE("Vectorized gamma of squared distances equals the scalar model", "[kriging][model]") {
    Eigen::VectorXd h = Eigen::VectorXd::LinSpaced(200, 0.0, 12.0);
    h(1) = 1e-150;  // tiny but with a representable square
    const Eigen::VectorXd d2 = h.array().square();
    for (const auto& m : test_models()) {
        Eigen::VectorXd g(h.size());
        m.gamma_of_squared(d2, g);
        CHECK(g(0) == 0.0);
        for (Eigen::Index i = 0; i < h.size(); ++i) {
            INFO(m.to_string() << " h " << h(i));
            CHECK(std::abs(g(i) - m(h(i))) <= 1e-14 * m.total_sill());
            CHECK(std::abs(m.covariance(h(i)) - (m.total_sill() - m(h(i)))) <= 1e-15);
        }
        // Model properties: gamma(0) = 0, increasing to the total sill.
        CHECK(m(0.0) == 0.0);
        CHECK(m(1e9) == Approx(m.total_sill()).epsilon(1e-12));
        CHECK(std::is_sorted(g.data() + 1, g.data() + g.size()));
    }
    CHECK(VariogramModel::spherical(0.1, 1.0, 2.0)(2.0) == Approx(1.1));
    CHECK(VariogramModel::from_paper_p(0.0, 0, 1, 1).family == VariogramFamily::Spherical);
    CHECK(VariogramModel::from_paper_p(0.4, 0, 1, 1).exponent == 0.4);
}

TEST_CASE("covariance_inverse is exactly symmetric, inverts the covariance matrix and reports its progress",
          "[kriging][properties]") {
    // More points than one block of the inverse's columns (256), so that several blocks and their mirrors
    // are checked; a nugget keeps the system well conditioned (no jitter: the inverse of C itself).
    const Eigen::MatrixXd pts = random_points(600, 2, 9);
    const VariogramModel model = VariogramModel::stable(1.5, 0.2, 1.0, 3.0);
    std::vector<std::pair<std::uint64_t, std::uint64_t>> reports;
    const CovarianceInverse inverse =
        Kriging::covariance_inverse(pts, model, {}, [&reports](const mocapdb::Progress& p) {
            CHECK(p.item == "kernel system");
            reports.emplace_back(p.done, p.total);
        });
    REQUIRE(inverse.factorization == FactorizationStatus::Ok);
    const Eigen::MatrixXd& a = inverse.inverse;
    CHECK(a == a.transpose());
    Eigen::MatrixXd cov = (model.total_sill() - Kriging::build(pts, model).gamma_matrix().array()).matrix();
    cov.diagonal().setConstant(model.total_sill());
    const double error = (cov * a - Eigen::MatrixXd::Identity(600, 600)).cwiseAbs().maxCoeff();
    CHECK(error < 1e-9);
    REQUIRE(reports.size() >= 4);  // the start, then each block of columns
    CHECK(reports.front().first == 0);
    for (std::size_t k = 1; k < reports.size(); ++k) {
        CHECK(reports[k].first > reports[k - 1].first);
        CHECK(reports[k].second == 600);
    }
    CHECK(reports.back().first == 600);
}

TEST_CASE("build from a precomputed covariance inverse gives the very same kriging", "[kriging][properties]") {
    Eigen::MatrixXd pts = random_points(40, 3, 5);
    pts.row(7) = pts.row(3);  // a duplicate: the inverse is over the unique points
    const Eigen::MatrixXd queries = random_points(25, 3, 6, -2.0, 12.0);
    for (const auto& model : test_models()) {
        for (const auto& opt : test_options()) {
            INFO(model.to_string() << " " << describe(opt));
            const Kriging direct = Kriging::build(pts, model, opt);
            const CovarianceInverse inverse = Kriging::covariance_inverse(pts, model, opt);
            CHECK(inverse.inverse.rows() == direct.unique_points().rows());
            CHECK(inverse.factorization == direct.status().factorization);
            const Kriging reused = Kriging::build(pts, model, opt, &inverse);
            CHECK(reused.status().factorization == direct.status().factorization);
            CHECK(reused.status().rcond == direct.status().rcond);
            const KrigingBatch a = direct.estimate_batch(queries), b = reused.estimate_batch(queries);
            CHECK(a.weights == b.weights);  // the same doubles through the same operations
            CHECK(a.reliability == b.reliability);
            CHECK(a.variance == b.variance);
        }
    }
    // One of another size is ignored: the system is factorized as without it.
    const VariogramModel model = VariogramModel::stable(1.0, 0.1, 1.0, 2.0);
    CovarianceInverse wrong;
    wrong.inverse = Eigen::MatrixXd::Identity(5, 5);
    const Kriging a = Kriging::build(pts, model, {}), b = Kriging::build(pts, model, {}, &wrong);
    CHECK(a.estimate_batch(queries).weights == b.estimate_batch(queries).weights);
}
