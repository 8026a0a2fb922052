#include "mocapdb/tensor/sample_decoder.hpp"

#include <algorithm>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/parallel_tasks.hpp"

namespace mocapdb::tensor {
namespace {

// Samples per task of decode_all (a multiple of 8: no padding but in the last).
constexpr Eigen::Index kSamplesPerTask = 256;

Eigen::Map<const MatX, 0, Eigen::OuterStride<>> leading_columns(const Eigen::Ref<const MatX>& u, Eigen::Index r) {
    return {u.data(), u.rows(), r, Eigen::OuterStride<>(u.outerStride())};
}

}  // namespace

SampleDecoder::SampleDecoder(const Tensor3& core, const Ranks& ranks, const Eigen::Ref<const MatX>& u0,
                             const Eigen::Ref<const MatX>& u1, const Eigen::Ref<const MatX>& u2)
    : u0_(leading_columns(u0, std::clamp<Eigen::Index>(ranks[0], 0, u0.cols()))),
      u1_(leading_columns(u1, std::clamp<Eigen::Index>(ranks[1], 0, u1.cols()))),
      u2_(leading_columns(u2, std::clamp<Eigen::Index>(ranks[2], 0, u2.cols()))) {
    const Eigen::Index r0 = ranks[0], r1 = ranks[1], r2 = ranks[2];
    const Eigen::Index f0 = core.dimension(0), f1 = core.dimension(1);
    if (r0 < 1 || r1 < 1 || r2 < 1 || r0 > f0 || r1 > f1 || r2 > core.dimension(2) || u0.cols() < r0 ||
        u1.cols() < r1 || u2.cols() < r2)
        throw InvalidArgument("SampleDecoder: ranks " + std::to_string(r0) + " x " + std::to_string(r1) + " x " +
                              std::to_string(r2) + " for a core of " + std::to_string(f0) + " x " + std::to_string(f1) +
                              " x " + std::to_string(core.dimension(2)) + " and bases of " + std::to_string(u0.cols()) +
                              ", " + std::to_string(u1.cols()) + ", " + std::to_string(u2.cols()) + " columns");
    core_.resize(r0 * r1, r2);
    for (Eigen::Index j = 0; j < r2; ++j)
        Eigen::Map<MatX>(core_.col(j).data(), r0, r1) =
            Eigen::Map<const MatX>(core.data() + j * f0 * f1, f0, f1).topLeftCorner(r0, r1);
}

SampleDecoder::SampleDecoder(const TuckerModel& model)
    : SampleDecoder(model.core, model.ranks, model.U[0], model.U[1], model.U[2]) {}

void SampleDecoder::decode(const std::vector<Eigen::Index>& ids, MatX& out) const {
    const Eigen::Index d = dofs(), t = frames(), n = samples();
    const Eigen::Index r0 = u0_.cols(), r1 = u1_.cols(), r2 = u2_.cols();
    const auto count = static_cast<Eigen::Index>(ids.size());
    const Eigen::Index width = (std::max(count, kColumns) + 7) / 8 * 8;
    MatX rows = MatX::Zero(width, r2);
    for (Eigen::Index i = 0; i < count; ++i) {
        const Eigen::Index s = ids[static_cast<std::size_t>(i)];
        if (s < 0 || s >= n)
            throw InvalidArgument("SampleDecoder: sample " + std::to_string(s) + " is not in [0, " + std::to_string(n) +
                                  ")");
        rows.row(i) = u2_.row(s);
    }
    MatX coefficients(r0 * r1, width);
    coefficients.noalias() = core_ * rows.transpose();
    MatX left(d, r1 * width);
    left.noalias() = u0_ * Eigen::Map<const MatX>(coefficients.data(), r0, r1 * width);
    // Each sample's last product on aligned copies: small products are evaluated coefficient by
    // coefficient with a vectorization that depends on the operands' alignment (FMA or not), which a
    // sample's place in `left` and `out` would otherwise change.
    out.resize(d, t * count);
    MatX block(d, r1), sample(d, t);
    for (Eigen::Index i = 0; i < count; ++i) {
        block = Eigen::Map<const MatX>(left.data() + i * d * r1, d, r1);
        sample.noalias() = block * u1_.transpose();
        Eigen::Map<MatX>(out.data() + i * d * t, d, t) = sample;
    }
}

Tensor3 SampleDecoder::decode_all() const {
    const Eigen::Index d = dofs(), t = frames(), n = samples();
    Tensor3 out(d, t, n);
    const auto tasks = static_cast<std::size_t>((n + kSamplesPerTask - 1) / kSamplesPerTask);
    run_parallel_tasks(tasks, [&](std::size_t c) {
        const Eigen::Index first = static_cast<Eigen::Index>(c) * kSamplesPerTask;
        std::vector<Eigen::Index> ids;
        for (Eigen::Index s = first; s < std::min(n, first + kSamplesPerTask); ++s) ids.push_back(s);
        MatX block;
        decode(ids, block);
        std::copy(block.data(), block.data() + block.size(), out.data() + first * d * t);
    });
    return out;
}

}  // namespace mocapdb::tensor
