// The Tucker model: poses, samples and levels of detail against the full reconstruction.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hooi.hpp"
#include "tensor_fixtures.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;
using mocapdb::test::low_rank_tensor;
using mocapdb::test::random_tensor;
using mocapdb::test::rel_diff;

TEST_CASE("A reconstructed pose equals the fibre of the reconstructed tensor", "[tensor][tucker]") {
    const Tensor3 a = low_rank_tensor({15, 20, 12}, {5, 4, 6}, 0.1, 91);
    const TuckerModel m = hooi(a, Ranks{5, 4, 6});
    const Tensor3 full = m.reconstruct();
    const PoseEvaluator pre(m, PoseEvaluator::Order::DofPrecomputed);
    const PoseEvaluator cf(m, PoseEvaluator::Order::CoreFirst);
    PoseEvaluator::Workspace ws;
    VecX q(15);
    double worst = 0.0;
    for (Eigen::Index n = 0; n < 12; ++n) {
        const MatX sample = m.reconstruct_sample(n);
        for (Eigen::Index t = 0; t < 20; ++t) {
            VecX fibre(15);
            for (Eigen::Index d = 0; d < 15; ++d) fibre(d) = full(d, t, n);
            const double scale = fibre.norm() + 1e-300;
            worst = std::max(worst, (m.pose(t, n) - fibre).norm() / scale);
            worst = std::max(worst, (sample.col(t) - fibre).norm() / scale);
            const Eigen::RowVectorXd ut = m.U[1].row(t), us = m.U[2].row(n);
            worst = std::max(worst, (m.pose(ut, us) - fibre).norm() / scale);
            pre.evaluate(ut, us, q, ws);
            worst = std::max(worst, (q - fibre).norm() / scale);
            cf.evaluate(ut, us, q, ws);
            worst = std::max(worst, (q - fibre).norm() / scale);
        }
    }
    INFO("worst relative difference pose vs fibre " << worst);
    CHECK(worst <= 1e-12);
}

TEST_CASE("Level of detail: a rank prefix is the truncated model", "[tensor][tucker]") {
    const Tensor3 a = random_tensor(14, 16, 12, 92);
    const TuckerModel big = hosvd(a, {8, 9, 7});
    const Ranks lod{3, 4, 5};
    const TuckerModel small = hosvd(a, lod);
    // For HOSVD the prefix is exactly the lower-rank HOSVD.
    CHECK(rel_diff(small.reconstruct(), big.reconstruct(lod)) <= 1e-10);
    CHECK(rel_diff(small.reconstruct(), truncate(big, lod).reconstruct()) <= 1e-10);
    const Tensor3 full_lod = big.reconstruct(lod);
    const PoseEvaluator ev(big, lod);
    CHECK(ev.ranks() == lod);
    for (Eigen::Index n = 0; n < 12; n += 5) {
        for (Eigen::Index t = 0; t < 16; t += 3) {
            const Eigen::RowVectorXd ut = big.U[1].row(t), us = big.U[2].row(n);
            const VecX q1 = big.pose(ut, us, lod);
            const VecX q2 = ev.evaluate(ut, us);
            VecX fibre(14);
            for (Eigen::Index d = 0; d < 14; ++d) fibre(d) = full_lod(d, t, n);
            CHECK((q1 - fibre).norm() <= 1e-12 * fibre.norm());
            CHECK((q2 - fibre).norm() <= 1e-12 * fibre.norm());
        }
    }
    CHECK(big.parameter_count() == 8 * 9 * 7 + 14 * 8 + 16 * 9 + 12 * 7);
    CHECK(big.compression_ratio() == Approx(14.0 * 16 * 12 / static_cast<double>(big.parameter_count())));
}

TEST_CASE("Tucker model accessors reject bad arguments", "[tensor][tucker]") {
    const Tensor3 a = random_tensor(6, 7, 5, 93);
    const TuckerModel m = hosvd(a, {2, 3, 2});
    CHECK_THROWS_AS(m.reconstruct({3, 1, 1}), InvalidArgument);
    CHECK_THROWS_AS(m.reconstruct({0, 1, 1}), InvalidArgument);
    CHECK_THROWS_AS(m.reconstruct_sample(5), InvalidArgument);
    CHECK_THROWS_AS(m.pose(7, 0), InvalidArgument);
    CHECK_THROWS_AS(m.pose(0, -1), InvalidArgument);
    CHECK_THROWS_AS(m.pose(Eigen::RowVectorXd::Zero(2), Eigen::RowVectorXd::Zero(2)), InvalidArgument);
    CHECK_THROWS_AS(truncate(m, {1, 4, 1}), InvalidArgument);
    CHECK_THROWS_AS(PoseEvaluator(m, Ranks{2, 3, 3}), InvalidArgument);
    const PoseEvaluator ev(m);
    CHECK_THROWS_AS(ev.evaluate(Eigen::RowVectorXd::Zero(2), Eigen::RowVectorXd::Zero(2)), InvalidArgument);
    CHECK_THROWS_AS(relative_error(random_tensor(6, 7, 4, 1), m), InvalidArgument);
}
