#include "truncation_reconstruction.hpp"

#include <algorithm>
#include <string>

#include "core_terms.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::compression::detail {

bool TruncationReconstruction::applies(const tensor::HosvdBases& bases, const tensor::Ranks& ranks) {
    const Tensor3& core = bases.factored_core;
    return bases.spans_projected_samples && core.size() > 0 && ranks[0] >= 1 && ranks[1] >= 1 && ranks[2] >= 0 &&
           ranks[0] <= bases.projected_dofs && ranks[1] <= bases.projected_frames && ranks[2] <= core.dimension(2) &&
           core.dimension(2) == bases.U[2].cols();
}

bool TruncationReconstruction::cheaper_than_direct(const tensor::HosvdBases& bases, const tensor::Ranks& ranks) {
    if (!applies(bases, ranks)) return false;
    const Eigen::Index d = bases.U[0].rows(), t = bases.U[1].rows();
    const Eigen::Index r0 = ranks[0], r1 = ranks[1], k = bases.factored_core.dimension(2);
    const Eigen::Index projections = r0 * d * t + r0 * t * r1 + d * r0 * r1 + d * r1 * t;
    return d * t * (k - ranks[2]) + projections < d * t * ranks[2];
}

TruncationReconstruction::TruncationReconstruction(const Tensor3& x, const tensor::HosvdBases& bases,
                                                   const tensor::Ranks& ranks, const VecX& mean, const VecX& weight)
    : x_(&x), bases_(&bases), ranks_(ranks), mean_(&mean), weight_(&weight) {
    const Eigen::Index d = bases.U[0].rows(), t = bases.U[1].rows();
    if (!applies(bases, ranks) || x.dimension(0) != d || x.dimension(1) != t || x.dimension(2) != bases.U[2].rows() ||
        mean.size() != d || weight.size() != d)
        throw InvalidArgument("TruncationReconstruction: ranks " + std::to_string(ranks[0]) + " x " +
                              std::to_string(ranks[1]) + " x " + std::to_string(ranks[2]) +
                              " are not within the projected path's bases, or the tensor of " +
                              std::to_string(x.dimension(0)) + " x " + std::to_string(x.dimension(1)) + " x " +
                              std::to_string(x.dimension(2)) + " is not theirs");
    core_terms(bases.factored_core, bases.U[0].leftCols(ranks[0]), bases.U[1].leftCols(ranks[1]), ranks[2],
               bases.factored_core.dimension(2), dropped_terms_);
}

void TruncationReconstruction::operator()(const std::vector<Eigen::Index>& samples, MatX& out) const {
    const Eigen::Index d = x_->dimension(0), t = x_->dimension(1), n = x_->dimension(2);
    const Eigen::Index r0 = ranks_[0], r1 = ranks_[1], first = ranks_[2];
    const auto dof = bases_->U[0].leftCols(r0);
    const auto time = bases_->U[1].leftCols(r1);
    const auto count = static_cast<Eigen::Index>(samples.size());
    const Eigen::Index dropped = dropped_terms_.cols();
    MatX coefficients(count, dropped);
    out.resize(d, t * count);
    MatX dof_side(r0, t), block(r0, r1), lifted(d, r1);
    for (Eigen::Index i = 0; i < count; ++i) {
        const Eigen::Index s = samples[static_cast<std::size_t>(i)];
        if (s < 0 || s >= n)
            throw InvalidArgument("TruncationReconstruction: sample " + std::to_string(s) + " is not in [0, " +
                                  std::to_string(n) + ")");
        coefficients.row(i) = bases_->U[2].row(s).segment(first, dropped);
        const Eigen::Map<const MatX> slice(x_->data() + s * d * t, d, t);
        dof_side.noalias() = dof.transpose() * slice;
        block.noalias() = dof_side * time;
        lifted.noalias() = dof * block;
        out.middleCols(i * t, t).noalias() = lifted * time.transpose();
    }
    if (dropped > 0) Eigen::Map<MatX>(out.data(), d * t, count).noalias() -= dropped_terms_ * coefficients.transpose();
    out = (out.array().colwise() / weight_->array()).matrix().colwise() + *mean_;
}

}  // namespace mocapdb::compression::detail
