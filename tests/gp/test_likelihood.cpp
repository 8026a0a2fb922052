// Log marginal likelihood of the hierarchical multi-output GP: dense oracle vs finite differences,
// structured vs dense, and the single-output single-layer case vs an ordinary GP written out here.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>

#include "gp_fixtures.hpp"
#include "mocapdb/core/error.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;
using namespace mocapdb::gp::test;

namespace {

MatX kron(const MatX& a, const MatX& b) {
    MatX k(a.rows() * b.rows(), a.cols() * b.cols());
    for (Eigen::Index j = 0; j < a.cols(); ++j)
        for (Eigen::Index i = 0; i < a.rows(); ++i) k.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
    return k;
}

}  // namespace

TEST_CASE("kernel derivatives match finite differences", "[gp][kernels]") {
    for (KernelType type : {KernelType::Rbf, KernelType::Matern32}) {
        for (double r : {0.0, 0.1, 0.7, 2.5}) {
            const double theta = std::log(0.6), h = 1e-6;
            const double fd = (kernel_value(type, theta + h, r) - kernel_value(type, theta - h, r)) / (2 * h);
            INFO(to_string(type) << " r=" << r << " analytic " << kernel_dlog_lengthscale(type, theta, r) << " fd " << fd);
            CHECK(kernel_dlog_lengthscale(type, theta, r) == Approx(fd).margin(1e-9));
        }
        CHECK(kernel_value(type, 0.0, 0.0) == 1.0);
    }
    CHECK(kernel_type_from_string("matern32") == KernelType::Matern32);
    CHECK_THROWS_AS(kernel_type_from_string("cosine"), InvalidArgument);
}

TEST_CASE("dense likelihood equals the generative covariance written with Kronecker products", "[gp][likelihood]") {
    const Eigen::Index d = 2, t = 5;
    const std::size_t r = 3;
    const HgpModel model = make_model(d, true);
    const HgpData data = make_data(d, t, r);
    const MatX kg = lmc_covariance(model.parent, data.times, data.times);
    MatX kf = lmc_covariance(model.child, data.times, data.times);
    for (Eigen::Index i = 0; i < d; ++i)
        kf.diagonal().segment(i * t, t).array() += model.noise_variance()[i];
    const MatX ones = MatX::Ones(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(r));
    const MatX sigma = kron(ones, kg) + kron(MatX::Identity(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(r)), kf);
    VecX y(sigma.rows());
    for (std::size_t c = 0; c < r; ++c)
        for (Eigen::Index i = 0; i < d; ++i)
            y.segment(static_cast<Eigen::Index>(c) * d * t + i * t, t) = data.children[c].row(i).transpose();
    Eigen::LLT<MatX> llt(sigma);
    REQUIRE(llt.info() == Eigen::Success);
    const double expected = -0.5 * y.dot(llt.solve(y)) - MatX(llt.matrixL()).diagonal().array().log().sum() -
                            0.5 * static_cast<double>(y.size()) * std::log(2 * kPi);
    const LikelihoodValue dense = log_likelihood(model, data, false, LikelihoodPath::Dense);
    REQUIRE(dense.ok());
    INFO("dense " << dense.log_likelihood << " kron " << expected);
    CHECK(relative_difference(dense.log_likelihood, expected) < 1e-12);
}

TEST_CASE("dense gradient matches finite differences (complete and partial children)", "[gp][likelihood]") {
    const Eigen::Index d = 2, t = 6;
    for (bool hierarchical : {true, false}) {
        const HgpModel model = make_model(d, hierarchical, 2, 1);
        HgpData data = make_data(d, t, 3);
        data.observed = {{}, {true, false, true, true, false, true}, {}};
        const LikelihoodValue v = log_likelihood(model, data, true, LikelihoodPath::Dense);
        REQUIRE(v.ok());
        REQUIRE(v.path == LikelihoodPath::Dense);
        const VecX fd = finite_difference_gradient(model, data, LikelihoodPath::Dense);
        const double diff = max_relative_difference(v.gradient, fd);
        INFO((hierarchical ? "MOHGP" : "MOA") << ": max relative difference analytic vs fd " << diff << " over "
                                              << fd.size() << " parameters");
        CHECK(diff < 1e-6);
    }
}

TEST_CASE("structured likelihood and gradient equal the dense oracle", "[gp][likelihood]") {
    struct Case {
        Eigen::Index d, t;
        std::size_t r, terms;
        Eigen::Index rank;
        bool hierarchical;
    };
    // n = D·T up to 150 so that the blocked in-place inverse crosses block boundaries (block 96).
    const Case cases[] = {{1, 7, 1, 1, 1, true}, {2, 6, 2, 2, 1, true}, {3, 8, 4, 2, 2, true},
                          {3, 50, 3, 2, 1, true}, {2, 9, 3, 2, 1, false}, {3, 50, 2, 1, 2, false}};
    for (const Case& c : cases) {
        const HgpModel model = make_model(c.d, c.hierarchical, c.terms, c.rank);
        const HgpData data = make_data(c.d, c.t, c.r, 17 + c.r);
        const LikelihoodValue dense = log_likelihood(model, data, true, LikelihoodPath::Dense);
        REQUIRE(dense.ok());
        for (int threads : {1, 2}) {
            const LikelihoodValue s = log_likelihood(model, data, true, LikelihoodPath::Structured, threads);
            REQUIRE(s.ok());
            const double dv = relative_difference(s.log_likelihood, dense.log_likelihood);
            const double dg = max_relative_difference(s.gradient, dense.gradient);
            INFO("D=" << c.d << " T=" << c.t << " R=" << c.r << " Q=" << c.terms << " rank=" << c.rank
                      << (c.hierarchical ? " MOHGP" : " MOA") << " threads=" << threads << ": value rel diff " << dv
                      << ", gradient max rel diff " << dg << " (log p = " << s.log_likelihood << ")");
            CHECK(dv < 1e-8);
            CHECK(dg < 1e-8);
        }
    }
    // Auto picks the structured path for complete data and the dense one otherwise.
    const HgpModel model = make_model(2, true);
    HgpData data = make_data(2, 5, 2);
    CHECK(log_likelihood(model, data, false).path == LikelihoodPath::Structured);
    data.observed = {{true, true, false, true, true}};
    CHECK(log_likelihood(model, data, false).path == LikelihoodPath::Dense);
    CHECK_THROWS_AS(log_likelihood(model, data, false, LikelihoodPath::Structured), InvalidArgument);
}

TEST_CASE("single-output single-layer model equals an ordinary GP", "[gp][likelihood][posterior]") {
    // MOA with D = 1, one RBF term: k(t,t') = (w² + κ)·exp(−r²/2ℓ²), noise σ². Written out directly.
    const Eigen::Index t = 9;
    HgpModel model;
    model.hierarchical = false;
    LmcTerm term;
    term.kernel = KernelType::Rbf;
    term.log_lengthscale = std::log(0.45);
    term.W = MatX::Constant(1, 1, 0.8);
    term.log_kappa = VecX::Constant(1, std::log(0.3));
    model.child.terms = {term};
    model.log_noise = VecX::Constant(1, std::log(0.02));
    model.noise_floor = 0.0;
    const HgpData data = make_data(1, t, 1, 3);
    const VecX y = data.children[0].row(0).transpose();
    const double s2 = 0.8 * 0.8 + 0.3, ell = 0.45, noise = 0.02;
    MatX k(t, t);
    for (Eigen::Index i = 0; i < t; ++i)
        for (Eigen::Index j = 0; j < t; ++j) {
            const double dt = data.times[i] - data.times[j];
            k(i, j) = s2 * std::exp(-dt * dt / (2 * ell * ell));
        }
    MatX ky = k + noise * MatX::Identity(t, t);
    Eigen::LLT<MatX> llt(ky);
    const VecX alpha = llt.solve(y);
    const double expected = -0.5 * y.dot(alpha) - MatX(llt.matrixL()).diagonal().array().log().sum() - 0.5 * t * std::log(2 * kPi);
    for (LikelihoodPath path : {LikelihoodPath::Dense, LikelihoodPath::Structured}) {
        const LikelihoodValue v = log_likelihood(model, data, true, path);
        REQUIRE(v.ok());
        INFO("ours " << v.log_likelihood << " ordinary GP " << expected);
        CHECK(relative_difference(v.log_likelihood, expected) < 1e-12);
        // ∂/∂log σ² of the ordinary GP: ½ σ² (αᵀα − tr K⁻¹).
        const double dnoise = 0.5 * noise * (alpha.squaredNorm() - llt.solve(MatX::Identity(t, t)).trace());
        CHECK(v.gradient[v.gradient.size() - 1] == Approx(dnoise).epsilon(1e-10));
    }
    // Posterior at new times: k*ᵀ (K + σ²I)⁻¹ y and k** − k*ᵀ (K + σ²I)⁻¹ k*.
    const VecX ts = VecX::LinSpaced(4, 0.1, 1.9);
    MatX ks(4, t);
    for (Eigen::Index i = 0; i < 4; ++i)
        for (Eigen::Index j = 0; j < t; ++j) {
            const double dt = ts[i] - data.times[j];
            ks(i, j) = s2 * std::exp(-dt * dt / (2 * ell * ell));
        }
    const VecX mean = ks * alpha;
    const VecX var = (VecX::Constant(4, s2) - (ks * llt.solve(MatX(ks.transpose()))).diagonal());
    for (int which = 0; which < 2; ++which) {
        const GaussianPrediction p = which == 0 ? predict_child(model, data, 0, ts) : predict_child_dense(model, data, 0, ts);
        CHECK(max_relative_difference(p.mean.row(0).transpose(), mean) < 1e-10);
        CHECK(max_relative_difference(p.variance.row(0).transpose(), var) < 1e-8);
    }
}

TEST_CASE("a covariance that is not positive definite is a status, not an exception", "[gp][likelihood]") {
    HgpModel model = make_model(2, true);
    model.noise_floor = 0.0;
    model.log_noise.setConstant(-800.0);
    for (auto& term : model.child.terms) {
        term.W.setZero();
        term.log_kappa.setConstant(-800.0);
    }
    for (auto& term : model.parent.terms) {
        term.W.setZero();
        term.log_kappa.setConstant(-800.0);
    }
    const HgpData data = make_data(2, 6, 2);
    for (LikelihoodPath path : {LikelihoodPath::Dense, LikelihoodPath::Structured}) {
        const LikelihoodValue v = log_likelihood(model, data, true, path);
        CHECK_FALSE(v.ok());
        CHECK_FALSE(v.message.empty());
    }
}

TEST_CASE("likelihood arguments are checked", "[gp][likelihood]") {
    const HgpModel model = make_model(2, true);
    HgpData data = make_data(3, 5, 2);
    CHECK_THROWS_AS(log_likelihood(model, data, false), InvalidArgument);  // D mismatch
    data = make_data(2, 5, 2);
    data.observed = {{true, false}};
    CHECK_THROWS_AS(log_likelihood(model, data, false), InvalidArgument);  // mask length
    data.observed.clear();
    data.children[1](0, 2) = std::nan("");
    CHECK_THROWS_AS(log_likelihood(model, data, false), InvalidArgument);
    data.observed = {{}, {true, true, false, true, true}};  // the NaN frame is unobserved: fine
    CHECK(log_likelihood(model, data, false).ok());
    HgpModel bad = model;
    bad.parent.terms.clear();
    CHECK_THROWS_AS(log_likelihood(bad, data, false), InvalidArgument);
}

TEST_CASE("low-rank likelihood and gradient equal the dense and structured oracles", "[gp][likelihood][lowrank]") {
    struct Case {
        Eigen::Index d, t;
        std::size_t r, terms;
        Eigen::Index rank;
        bool hierarchical;
        bool zero_kappa;  ///< κ → 0 (log κ = −40): the block-diagonal part is the noise alone
    };
    const Case cases[] = {{1, 7, 1, 1, 1, true, false},  {2, 6, 2, 2, 1, true, false}, {3, 8, 4, 2, 2, true, false},
                          {4, 30, 3, 2, 1, true, false}, {5, 20, 3, 1, 3, true, false}, {3, 12, 3, 2, 2, true, true},
                          {2, 9, 3, 2, 1, false, false}, {4, 20, 2, 1, 2, false, true}};
    for (const Case& c : cases) {
        HgpModel model = make_model(c.d, c.hierarchical, c.terms, c.rank);
        if (c.zero_kappa)
            for (Lmc* lmc : {&model.child, &model.parent})
                for (auto& term : lmc->terms) term.log_kappa.setConstant(-40.0);
        const HgpData data = make_data(c.d, c.t, c.r, 23 + c.r);
        const LikelihoodValue dense = log_likelihood(model, data, true, LikelihoodPath::Dense);
        const LikelihoodValue structured = log_likelihood(model, data, true, LikelihoodPath::Structured);
        REQUIRE(dense.ok());
        REQUIRE(structured.ok());
        for (int threads : {1, 2}) {
            const LikelihoodValue lr = log_likelihood(model, data, true, LikelihoodPath::LowRank, threads);
            REQUIRE(lr.ok());
            CHECK(lr.path == LikelihoodPath::LowRank);
            const double dv = relative_difference(lr.log_likelihood, dense.log_likelihood);
            const double dg = max_relative_difference(lr.gradient, dense.gradient);
            const double sv = relative_difference(lr.log_likelihood, structured.log_likelihood);
            const double sg = max_relative_difference(lr.gradient, structured.gradient);
            INFO("D=" << c.d << " T=" << c.t << " R=" << c.r << " Q=" << c.terms << " rank=" << c.rank
                      << (c.hierarchical ? " MOHGP" : " MOA") << (c.zero_kappa ? " kappa=0" : "") << " threads=" << threads
                      << ": vs dense value " << dv << " gradient " << dg << "; vs structured value " << sv
                      << " gradient " << sg << " (log p = " << lr.log_likelihood << ")");
            CHECK(dv < 1e-8);
            CHECK(dg < 1e-8);
            CHECK(sv < 1e-8);
            CHECK(sg < 1e-8);
        }
        // And against finite differences of the low-rank likelihood itself.
        const LikelihoodValue lr = log_likelihood(model, data, true, LikelihoodPath::LowRank, 1);
        const VecX fd = finite_difference_gradient(model, data, LikelihoodPath::LowRank);
        const double diff = max_relative_difference(lr.gradient, fd);
        INFO("low rank vs finite differences: " << diff);
        CHECK(diff < 1e-6);
    }
}

TEST_CASE("Auto picks the low-rank path when it is cheaper, singular blocks are a status",
          "[gp][likelihood][lowrank]") {
    // Many outputs, rank 1: M = Q·T columns against n = D·T.
    HgpModel model = make_model(12, true, 1, 1);
    const HgpData data = make_data(12, 25, 3);
    const LikelihoodValue a = log_likelihood(model, data, true);
    REQUIRE(a.ok());
    CHECK(a.path == LikelihoodPath::LowRank);
    const LikelihoodValue s = log_likelihood(model, data, true, LikelihoodPath::Structured);
    CHECK(relative_difference(a.log_likelihood, s.log_likelihood) < 1e-8);
    CHECK(max_relative_difference(a.gradient, s.gradient) < 1e-8);
    // One output, rank 1: the low-rank part is as wide as the matrix; the structured path is used.
    const HgpModel small = make_model(1, true, 2, 1);
    CHECK(log_likelihood(small, make_data(1, 20, 3), false).path == LikelihoodPath::Structured);
    // No noise and κ → 0: every block P_d is singular, the full covariance is not (W has full rank D):
    // the low-rank path reports it as a status; Auto (here the structured path, and in general the
    // fallback when the low-rank path fails) agrees with the structured path.
    HgpModel singular = make_model(2, true, 1, 2);
    singular.noise_floor = 0.0;
    singular.log_noise.setConstant(-800.0);
    for (Lmc* lmc : {&singular.child, &singular.parent})
        for (auto& term : lmc->terms) {
            term.log_kappa.setConstant(-800.0);
            term.kernel = KernelType::Matern32;
        }
    const HgpData few = make_data(2, 6, 2);
    const LikelihoodValue lr = log_likelihood(singular, few, false, LikelihoodPath::LowRank);
    CHECK_FALSE(lr.ok());
    CHECK_FALSE(lr.message.empty());
    const LikelihoodValue st = log_likelihood(singular, few, false, LikelihoodPath::Structured);
    const LikelihoodValue au = log_likelihood(singular, few, false, LikelihoodPath::Auto);
    CHECK(au.ok() == st.ok());
    if (st.ok()) CHECK(au.log_likelihood == st.log_likelihood);
    HgpData partial = make_data(2, 5, 2);
    partial.observed = {{true, true, false, true, true}};
    CHECK_THROWS_AS(log_likelihood(make_model(2, true), partial, false, LikelihoodPath::LowRank), InvalidArgument);
}

TEST_CASE("MOA synthesis trend from the replicates' mean equals conditioning on every replicate", "[gp][posterior]") {
    const Eigen::Index d = 2, t = 7;
    const std::size_t r = 3;
    const HgpModel model = make_model(d, false, 2, 1);
    const HgpData data = make_data(d, t, r, 41);
    // Oracle: every value of every child observes one f ~ GP(0, K_f): Σ = 1 1ᵀ ⊗ K_f + I ⊗ N.
    const MatX kf = lmc_covariance(model.child, data.times, data.times);
    MatX noise = MatX::Zero(d * t, d * t);
    for (Eigen::Index i = 0; i < d; ++i) noise.diagonal().segment(i * t, t).setConstant(model.noise_variance()[i]);
    const Eigen::Index rr = static_cast<Eigen::Index>(r);
    const MatX sigma = kron(MatX::Ones(rr, rr), kf) + kron(MatX::Identity(rr, rr), noise);
    VecX y(sigma.rows());
    for (std::size_t c = 0; c < r; ++c)
        for (Eigen::Index i = 0; i < d; ++i)
            y.segment(static_cast<Eigen::Index>(c) * d * t + i * t, t) = data.children[c].row(i).transpose();
    const VecX ts = VecX::LinSpaced(5, 0.1, 1.9);
    const MatX cross = kron(MatX::Ones(1, rr), lmc_covariance(model.child, ts, data.times));
    const VecX expected = cross * Eigen::LLT<MatX>(sigma).solve(y);
    const MatX trend = synthesis_trend(model, data, ts);
    VecX got(expected.size());
    for (Eigen::Index i = 0; i < d; ++i) got.segment(i * ts.size(), ts.size()) = trend.row(i).transpose();
    CHECK(max_relative_difference(got, expected) < 1e-10);
}
