// Truncated HOSVD, ST-HOSVD and the streamed Gram accumulation.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hooi.hpp"
#include "mocapdb/tensor/hosvd.hpp"
#include "mocapdb/tensor/mode_product.hpp"
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

namespace {

HosvdOptions sample_basis_by(SampleBasisMethod method) {
    HosvdOptions o;
    o.sample_basis = method;
    return o;
}

double max_spectrum_difference(const VecX& a, const VecX& b) {
    REQUIRE(a.size() == b.size());
    return (a - b).cwiseAbs().maxCoeff();
}

// ST-HOSVD as it was before issue #16: every basis from the dense Gram of its mode.
TuckerModel dense_st_hosvd(const Tensor3& a, const Ranks& r, const std::array<int, 3>& order) {
    TuckerModel m;
    Tensor3 b = a;
    for (const int n : order) {
        VecX ev;
        const auto un = static_cast<std::size_t>(n);
        m.U[un] = gram_eigenbasis(mode_gram(b, n), ev).leftCols(r[un]);
        b = mode_product_transposed(b, m.U[un], n);
    }
    m.core = b;
    m.ranks = r;
    return m;
}

}  // namespace

TEST_CASE("Projected sample basis equals the dense N by N one (#16)", "[tensor][hosvd]") {
    struct Case {
        const char* what;
        Tensor3 a;
    };
    const Case cases[] = {
        {"random, N < D T", random_tensor(6, 5, 20, 61)},
        {"random, N > D T", random_tensor(5, 4, 60, 62)},
        {"low rank + 1% noise, N > D T", low_rank_tensor({8, 9, 150}, {4, 5, 6}, 0.01, 63)},
        {"exactly low rank, N > D T (the projection leaves dof and time vectors out)",
         low_rank_tensor({8, 9, 150}, {4, 5, 6}, 0.0, 64)},
        {"sample rank 12 with full dof and time ranks, D T > 256 (randomized range)",
         low_rank_tensor({20, 15, 400}, {20, 15, 12}, 0.0, 65)},
        {"random, N > D T > 256 (the randomized range gives up early: no low rank)", random_tensor(20, 15, 400, 66)},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        const Dims3 dims = dims_of(c.a);
        const Eigen::Index dt = dims[0] * dims[1];
        const HosvdBases dense = hosvd_bases(c.a, sample_basis_by(SampleBasisMethod::Dense));
        const HosvdBases projected = hosvd_bases(c.a, sample_basis_by(SampleBasisMethod::Projected));
        const HosvdBases automatic = hosvd_bases(c.a);
        CHECK(dense.U[2].cols() == dims[2]);
        CHECK(projected.U[2].cols() <= std::min(dims[2], dt));
        if (dims[2] > dt) CHECK(automatic.U[2].cols() <= dt);  // Auto takes the projected path
        CHECK(orthonormality_error(projected.U[2]) < 1e-12);
        const double top = dense.spectra.squared_sv[2](0);
        for (std::size_t n = 0; n < 3; ++n) {
            CHECK(projected.spectra.dims[n] == dims[n]);
            const double diff = max_spectrum_difference(dense.spectra.squared_sv[n], projected.spectra.squared_sv[n]);
            INFO("mode " << n << ": largest eigenvalue difference " << diff << " (largest " << top << ")");
            CHECK(diff <= 1e-12 * top);
        }
        CHECK(projected.spectra.squared_norm == dense.spectra.squared_norm);
        // Leading sample vectors (well separated eigenvalues): equal, with the same signs.
        const Eigen::Index lead = std::min<Eigen::Index>(5, projected.U[2].cols());
        const double vdiff = (dense.U[2].leftCols(lead) - projected.U[2].leftCols(lead)).cwiseAbs().maxCoeff();
        INFO("leading " << lead << " sample vectors differ by " << vdiff);
        CHECK(vdiff <= 1e-8);
        const Ranks rank_list[] = {{1, 1, 1},
                                   {2, 3, 4},
                                   {dims[0], dims[1], std::min(dims[2], dt)},
                                   {dims[0] - 1, dims[1] - 2, std::min(dims[2], dt) / 2},
                                   dims};  // more sample columns than can carry energy: completed
        for (const Ranks& r : rank_list) {
            const TuckerModel hd = hosvd_from_bases(c.a, dense, r);
            const TuckerModel hp = hosvd_from_bases(c.a, projected, r);
            const double rd = rel_diff(hd.reconstruct(), hp.reconstruct());
            INFO("ranks " << r[0] << "x" << r[1] << "x" << r[2] << ": reconstructions differ by " << rd << ", fits "
                          << hd.fit << " / " << hp.fit << ", bounds " << hd.error_bound << " / " << hp.error_bound);
            CHECK(rd <= 1e-9);
            // Fit and bound are square roots of energies: compare the energies (near full ranks the
            // dense path's bound is the root of N rounding-level eigenvalues, the projected one's 0).
            const double ed = (1.0 - hd.fit) * (1.0 - hd.fit), ep = (1.0 - hp.fit) * (1.0 - hp.fit);
            CHECK(std::abs(ed - ep) <= 1e-12);
            const double norm2 = hd.data_norm * hd.data_norm;
            CHECK(std::abs(hd.error_bound * hd.error_bound - hp.error_bound * hp.error_bound) <= 1e-12 * norm2);
            CHECK(hp.U[2].rows() == dims[2]);
            CHECK(hp.U[2].cols() == r[2]);
            CHECK(orthonormality_error(hp.U[2]) < 1e-12);
        }
    }
}

TEST_CASE("sample_mode_basis, ST-HOSVD and HOOI without an N by N Gram (#16)", "[tensor][hosvd]") {
    const Tensor3 a = low_rank_tensor({6, 5, 200}, {4, 4, 9}, 0.02, 71);
    VecX ev_dense, ev;
    const MatX dense = gram_eigenbasis(mode_gram(a, 2), ev_dense);
    const MatX u = sample_mode_basis(a, 12, ev);
    REQUIRE(u.rows() == 200);
    REQUIRE(u.cols() == 12);
    CHECK(max_spectrum_difference(ev_dense, ev) <= 1e-12 * ev_dense(0));
    CHECK((dense.leftCols(9) - u.leftCols(9)).cwiseAbs().maxCoeff() <= 1e-8);
    CHECK(orthonormality_error(sample_mode_basis(a, 200, ev)) < 1e-12);  // completed to N columns
    CHECK_THROWS_AS(sample_mode_basis(a, 0, ev), InvalidArgument);
    CHECK_THROWS_AS(sample_mode_basis(a, 201, ev), InvalidArgument);

    const Ranks r{4, 4, 9};
    for (const std::array<int, 3>& order : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{2, 0, 1}}) {
        const TuckerModel s = st_hosvd(a, r, order);
        const TuckerModel oracle = dense_st_hosvd(a, r, order);
        const double rd = rel_diff(oracle.reconstruct(), s.reconstruct());
        INFO("order " << order[0] << order[1] << order[2] << ": differs from the dense ST-HOSVD by " << rd);
        CHECK(rd <= 1e-9);
    }
    const TuckerModel h = hosvd(a, r);
    const TuckerModel o = hooi(a, r);
    CHECK(o.fit >= h.fit - 1e-12);
    CHECK(orthonormality_error(o.U[2]) < 1e-12);
    CHECK(relative_error(a, o) <= relative_error(a, h) + 1e-12);
}

TEST_CASE("The projected path's factored core equals the projected full core (#16)", "[tensor][hosvd]") {
    struct Case {
        const char* what;
        Tensor3 a;
        bool spans;  // the sample basis spans the projected samples (not the randomized range)
    };
    const Case cases[] = {
        {"low rank + 1% noise: the samples as stored", low_rank_tensor({8, 9, 150}, {4, 5, 6}, 0.01, 91), true},
        {"exactly low rank: dof and time vectors left out", low_rank_tensor({8, 9, 150}, {4, 5, 6}, 0.0, 92), true},
        {"sample rank 12, D T > 256: randomized range", low_rank_tensor({20, 15, 400}, {20, 15, 12}, 0.0, 93), false},
        {"random, D T > 256: the range gives up, exact Gram", random_tensor(20, 15, 400, 94), true},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        const HosvdBases b = hosvd_bases(c.a);
        REQUIRE(b.factored_core.size() > 0);
        const Tensor3 full = hosvd_full_core(c.a, b);
        REQUIRE(dims_of(b.factored_core) == dims_of(full));
        const double rd = rel_diff(b.factored_core, full);
        INFO("relative difference " << rd);
        CHECK(rd <= 1e-10);
        CHECK(b.spans_projected_samples == c.spans);
        const Dims3 dims = dims_of(c.a);
        REQUIRE(b.projected_dofs >= 1);
        REQUIRE(b.projected_dofs <= dims[0]);
        REQUIRE(b.projected_frames >= 1);
        REQUIRE(b.projected_frames <= dims[1]);
        if (!c.spans) continue;
        // Spanning: the model over every sample column, at ranks up to k0 x k1, is each sample's
        // projection on the leading dof and time vectors (what the rank search's truncation
        // reconstruction relies on).
        for (const Ranks r : {Ranks{b.projected_dofs, b.projected_frames, b.U[2].cols()},
                              Ranks{std::max<Eigen::Index>(1, b.projected_dofs - 1), b.projected_frames, b.U[2].cols()}}) {
            const MatX u0 = b.U[0].leftCols(r[0]), u1 = b.U[1].leftCols(r[1]);
            const Tensor3 projection = mode_product(
                mode_product(mode_product_transposed(mode_product_transposed(c.a, u0, 0), u1, 1), u0, 0), u1, 1);
            const double pd = rel_diff(hosvd_from_core(b, b.factored_core, r).reconstruct(), projection);
            INFO("ranks " << r[0] << "x" << r[1] << "x" << r[2] << ": differs from the projection by " << pd);
            CHECK(pd <= 1e-10);
        }
    }
    // The dense path makes none (hosvd_full_core projects).
    CHECK(hosvd_bases(random_tensor(6, 5, 20, 95)).factored_core.size() == 0);
}

TEST_CASE("A truncated HOSVD is a block of the full core (#16: one projection per rank search)", "[tensor][hosvd]") {
    // Both sample-basis paths; N = 300 spans several projection chunks and both halves of the samples.
    const Tensor3 cases[] = {random_tensor(6, 5, 20, 81), low_rank_tensor({8, 9, 300}, {5, 6, 10}, 0.01, 82)};
    for (const Tensor3& a : cases) {
        const Dims3 dims = dims_of(a);
        const HosvdBases b = hosvd_bases(a);
        const Tensor3 full = hosvd_full_core(a, b);
        REQUIRE(full.dimension(0) == dims[0]);
        REQUIRE(full.dimension(1) == dims[1]);
        REQUIRE(full.dimension(2) == b.U[2].cols());
        const Ranks rank_list[] = {{1, 1, 1}, {2, 3, 4}, {dims[0] - 1, dims[1], b.U[2].cols()}};
        for (const Ranks& r : rank_list) {
            const TuckerModel from_core = hosvd_from_core(b, full, r);
            const TuckerModel from_bases = hosvd_from_bases(a, b, r);
            INFO(dims[0] << "x" << dims[1] << "x" << dims[2] << " at ranks " << r[0] << "x" << r[1] << "x" << r[2]);
            CHECK(from_core.ranks == r);
            CHECK(rel_diff(from_core.core, from_bases.core) <= 1e-12);
            for (std::size_t n = 0; n < 3; ++n) CHECK(from_core.U[n] == from_bases.U[n]);
            CHECK(from_core.error_bound == from_bases.error_bound);
            CHECK(std::abs(from_core.fit - from_bases.fit) <= 1e-12);
            CHECK(rel_diff(from_core.reconstruct(), from_bases.reconstruct()) <= 1e-12);
        }
        // A sample rank beyond the core's columns is the caller's to complete (hosvd_from_bases).
        if (b.U[2].cols() < dims[2])
            CHECK_THROWS_AS(hosvd_from_core(b, full, {1, 1, b.U[2].cols() + 1}), InvalidArgument);
        // Taking the bases (their factored core as the full core, where there is one) gives the
        // copying overload's model bit for bit.
        for (const Ranks& r : rank_list) {
            HosvdBases taken = b;
            const Tensor3& core = b.factored_core.size() > 0 ? taken.factored_core : full;
            const TuckerModel copied = hosvd_from_core(b, b.factored_core.size() > 0 ? b.factored_core : full, r);
            const TuckerModel moved = hosvd_from_core(std::move(taken), core, r);
            for (std::size_t n = 0; n < 3; ++n) CHECK(moved.U[n] == copied.U[n]);
            CHECK(rel_diff(moved.core, copied.core) == 0.0);
            CHECK(moved.fit == copied.fit);
            CHECK(moved.error_bound == copied.error_bound);
            CHECK(taken.U[2].size() == 0);
            CHECK(taken.factored_core.size() == 0);
        }
    }
}
