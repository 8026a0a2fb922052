// Truncated HOSVD, ST-HOSVD and the streamed Gram accumulation.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hosvd.hpp"
#include "tensor_fixtures.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;
using mocapdb::test::low_rank_tensor;
using mocapdb::test::random_tensor;
using mocapdb::test::rel_diff;

namespace {

double orthonormality_error(const MatX& u) {
    return (u.transpose() * u - MatX::Identity(u.cols(), u.cols())).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("HOSVD and ST-HOSVD at full ranks reconstruct exactly", "[tensor][hosvd]") {
    const Tensor3 a = random_tensor(9, 11, 7, 11);
    const Ranks full{9, 11, 7};
    for (const TuckerModel& m : {hosvd(a, full), st_hosvd(a, full)}) {
        const double err = relative_error(a, m);
        INFO(to_string(m.method) << ": relative error at full ranks " << err << ", bound " << m.error_bound);
        CHECK(err <= 1e-10);
        CHECK(m.error_bound <= 1e-6 * m.data_norm);
        for (const MatX& u : m.U) CHECK(orthonormality_error(u) < 1e-12);
    }
}

TEST_CASE("Truncated HOSVD error is within the discarded-singular-value bound", "[tensor][hosvd]") {
    struct Case {
        Tensor3 a;
        Ranks r;
    };
    const Case cases[] = {
        {random_tensor(12, 15, 10, 21), {4, 5, 3}},
        {low_rank_tensor({20, 25, 18}, {5, 4, 6}, 0.05, 22), {5, 4, 6}},
        {low_rank_tensor({20, 25, 18}, {5, 4, 6}, 0.05, 23), {3, 2, 4}},
        {random_tensor(94, 100, 92, 24), {22, 6, 24}},  // the paper's sizes
    };
    for (const Case& c : cases) {
        const TuckerModel h = hosvd(c.a, c.r);
        const double measured = absolute_error(c.a, h);
        const double fit_error = (1.0 - h.fit) * h.data_norm;
        INFO("ranks " << c.r[0] << "x" << c.r[1] << "x" << c.r[2] << ": measured " << measured << ", bound "
                      << h.error_bound << ", from fit " << fit_error << ", ||A|| " << h.data_norm);
        CHECK(measured <= h.error_bound * (1.0 + 1e-12));
        CHECK(std::abs(fit_error - measured) <= 1e-8 * h.data_norm);
        for (const MatX& u : h.U) CHECK(orthonormality_error(u) < 1e-12);

        // ST-HOSVD (every mode order) stays within the HOSVD bound, and its own bound is its error.
        for (const std::array<int, 3>& order : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{2, 0, 1}}) {
            const TuckerModel s = st_hosvd(c.a, c.r, order);
            const double st_err = absolute_error(c.a, s);
            INFO("st-hosvd order " << order[0] << order[1] << order[2] << ": measured " << st_err << ", own bound "
                                   << s.error_bound);
            CHECK(st_err <= h.error_bound * (1.0 + 1e-12));
            CHECK(std::abs(st_err - s.error_bound) <= 1e-7 * h.data_norm);
        }
    }
}

TEST_CASE("HOSVD of an exactly low-rank tensor is exact at its ranks", "[tensor][hosvd]") {
    const Tensor3 a = low_rank_tensor({14, 16, 12}, {3, 4, 5}, 0.0, 31);
    const TuckerModel h = hosvd(a, {3, 4, 5});
    const double err = relative_error(a, h);
    INFO("relative error " << err << ", bound " << h.error_bound / h.data_norm);
    CHECK(err <= 1e-10);
}

TEST_CASE("Streamed Gram accumulation equals the in-memory Gram matrices", "[tensor][hosvd]") {
    const Tensor3 a = random_tensor(13, 17, 9, 41);
    const double norm2 = squared_norm(a);
    // Oracle: the unfoldings times their transposes.
    MatX oracle[3];
    for (int n = 0; n < 3; ++n) {
        const MatX u = unfold(a, n);
        oracle[n] = u * u.transpose();
    }
    // One slice at a time, as a streaming reader would deliver them.
    GramAccumulator by_slice(13, 17);
    for (Eigen::Index k = 0; k < 9; ++k) {
        const MatX slice = Eigen::Map<const MatX>(a.data() + k * 13 * 17, 13, 17);
        by_slice.add_slice(slice);
    }
    // Uneven chunks (4, 4, 1 samples).
    GramAccumulator by_chunk(13, 17);
    for (Eigen::Index k0 = 0; k0 < 9; k0 += 4) {
        const Eigen::Index k = std::min<Eigen::Index>(4, 9 - k0);
        Tensor3 chunk(13, 17, k);
        std::copy(a.data() + k0 * 13 * 17, a.data() + (k0 + k) * 13 * 17, chunk.data());
        by_chunk.add_chunk(chunk);
    }
    for (const GramAccumulator* acc : {&by_slice, &by_chunk}) {
        CHECK(acc->samples() == 9);
        const double e0 = rel_diff(oracle[0], acc->dof_gram());
        const double e1 = rel_diff(oracle[1], acc->time_gram());
        INFO("dof Gram rel. diff " << e0 << ", time Gram rel. diff " << e1);
        CHECK(e0 <= 1e-12);
        CHECK(e1 <= 1e-12);
        CHECK(std::abs(acc->squared_norm() - norm2) <= 1e-12 * norm2);
    }
    for (int n = 0; n < 3; ++n) CHECK(rel_diff(oracle[n], mode_gram(a, n)) <= 1e-12);
    // Bases from the streamed Grams give the same HOSVD as the in-memory path.
    const HosvdBases streamed =
        hosvd_bases_from_grams(by_slice.dof_gram(), by_slice.time_gram(), mode_gram(a, 2), by_slice.squared_norm());
    const TuckerModel h1 = hosvd_from_bases(a, streamed, {4, 5, 3});
    const TuckerModel h2 = hosvd(a, {4, 5, 3}, HosvdOptions{2});
    CHECK(rel_diff(h1.reconstruct(), h2.reconstruct()) <= 1e-10);
}

TEST_CASE("HOSVD rejects bad arguments", "[tensor][hosvd]") {
    const Tensor3 a = random_tensor(4, 5, 6, 51);
    CHECK_THROWS_AS(hosvd(a, {0, 2, 2}), InvalidArgument);
    CHECK_THROWS_AS(hosvd(a, {2, 6, 2}), InvalidArgument);
    CHECK_THROWS_WITH(hosvd(a, {2, 6, 2}), Catch::Contains("ranks[1] (time) must be in [1, 5], got 6"));
    CHECK_THROWS_AS(st_hosvd(a, {2, 2, 7}), InvalidArgument);
    CHECK_THROWS_AS(st_hosvd(a, {2, 2, 2}, {0, 0, 1}), InvalidArgument);
    CHECK_THROWS_AS(hosvd(Tensor3(0, 5, 6), {1, 1, 1}), InvalidArgument);
    CHECK_THROWS_WITH(hosvd(Tensor3(4, 5, 0), {1, 1, 1}), Catch::Contains("must not be empty"));
    Tensor3 bad = a;
    bad(1, 2, 3) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(hosvd(bad, {1, 1, 1}), InvalidArgument);
    CHECK_THROWS_AS(hosvd(a, {1, 1, 1}, HosvdOptions{0}), InvalidArgument);
    CHECK_THROWS_AS(GramAccumulator(0, 3), InvalidArgument);
    GramAccumulator acc(4, 5);
    CHECK_THROWS_AS(acc.add_slice(MatX::Zero(4, 6)), InvalidArgument);
    CHECK_THROWS_AS(acc.add_slices(MatX::Zero(4, 12)), InvalidArgument);
}
