// fit_coefficient_kernel's leave-one-out choice of the exponent and shape (kernel_fit.hpp): its errors are
// computed on the values reduced to N columns, and must be those of the full values.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

using namespace mocapdb;

namespace {

// c: n by 2 standard normal parameters; values: n by s, field(c(i, 0), c(i, 1), j) plus Gaussian noise of
// standard deviation noise (drawn after c, value by value).
template <class Field>
void random_design(Eigen::Index n, Eigen::Index s, unsigned seed, double noise, MatX& c, MatX& values, Field field) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal;
    c.resize(n, 2);
    values.resize(n, s);
    for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] = normal(rng);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < s; ++j)
            values(i, j) = field(c(i, 0), c(i, 1), static_cast<double>(j)) + noise * normal(rng);
}

}  // namespace

TEST_CASE("the exponent's leave-one-out error equals that of the full values", "[synthesis]") {
    // Many more values per sample than samples (S = 300 >> N = 20), a smooth field plus noise, as the core
    // slices of a Tucker model are.
    MatX c, values;
    random_design(20, 300, 7, 0.1, c, values, [](double c0, double c1, double j) {
        return std::sin(0.7 * c0 + 0.01 * j) * std::cos(c1);
    });
    const synthesis::SynthesisOptions options;
    const synthesis::KernelFit fit = synthesis::fit_coefficient_kernel(c, values, options, "test");
    REQUIRE(fit.exponent_loo_mse.size() == static_cast<Eigen::Index>(options.exponent_grid.size()));
    // The criterion: the leave-one-out MSE (the chosen grid shape's sill scale does not change the weights).
    const auto loo_mse = [&](const MatX& v, const kriging::VariogramModel& m) {
        return kriging::Kriging::build(c, m, options.kriging).leave_one_out(v).mse;
    };
    const double full = loo_mse(values, fit.variogram);
    CHECK(fit.exponent_loo_mse.minCoeff() == Approx(full).epsilon(1e-9));
    // Fewer values than samples take the direct path: the same identity.
    const MatX few = values.leftCols(5);
    const synthesis::KernelFit fit_few = synthesis::fit_coefficient_kernel(c, few, options, "test");
    const double full_few = loo_mse(few, fit_few.variogram);
    CHECK(fit_few.exponent_loo_mse.minCoeff() == Approx(full_few).epsilon(1e-12));
}

TEST_CASE("the leave-one-out shape search predicts the left-out samples at least as well as the least-squares fit",
          "[synthesis]") {
    // Short-range structure on a coarse design (the experimental variogram's bins mix it with the noise),
    // plus a linear drift, in 2 parameters.
    MatX c, values;
    random_design(24, 40, 11, 0.2, c, values, [](double c0, double c1, double j) {
        return 0.5 * c0 - 0.3 * c1 + std::sin(3.0 * c0 + 0.1 * j) * std::cos(2.0 * c1);
    });
    synthesis::SynthesisOptions least_squares;
    least_squares.shape_selection = synthesis::SynthesisOptions::ShapeSelection::LeastSquares;
    const synthesis::SynthesisOptions loo;  // the default
    const auto loo_mse = [&](const kriging::VariogramModel& m, const kriging::KrigingOptions& ko) {
        return kriging::Kriging::build(c, m, ko).leave_one_out(values).mse;
    };
    const synthesis::KernelFit a = synthesis::fit_coefficient_kernel(c, values, least_squares, "test");
    const synthesis::KernelFit b = synthesis::fit_coefficient_kernel(c, values, loo, "test");
    const double error_ls = loo_mse(a.variogram, least_squares.kriging);
    const double error_loo = loo_mse(b.variogram, loo.kriging);
    CHECK(error_loo <= error_ls * (1.0 + 1e-12));
    // And both beat the trend alone (a pure nugget) on this correlated field.
    const kriging::VariogramModel nugget = kriging::VariogramModel::spherical(1.0, 0.0, 1.0);
    CHECK(error_loo < loo_mse(nugget, loo.kriging));
    REQUIRE(b.loo_mean_z2);
    CHECK(std::isfinite(*b.loo_mean_z2));
    // Bad options are refused.
    synthesis::SynthesisOptions bad;
    bad.range_fractions = {0.0};
    CHECK_THROWS_AS(synthesis::fit_coefficient_kernel(c, values, bad, "test"), InvalidArgument);
    bad = {};
    bad.nugget_shares = {1.0};
    CHECK_THROWS_AS(synthesis::fit_coefficient_kernel(c, values, bad, "test"), InvalidArgument);
}

TEST_CASE("above max_fit_samples the variogram is chosen on that many evenly spread samples", "[synthesis]") {
    MatX c, values;
    random_design(60, 40, 11, 0.05, c, values, [](double c0, double c1, double j) {
        return std::sin(0.8 * c0 + 0.05 * j) + 0.5 * c1;
    });
    synthesis::SynthesisOptions options;
    options.max_fit_samples = 20;
    int calls = 0;
    std::uint64_t last_done = 0, total = 0;
    options.fit_progress = [&](const Progress& p) {
        ++calls;
        CHECK(p.done >= last_done);
        last_done = p.done;
        total = p.total;
    };
    const synthesis::KernelFit sub = synthesis::fit_coefficient_kernel(c, values, options, "test");
    CHECK(sub.fit_samples == 20);
    CHECK(calls >= 2);
    CHECK(last_done == total);  // the last call says done
    // The same as fitting the rows round(i * 59 / 19) themselves.
    MatX cs(20, 2), vs(20, values.cols());
    for (Eigen::Index i = 0; i < 20; ++i) {
        const auto row = static_cast<Eigen::Index>(std::lround(59.0 * static_cast<double>(i) / 19.0));
        cs.row(i) = c.row(row);
        vs.row(i) = values.row(row);
    }
    options.fit_progress = {};
    const synthesis::KernelFit direct = synthesis::fit_coefficient_kernel(cs, vs, options, "test");
    CHECK(direct.fit_samples == 20);
    CHECK(direct.variogram.to_string() == sub.variogram.to_string());
    // All samples: a fit of its own (N of them).
    options.max_fit_samples = 60;
    CHECK(synthesis::fit_coefficient_kernel(c, values, options, "test").fit_samples == 60);
    options.max_fit_samples = 1;
    CHECK_THROWS_AS(synthesis::fit_coefficient_kernel(c, values, options, "test"), InvalidArgument);
}
