// RBF baseline: same interface and the same guarantees (partition of unity, exact interpolation).
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/rbf.hpp"

using namespace mocapdb::kriging;

namespace {
Eigen::MatrixXd rbf_points(Eigen::Index n, Eigen::Index p, unsigned seed, double lo = 0.0, double hi = 10.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ud(lo, hi);
    Eigen::MatrixXd m(n, p);
    for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = ud(rng);
    return m;
}

// Mean of a prediction error over queries; any Interpolator.
double rms_error(const Interpolator& f, const Eigen::MatrixXd& queries, const Eigen::VectorXd& values,
                 const Eigen::VectorXd& truth) {
    const Eigen::VectorXd pred = f.predict(queries, values).col(0);
    return std::sqrt((pred - truth).squaredNorm() / static_cast<double>(truth.size()));
}
}  // namespace

TEST_CASE("RBF weights: partition of unity, exact interpolation, linear precision", "[kriging][rbf]") {
    const Eigen::MatrixXd pts = rbf_points(30, 2, 21);
    const Eigen::MatrixXd queries = rbf_points(20, 2, 22, -3.0, 13.0);
    const Eigen::Vector2d slope(0.4, -0.9);
    const Eigen::VectorXd lin = (pts * slope).array() + 1.5;
    const Eigen::VectorXd lin_truth = (queries * slope).array() + 1.5;
    for (RadialFunction f : {RadialFunction::CubicBSpline, RadialFunction::Gaussian, RadialFunction::Linear,
                             RadialFunction::Cubic, RadialFunction::ThinPlate}) {
        RbfOptions o;
        o.function = f;
        const RbfInterpolator r = RbfInterpolator::build(pts, o);
        INFO(to_string(f) << " ridge " << r.status().ridge << " rcond " << r.status().rcond);
        const Eigen::MatrixXd w = r.weights_batch(queries);
        CHECK(w.allFinite());
        CHECK((w.colwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-10);
        CHECK((r.status().factorization == FactorizationStatus::Ok) == (r.status().ridge == 0.0));
        if (r.status().ridge == 0.0) {
            CHECK((r.weights_batch(pts) - Eigen::MatrixXd::Identity(30, 30)).cwiseAbs().maxCoeff() <= 1e-9);
        }
        CHECK((r.predict(queries, lin).col(0) - lin_truth).cwiseAbs().maxCoeff() <= 1e-9);
        // Single and batch paths agree (to rounding amplified by the system's conditioning: the two
        // paths sum in different orders, and the cubic system has rcond ~5e-6).
        QueryWorkspace ws;
        Eigen::VectorXd wq(30);
        r.weights(queries.row(3).transpose(), wq, ws);
        CHECK((wq - w.col(3)).cwiseAbs().maxCoeff() <= 1e-15 / std::min(r.status().rcond, 1e-3));
    }
}

TEST_CASE("A near-singular radial matrix is ridged and says so in its status", "[kriging][rbf]") {
    RbfOptions o;
    o.function = RadialFunction::Gaussian;
    o.width = 1e4;  // every radial value ~1: Phi is numerically of rank one
    const RbfInterpolator r = RbfInterpolator::build(rbf_points(12, 2, 5), o);
    CHECK(r.status().factorization != FactorizationStatus::Ok);
    CHECK(r.status().ridge > 0.0);
    CHECK(r.weights_batch(rbf_points(4, 2, 6)).allFinite());
}

TEST_CASE("Cubic B-spline radii follow the nearest-neighbour rule", "[kriging][rbf]") {
    Eigen::MatrixXd pts(3, 1);
    pts << 0.0, 1.0, 4.0;
    const RbfInterpolator r = RbfInterpolator::build(pts, {});
    CHECK(r.radii()(0) == Approx(2.0));
    CHECK(r.radii()(1) == Approx(2.0));
    CHECK(r.radii()(2) == Approx(6.0));
}

TEST_CASE("RBF and kriging are interchangeable through Interpolator", "[kriging][rbf]") {
    const Eigen::MatrixXd pts = rbf_points(40, 2, 23);
    const Eigen::MatrixXd queries = rbf_points(50, 2, 24);
    Eigen::VectorXd s(40), truth(50);
    for (Eigen::Index i = 0; i < 40; ++i) s(i) = std::sin(pts(i, 0) * 0.5) + 0.1 * pts(i, 1);
    for (Eigen::Index i = 0; i < 50; ++i) truth(i) = std::sin(queries(i, 0) * 0.5) + 0.1 * queries(i, 1);
    const RbfInterpolator rbf = RbfInterpolator::build(pts, {});
    const Kriging kr = Kriging::build(pts, VariogramModel::stable(1.5, 0.0, 1.0, 4.0), {});
    const std::vector<const Interpolator*> methods = {&rbf, &kr};
    for (const Interpolator* m : methods) {
        const double e = rms_error(*m, queries, s, truth);
        INFO("rms error " << e);
        CHECK(std::isfinite(e));
        CHECK(e < 0.5);  // both are sane interpolants of a smooth function of amplitude ~1.5
    }
}

TEST_CASE("RBF merges duplicates and rejects bad options", "[kriging][rbf][robustness]") {
    Eigen::MatrixXd pts = rbf_points(10, 2, 25);
    pts.row(4) = pts.row(1);
    const RbfInterpolator r = RbfInterpolator::build(pts, {});
    CHECK(r.status().duplicates_merged == 1);
    const Eigen::VectorXd w = r.weights(pts.row(1).transpose());
    CHECK(w(1) == Approx(0.5));
    CHECK(w(4) == Approx(0.5));
    RbfOptions bad;
    bad.radius_scale = 0.0;
    CHECK_THROWS_AS(RbfInterpolator::build(pts, bad), mocapdb::InvalidArgument);
    CHECK_THROWS_AS(RbfInterpolator::build(Eigen::MatrixXd(0, 2), {}), mocapdb::InvalidArgument);
}
