// tensor::SampleDecoder: any list of samples decodes to the values of TuckerModel::reconstruct(), bit
// for bit (the rank search's measured errors are the stored model's own), and agrees with the
// mode products to rounding.
#include <catch2/catch.hpp>

#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hosvd.hpp"
#include "mocapdb/tensor/mode_product.hpp"
#include "mocapdb/tensor/sample_decoder.hpp"
#include "tensor_fixtures.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;
using mocapdb::test::random_tensor;
using mocapdb::test::rel_diff;

namespace {

// The model by the mode products in the textbook order (dof, time, sample).
Tensor3 by_mode_products(const TuckerModel& m) {
    Tensor3 t = mode_product(m.core, m.U[0], 0);
    t = mode_product(t, m.U[1], 1);
    return mode_product(t, m.U[2], 2);
}

}  // namespace

TEST_CASE("sample decoder: any list of samples gives reconstruct()'s values bit for bit (#16)", "[tensor][tucker]") {
    // Tiny ranks (where Eigen would pick coefficient-based products and matrix-vector products), and
    // larger ones; sample counts below and above the decoder's padded width, not multiples of 8.
    struct Case {
        Dims3 dims;
        Ranks ranks;
    };
    for (const Case& c : {Case{{6, 5, 23}, {2, 3, 1}}, Case{{6, 5, 23}, {3, 2, 4}}, Case{{20, 17, 301}, {9, 11, 40}},
                          Case{{12, 30, 70}, {12, 30, 70}}}) {
        const Tensor3 a = random_tensor(c.dims[0], c.dims[1], c.dims[2], 7);
        const TuckerModel m = hosvd(a, c.ranks);
        const Tensor3 full = m.reconstruct();
        CHECK(rel_diff(full, by_mode_products(m)) <= 1e-12);
        const SampleDecoder decoder(m);
        const Eigen::Index d = c.dims[0], t = c.dims[1], n = c.dims[2];
        const std::vector<std::vector<Eigen::Index>> lists = {
            {0}, {n - 1}, {n - 1, 0, n / 2}, {3, 3, 1}, [&] {
                std::vector<Eigen::Index> all;
                for (Eigen::Index s = n - 1; s >= 0; s -= 2) all.push_back(s);
                return all;
            }()};
        for (const auto& ids : lists) {
            MatX out;
            decoder.decode(ids, out);
            REQUIRE(out.rows() == d);
            REQUIRE(out.cols() == t * static_cast<Eigen::Index>(ids.size()));
            bool same = true;
            for (std::size_t i = 0; i < ids.size(); ++i)
                for (Eigen::Index f = 0; f < t; ++f)
                    for (Eigen::Index k = 0; k < d; ++k)
                        same = same && out(k, static_cast<Eigen::Index>(i) * t + f) == full(k, f, ids[i]);
            INFO("ranks " << c.ranks[0] << "x" << c.ranks[1] << "x" << c.ranks[2] << ", " << ids.size() << " samples");
            CHECK(same);
        }
    }
}

TEST_CASE("sample decoder: ranks beyond the core or the bases, and samples out of range, are refused", "[tensor][tucker]") {
    const TuckerModel m = hosvd(random_tensor(6, 5, 9, 3), {2, 3, 4});
    CHECK_THROWS_AS(SampleDecoder(m.core, {3, 3, 4}, m.U[0], m.U[1], m.U[2]), InvalidArgument);
    CHECK_THROWS_AS(SampleDecoder(m.core, {2, 3, 0}, m.U[0], m.U[1], m.U[2]), InvalidArgument);
    CHECK_THROWS_AS(SampleDecoder(m.core, {2, 3, 4}, m.U[0], m.U[1], m.U[2].leftCols(3)), InvalidArgument);
    const SampleDecoder decoder(m);
    MatX out;
    CHECK_THROWS_AS(decoder.decode({9}, out), InvalidArgument);
    CHECK_THROWS_AS(decoder.decode({-1}, out), InvalidArgument);
}
