// Unfolding / folding and the n-mode product against brute-force element formulas.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "tensor_fixtures.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;
using mocapdb::test::random_matrix;
using mocapdb::test::random_tensor;

namespace {

// Column of element (i0, i1, i2) in the mode-n unfolding, written out per the documented convention.
Eigen::Index column_of(int mode, Eigen::Index i0, Eigen::Index i1, Eigen::Index i2, const Dims3& d) {
    if (mode == 0) return i1 + d[1] * i2;
    if (mode == 1) return i0 + d[0] * i2;
    return i0 + d[0] * i1;
}

}  // namespace

TEST_CASE("unfold agrees with the element formula and fold inverts it", "[tensor][unfold]") {
    const Tensor3 a = random_tensor(4, 5, 3, 1);
    const Dims3 d = dims_of(a);
    for (int mode = 0; mode < 3; ++mode) {
        const MatX m = unfold(a, mode);
        const Eigen::Index rows = d[static_cast<std::size_t>(mode)];
        REQUIRE(m.rows() == rows);
        REQUIRE(m.cols() == a.size() / rows);
        for (Eigen::Index i2 = 0; i2 < d[2]; ++i2)
            for (Eigen::Index i1 = 0; i1 < d[1]; ++i1)
                for (Eigen::Index i0 = 0; i0 < d[0]; ++i0) {
                    const Eigen::Index row = mode == 0 ? i0 : mode == 1 ? i1 : i2;
                    REQUIRE(m(row, column_of(mode, i0, i1, i2, d)) == a(i0, i1, i2));
                }
        const Tensor3 back = fold(m, mode, d);
        REQUIRE(dims_of(back) == d);
        for (Eigen::Index i = 0; i < a.size(); ++i) REQUIRE(back.data()[i] == a.data()[i]);
    }
}

TEST_CASE("mode product equals M times the unfolding, folded back", "[tensor][unfold]") {
    const Tensor3 a = random_tensor(4, 5, 3, 2);
    for (int mode = 0; mode < 3; ++mode) {
        const Eigen::Index in = a.dimension(mode);
        const MatX m = random_matrix(6, in, 3u + static_cast<unsigned>(mode));
        const Tensor3 b = mode_product(a, m, mode);
        Dims3 bd = dims_of(a);
        bd[static_cast<std::size_t>(mode)] = 6;
        REQUIRE(dims_of(b) == bd);
        // Brute force: b(j0, j1, j2) = sum_k m(j_mode, k) a(..k..).
        double max_err = 0.0;
        for (Eigen::Index j2 = 0; j2 < bd[2]; ++j2)
            for (Eigen::Index j1 = 0; j1 < bd[1]; ++j1)
                for (Eigen::Index j0 = 0; j0 < bd[0]; ++j0) {
                    double s = 0.0;
                    for (Eigen::Index k = 0; k < in; ++k) {
                        if (mode == 0) s += m(j0, k) * a(k, j1, j2);
                        if (mode == 1) s += m(j1, k) * a(j0, k, j2);
                        if (mode == 2) s += m(j2, k) * a(j0, j1, k);
                    }
                    max_err = std::max(max_err, std::abs(s - b(j0, j1, j2)));
                }
        INFO("mode " << mode << " max abs error " << max_err);
        CHECK(max_err < 1e-12);
        const MatX via_unfold = m * unfold(a, mode);
        CHECK((unfold(b, mode) - via_unfold).norm() < 1e-12 * via_unfold.norm());
        const Tensor3 bt = mode_product_transposed(a, m.transpose(), mode);
        CHECK(mocapdb::test::rel_diff(b, bt) < 1e-15);
    }
}

TEST_CASE("unfold, fold and mode_product reject bad arguments", "[tensor][unfold]") {
    const Tensor3 a = random_tensor(2, 3, 4, 5);
    CHECK_THROWS_AS(unfold(a, 3), InvalidArgument);
    CHECK_THROWS_AS(unfold(a, -1), InvalidArgument);
    CHECK_THROWS_AS(fold(MatX::Zero(2, 11), 0, {2, 3, 4}), InvalidArgument);
    CHECK_THROWS_AS(fold(MatX::Zero(2, 12), 1, {2, 3, 4}), InvalidArgument);
    CHECK_THROWS_AS(mode_product(a, MatX::Zero(5, 4), 1), InvalidArgument);
    CHECK_THROWS_AS(mode_product_transposed(a, MatX::Zero(4, 5), 1), InvalidArgument);
    CHECK_THROWS_WITH(mode_product(a, MatX::Zero(5, 4), 7), Catch::Contains("mode must be 0 (dof), 1 (time) or 2"));
}
