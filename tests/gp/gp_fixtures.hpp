#pragma once
// Small deterministic models and data sets for the gp tests.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "mocapdb/gp/hierarchical_gp.hpp"

namespace mocapdb::gp::test {

inline LmcTerm make_term(KernelType kernel, double lengthscale, Eigen::Index d, Eigen::Index rank, double scale,
                         std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    LmcTerm t;
    t.kernel = kernel;
    t.log_lengthscale = std::log(lengthscale);
    t.W.resize(d, rank);
    for (Eigen::Index i = 0; i < t.W.size(); ++i) t.W.data()[i] = scale * normal(rng);
    t.log_kappa.resize(d);
    for (Eigen::Index i = 0; i < d; ++i) t.log_kappa[i] = std::log(scale * scale * (0.2 + 0.1 * static_cast<double>(i)));
    return t;
}

/// A hierarchical model with a mixed-kernel LMC in each layer.
inline HgpModel make_model(Eigen::Index d, bool hierarchical, std::size_t terms = 2, Eigen::Index rank = 1) {
    HgpModel m;
    m.hierarchical = hierarchical;
    for (std::size_t q = 0; q < terms; ++q) {
        const KernelType k = q % 2 == 0 ? KernelType::Rbf : KernelType::Matern32;
        m.child.terms.push_back(make_term(k, 0.3 + 0.4 * static_cast<double>(q), d, rank, 0.4, 11 + q));
        if (hierarchical) m.parent.terms.push_back(make_term(k, 0.8 + 0.5 * static_cast<double>(q), d, rank, 1.0, 31 + q));
    }
    m.log_noise = VecX::LinSpaced(d, std::log(0.01), std::log(0.05));
    m.noise_floor = 1e-6;
    return m;
}

/// R children, D outputs, T frames on [0, 2], values from a fixed generator (not from the model:
/// the likelihood identities hold for any data).
inline HgpData make_data(Eigen::Index d, Eigen::Index t, std::size_t r, std::uint64_t seed = 5) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    HgpData data;
    data.times = VecX::LinSpaced(t, 0.0, 2.0);
    for (std::size_t c = 0; c < r; ++c) {
        MatX y(d, t);
        for (Eigen::Index i = 0; i < d; ++i)
            for (Eigen::Index f = 0; f < t; ++f)
                y(i, f) = std::sin(2.0 * data.times[f] + static_cast<double>(i)) + 0.3 * normal(rng);
        data.children.push_back(y);
    }
    return data;
}

/// Central differences of the log likelihood on `path`, parameter by parameter.
inline VecX finite_difference_gradient(HgpModel model, const HgpData& data, LikelihoodPath path, double h = 1e-5) {
    const VecX p0 = model.parameters();
    VecX g(p0.size());
    for (Eigen::Index i = 0; i < p0.size(); ++i) {
        VecX p = p0;
        p[i] = p0[i] + h;
        model.set_parameters(p);
        const double fp = log_likelihood(model, data, false, path).log_likelihood;
        p[i] = p0[i] - h;
        model.set_parameters(p);
        const double fm = log_likelihood(model, data, false, path).log_likelihood;
        g[i] = (fp - fm) / (2.0 * h);
    }
    return g;
}

inline double relative_difference(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); }

inline double max_relative_difference(const VecX& a, const VecX& b) {
    // Relative to the larger vector's norm (entries near zero are compared against the scale).
    const double scale = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), 1e-300});
    return (a - b).cwiseAbs().maxCoeff() / scale;
}

/// `actual` has the value and gradient of `oracle` to `tolerance` (relative).
inline void check_same_likelihood(const LikelihoodValue& actual, const LikelihoodValue& oracle, double tolerance = 1e-8) {
    REQUIRE(actual.ok());
    REQUIRE(oracle.ok());
    const double dv = relative_difference(actual.log_likelihood, oracle.log_likelihood);
    const double dg = max_relative_difference(actual.gradient, oracle.gradient);
    INFO("value rel diff " << dv << ", gradient max rel diff " << dg << " (log p = " << actual.log_likelihood << ")");
    CHECK(dv < tolerance);
    CHECK(dg < tolerance);
}

}  // namespace mocapdb::gp::test

namespace mocapdb::gp::test {

/// A three-layer model (trend → group → child): make_model's layers plus a group LMC.
inline HgpModel make_grouped_model(Eigen::Index d, std::size_t terms = 2, Eigen::Index rank = 1) {
    HgpModel m = make_model(d, true, terms, rank);
    m.grouped = true;
    for (std::size_t q = 0; q < terms; ++q) {
        const KernelType k = q % 2 == 0 ? KernelType::Matern32 : KernelType::Rbf;
        m.group.terms.push_back(make_term(k, 0.5 + 0.3 * static_cast<double>(q), d, rank, 0.7, 51 + q));
    }
    return m;
}

}  // namespace mocapdb::gp::test
