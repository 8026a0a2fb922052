// Rank selection: explicit, by target error (bound, then measured), by compression ratio, by tolerance.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/rank_selection.hpp"
#include "tensor_fixtures.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;
using mocapdb::test::low_rank_tensor;
using mocapdb::test::random_tensor;

TEST_CASE("Rank selection recovers the multilinear rank of a noisy low-rank tensor", "[tensor][ranks]") {
    const Ranks truth[] = {{3, 4, 5}, {6, 2, 4}, {2, 3, 2}};  // each rank <= product of the others
    unsigned seed = 101;
    for (const Ranks& r : truth) {
        const Tensor3 a = low_rank_tensor({12, 14, 10}, r, 1e-6, seed++);
        const RankSelection by_error = select_ranks_for_error(a, 1e-3);
        const RankSelection by_bound = select_ranks_for_error(a, 1e-3, false);
        const RankSelection by_tol = select_ranks_for_tolerance(a, 1e-4);
        INFO("truth " << r[0] << "x" << r[1] << "x" << r[2] << "; by error " << by_error.ranks[0] << "x"
                      << by_error.ranks[1] << "x" << by_error.ranks[2] << " (measured " << by_error.measured_relative
                      << ", bound " << by_error.bound_relative << "); by tolerance " << by_tol.ranks[0] << "x"
                      << by_tol.ranks[1] << "x" << by_tol.ranks[2]);
        CHECK(by_error.ranks == r);
        CHECK(by_bound.ranks == r);
        CHECK(by_tol.ranks == r);
        CHECK(by_error.target_met);
        CHECK(by_error.measured_relative <= by_error.bound_relative * (1.0 + 1e-9));
        CHECK(by_error.measured_relative < 1e-5);
    }
}

TEST_CASE("Target error: measured error meets the target, bound-only choice is conservative", "[tensor][ranks]") {
    const Tensor3 a = low_rank_tensor({20, 24, 16}, {8, 6, 10}, 0.2, 111);
    for (const double target : {0.5, 0.3, 0.21, 0.1, 0.0}) {
        const RankSelection s = select_ranks_for_error(a, target);
        const RankSelection b = select_ranks_for_error(a, target, false);
        INFO("target " << target << ": measured " << s.measured_relative << " at " << s.ranks[0] << "x" << s.ranks[1]
                       << "x" << s.ranks[2] << " (" << s.parameters << " params), bound-only " << b.ranks[0] << "x"
                       << b.ranks[1] << "x" << b.ranks[2] << " (" << b.parameters << " params, bound "
                       << b.bound_relative << ", measured " << b.measured_relative << ")");
        CHECK(s.target_met);
        CHECK(s.measured_relative <= target + 1e-10);
        CHECK(b.bound_relative <= target * (1.0 + 1e-12) + 1e-12);
        CHECK(s.parameters <= b.parameters);
        CHECK(s.measured_relative <= s.bound_relative * (1.0 + 1e-9) + 1e-12);
    }
    // Target 0: full ranks (every singular value kept).
    const RankSelection z = select_ranks_for_error(a, 0.0, false);
    CHECK(z.ranks == Ranks{20, 24, 16});
}

TEST_CASE("Target compression ratio: ratio met with the smallest bound", "[tensor][ranks]") {
    const Tensor3 a = low_rank_tensor({10, 12, 8}, {4, 3, 5}, 0.1, 121);
    const HosvdBases b = hosvd_bases(a);
    for (const double ratio : {2.0, 4.0, 8.0}) {
        const RankSelection s = select_ranks_for_compression(a, ratio);
        CHECK(s.target_met);
        CHECK(s.compression_ratio >= ratio);
        // Brute force over every rank triple.
        double best = std::numeric_limits<double>::infinity();
        for (Eigen::Index i = 1; i <= 10; ++i)
            for (Eigen::Index j = 1; j <= 12; ++j)
                for (Eigen::Index k = 1; k <= 8; ++k) {
                    const Ranks r{i, j, k};
                    if (i > j * k || j > i * k || k > i * j) continue;
                    if (tucker_compression_ratio(b.spectra.dims, r) < ratio) continue;
                    best = std::min(best, hosvd_error_bound(b.spectra, r));
                }
        INFO("ratio " << ratio << ": chosen " << s.ranks[0] << "x" << s.ranks[1] << "x" << s.ranks[2] << " bound "
                      << s.bound_relative << ", brute-force best " << best / std::sqrt(b.spectra.squared_norm));
        CHECK(s.bound_relative * std::sqrt(b.spectra.squared_norm) == Approx(best).epsilon(1e-12));
        CHECK(s.measured_relative <= s.bound_relative * (1.0 + 1e-9));
    }
    const RankSelection impossible = select_ranks_for_compression(a, 1e6);
    CHECK_FALSE(impossible.target_met);
    CHECK(impossible.ranks == Ranks{1, 1, 1});
}

TEST_CASE("Rank selection rejects bad arguments", "[tensor][ranks]") {
    const Tensor3 a = random_tensor(4, 5, 6, 131);
    CHECK_THROWS_AS(select_ranks(a, {0, 1, 1}), InvalidArgument);
    CHECK_THROWS_AS(select_ranks(a, {5, 1, 1}), InvalidArgument);
    CHECK_THROWS_AS(select_ranks(Tensor3(0, 0, 0), {1, 1, 1}), InvalidArgument);
    CHECK_THROWS_AS(select_ranks_for_error(a, -0.1), InvalidArgument);
    CHECK_THROWS_AS(select_ranks_for_error(a, std::numeric_limits<double>::quiet_NaN()), InvalidArgument);
    CHECK_THROWS_AS(select_ranks_for_compression(a, 0.0), InvalidArgument);
    CHECK_THROWS_AS(select_ranks_for_tolerance(a, 1.0), InvalidArgument);
    CHECK_THROWS_AS(select_ranks_for_error(Tensor3(3, 0, 2), 0.1), InvalidArgument);
    const RankSelection s = select_ranks(a, {2, 3, 4});
    CHECK(s.ranks == Ranks{2, 3, 4});
    CHECK(s.measured_relative <= s.bound_relative * (1.0 + 1e-12));
}
