// fit_coefficient_kernel's leave-one-out choice of the exponent (kernel_fit.hpp): its errors are computed
// on the values reduced to N columns, and must be those of the full values.
#include <catch2/catch.hpp>

#include <random>

#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

using namespace mocapdb;

TEST_CASE("the exponent's leave-one-out error equals that of the full values", "[synthesis]") {
    // Many more values per sample than samples (S = 300 >> N = 20), a smooth field plus noise, as the core
    // slices of a Tucker model are.
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    const Eigen::Index n = 20, s = 300;
    MatX c(n, 2), values(n, s);
    for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] = normal(rng);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < s; ++j)
            values(i, j) = std::sin(0.7 * c(i, 0) + 0.01 * static_cast<double>(j)) * std::cos(c(i, 1)) + 0.1 * normal(rng);
    const synthesis::SynthesisOptions options;
    const synthesis::KernelFit fit = synthesis::fit_coefficient_kernel(c, values, options, "test");
    REQUIRE(fit.exponent_loo_mse.size() == static_cast<Eigen::Index>(options.exponent_grid.size()));
    const double full = kriging::Kriging::build(c, fit.variogram, options.kriging).leave_one_out(values).mse;
    CHECK(fit.exponent_loo_mse.minCoeff() == Approx(full).epsilon(1e-9));
    // Fewer values than samples take the direct path: the same identity.
    const MatX few = values.leftCols(5);
    const synthesis::KernelFit fit_few = synthesis::fit_coefficient_kernel(c, few, options, "test");
    const double full_few = kriging::Kriging::build(c, fit_few.variogram, options.kriging).leave_one_out(few).mse;
    CHECK(fit_few.exponent_loo_mse.minCoeff() == Approx(full_few).epsilon(1e-12));
}
