// Per-element, per-pose and per-set kernels on plain Eigen motion matrices.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/motion_kriging.hpp"

using namespace mocapdb::kriging;

namespace {
// N samples of a "motion" with D dofs and T frames: smooth nonlinear functions of 2 control parameters.
struct MotionSet {
    Eigen::MatrixXd coords;  // N by 2
    Eigen::MatrixXd samples; // N by D*T
    Eigen::MatrixXd pose;    // N by T
};

MotionSet make_motions(Eigen::Index n, Eigen::Index d, Eigen::Index t, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ua(0.0, 180.0), uh(50.0, 200.0);  // degrees and centimetres
    MotionSet m;
    m.coords.resize(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) {
        m.coords(i, 0) = ua(rng);
        m.coords(i, 1) = uh(rng);
    }
    m.samples.resize(n, d * t);
    m.pose.resize(n, t);
    for (Eigen::Index i = 0; i < n; ++i) {
        const double a = m.coords(i, 0) / 90.0, h = m.coords(i, 1) / 100.0;
        for (Eigen::Index f = 0; f < t; ++f) {
            const double ph = static_cast<double>(f) / static_cast<double>(t);
            double sq = 0.0;
            for (Eigen::Index k = 0; k < d; ++k) {
                const double v = std::sin(a * (1.0 + 0.1 * static_cast<double>(k)) + ph) * h + 0.3 * static_cast<double>(k) * a;
                m.samples(i, f * d + k) = v;
                sq += v * v;
            }
            m.pose(i, f) = std::sqrt(sq);
        }
    }
    return m;
}
}  // namespace

TEST_CASE("Every kernel scope interpolates the samples exactly", "[kriging][motion]") {
    const MotionSet m = make_motions(20, 4, 3, 41);
    for (KernelScope scope : {KernelScope::PerElement, KernelScope::PerPose, KernelScope::PerSet}) {
        for (InterpolationMethod method : {InterpolationMethod::Kriging, InterpolationMethod::Rbf}) {
            MotionKrigingOptions o;
            o.scope = scope;
            o.method = method;
            o.dofs_per_frame = 4;
            o.root_dofs = {0};
            const MotionKriging mk = MotionKriging::build(m.coords, m.samples, m.pose, Eigen::MatrixXd(), o);
            INFO(to_string(scope) << " method " << (method == InterpolationMethod::Kriging ? "kriging" : "rbf") << " p "
                                  << mk.report().exponent << " kernels " << mk.report().kernels);
            const Eigen::MatrixXd at = mk.predict_batch(m.coords);
            CHECK((at - m.samples).cwiseAbs().maxCoeff() <= 1e-7 * m.samples.cwiseAbs().maxCoeff());
            // Single query equals batch.
            Eigen::VectorXd one(12);
            const Eigen::Vector2d q(45.0, 120.0);
            mk.predict(q, one);
            CHECK((one.transpose() - mk.predict_batch(q.transpose())).cwiseAbs().maxCoeff() <= 1e-10);
            CHECK(one.allFinite());
            if (method == InterpolationMethod::Kriging) {
                const Eigen::Index expected = scope == KernelScope::PerElement ? 12 : (scope == KernelScope::PerPose ? 3 * 2 : 1);
                CHECK(mk.report().kernels == expected);
                CHECK(mk.report().exponent >= 0.0);
                CHECK(mk.report().exponent <= 2.0);
            }
        }
    }
}

TEST_CASE("Per-pose kernels: one per frame plus per-element root dofs", "[kriging][motion]") {
    const MotionSet m = make_motions(15, 3, 4, 42);
    MotionKrigingOptions o;
    o.scope = KernelScope::PerPose;
    o.dofs_per_frame = 3;
    o.root_dofs = {0, 2};
    o.exponent = 1.0;
    const MotionKriging mk = MotionKriging::build(m.coords, m.samples, m.pose, Eigen::MatrixXd(), o);
    CHECK(mk.report().kernels == 4 * 3);
    const auto& kc = mk.kernel_of_column();
    for (Eigen::Index f = 0; f < 4; ++f) {
        // dof 1 is served by the frame kernel, dofs 0 and 2 have their own.
        CHECK(kc[static_cast<std::size_t>(f * 3 + 0)] != kc[static_cast<std::size_t>(f * 3 + 1)]);
        CHECK(kc[static_cast<std::size_t>(f * 3 + 2)] != kc[static_cast<std::size_t>(f * 3 + 1)]);
    }
}

TEST_CASE("Motions linear in the control parameters are reproduced everywhere", "[kriging][motion]") {
    MotionSet m = make_motions(12, 2, 2, 43);
    for (Eigen::Index c = 0; c < m.samples.cols(); ++c) {
        m.samples.col(c) = 0.5 * static_cast<double>(c) + 0.02 * m.coords.col(0).array() - 0.01 * m.coords.col(1).array() * static_cast<double>(c);
    }
    Eigen::MatrixXd q(3, 2);
    q << 10.0, 60.0, 170.0, 190.0, 300.0, -50.0;
    for (KernelScope scope : {KernelScope::PerElement, KernelScope::PerPose, KernelScope::PerSet}) {
        MotionKrigingOptions o;
        o.scope = scope;
        o.dofs_per_frame = 2;
        const MotionKriging mk = MotionKriging::build(m.coords, m.samples, m.pose, Eigen::MatrixXd(), o);
        const Eigen::MatrixXd pred = mk.predict_batch(q);
        for (Eigen::Index c = 0; c < m.samples.cols(); ++c) {
            const Eigen::VectorXd truth =
                (0.5 * static_cast<double>(c) + 0.02 * q.col(0).array() - 0.01 * q.col(1).array() * static_cast<double>(c)).matrix();
            INFO(to_string(scope) << " column " << c);
            CHECK((pred.col(c) - truth).cwiseAbs().maxCoeff() <= 1e-8);
        }
        if (scope == KernelScope::PerElement) CHECK(mk.report().degenerate_kernels == 4);
    }
}

TEST_CASE("Normalized control parameters make predictions independent of units", "[kriging][motion]") {
    const MotionSet m = make_motions(18, 2, 2, 44);
    Eigen::MatrixXd scaled = m.coords;
    scaled.col(0) *= 3.14159265358979 / 180.0;  // degrees -> radians
    scaled.col(1) *= 10.0;                      // cm -> mm
    Eigen::MatrixXd q(2, 2);
    q << 33.0, 77.0, 120.0, 150.0;
    Eigen::MatrixXd qs = q;
    qs.col(0) *= 3.14159265358979 / 180.0;
    qs.col(1) *= 10.0;
    MotionKrigingOptions o;
    o.scope = KernelScope::PerSet;
    const MotionKriging a = MotionKriging::build(m.coords, m.samples, m.pose, Eigen::MatrixXd(), o);
    const MotionKriging b = MotionKriging::build(scaled, m.samples, m.pose, Eigen::MatrixXd(), o);
    CHECK((a.predict_batch(q) - b.predict_batch(qs)).cwiseAbs().maxCoeff() <= 1e-9);
    // A user-given scaling overrides the automatic one.
    MotionKrigingOptions user = o;
    user.scaling = ControlScaling::identity(2);
    const MotionKriging c = MotionKriging::build(m.coords, m.samples, m.pose, Eigen::MatrixXd(), user);
    CHECK((c.scaling().scale.array() == 1.0).all());
}

TEST_CASE("Per-set kernel accepts a given dissimilarity, bad shapes throw", "[kriging][motion][errors]") {
    const MotionSet m = make_motions(10, 2, 3, 45);
    Eigen::MatrixXd dis(10, 10);
    for (Eigen::Index i = 0; i < 10; ++i) {
        for (Eigen::Index j = 0; j < 10; ++j) dis(i, j) = (m.samples.row(i) - m.samples.row(j)).norm();
    }
    MotionKrigingOptions o;
    o.scope = KernelScope::PerSet;
    const MotionKriging mk = MotionKriging::build(m.coords, m.samples, Eigen::MatrixXd(), dis, o);
    CHECK(mk.report().kernels == 1);
    CHECK(mk.predict_batch(m.coords).isApprox(m.samples, 1e-8));
    o.scope = KernelScope::PerPose;
    o.dofs_per_frame = 2;
    CHECK_THROWS_AS(MotionKriging::build(m.coords, m.samples, Eigen::MatrixXd(10, 2), Eigen::MatrixXd(), o),
                    mocapdb::InvalidArgument);
    o.dofs_per_frame = 4;
    CHECK_THROWS_AS(MotionKriging::build(m.coords, m.samples, m.pose, Eigen::MatrixXd(), o), mocapdb::InvalidArgument);
    o.scope = KernelScope::PerSet;
    CHECK_THROWS_AS(MotionKriging::build(m.coords, m.samples, Eigen::MatrixXd(), Eigen::MatrixXd(3, 3), o),
                    mocapdb::InvalidArgument);
}
