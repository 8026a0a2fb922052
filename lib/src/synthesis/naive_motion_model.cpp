#include "mocapdb/synthesis/naive_motion_model.hpp"

#include <string>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::synthesis {
namespace {

/// Rows vec(X_i), X = (A - mean) w (N by D T).
MatX weighted_sample_rows(const AlignedSet& aligned, const VecX& weight) {
    if (weight.size() != aligned.dofs())
        throw InvalidArgument("naive synthesis model: weight must have D = " + std::to_string(aligned.dofs()) +
                              " entries, got " + std::to_string(weight.size()));
    const Tensor3 x = compression::weighted_centred(aligned.tensor, compression::dof_means(aligned.tensor), weight);
    const Eigen::Map<const MatX> cols(x.data(), aligned.dofs() * aligned.frames(), aligned.samples());
    return cols.transpose();
}

}  // namespace

NaiveMotionModel::NaiveMotionModel(const AlignedSet& aligned, const MotionSet& set,
                                   std::shared_ptr<const Skeleton> skeleton, double frame_rate, const VecX& weight,
                                   const SynthesisOptions& options)
    : SynthesisModel(
          checked_timing(aligned), set, std::move(skeleton), frame_rate,
          [&aligned, &weight] { return weighted_sample_rows(aligned, weight); }, 0, options, "naive synthesis model") {
    if (!options.levels.empty())
        throw InvalidArgument(
            "naive synthesis model: the naive model has no levels of detail (options.levels must be empty)");
    const Eigen::Index d = aligned.dofs(), t_count = aligned.frames(), n = aligned.samples();
    frames_by_sample_.resize(d, t_count * n);
    for (Eigen::Index t = 0; t < t_count; ++t)
        for (Eigen::Index i = 0; i < n; ++i)
            for (Eigen::Index k = 0; k < d; ++k) frames_by_sample_(k, t * n + i) = aligned.tensor(k, t, i);
}

tensor::Ranks NaiveMotionModel::level_ranks(Eigen::Index level) const {
    if (level != 0) throw InvalidArgument("NaiveMotionModel::level_ranks: the naive model has only level 0");
    return {dofs(), frames(), samples()};
}

std::size_t NaiveMotionModel::memory_bytes() const {
    return SynthesisModel::memory_bytes() + static_cast<std::size_t>(frames_by_sample_.size()) * sizeof(double);
}

void NaiveMotionModel::coefficients_from_weights(const Eigen::Ref<const VecX>& w, Eigen::Ref<VecX> out) const {
    out = w;
}

void NaiveMotionModel::coefficients_from_weights_batch(const Eigen::Ref<const MatX>& w, MatX& out) const { out = w; }

void NaiveMotionModel::pose_from_coefficients(const Eigen::Ref<const VecX>& coefficients, double t,
                                              Eigen::Ref<VecX> out, Workspace& /*ws*/, Eigen::Index level) const {
    Eigen::Index t0 = 0, t1 = 0;
    double a = 0.0;
    frame_pair(t, level, t0, t1, a, "NaiveMotionModel::pose");
    const Eigen::Index n = samples();
    if (coefficients.size() != n || out.size() != dofs()) {
        throw InvalidArgument("NaiveMotionModel::pose: coefficients must have N = " + std::to_string(n) +
                              " entries and out D = " + std::to_string(dofs()) + ", got " +
                              std::to_string(coefficients.size()) + " and " + std::to_string(out.size()));
    }
    out.noalias() = frames_by_sample_.middleCols(t0 * n, n) * coefficients;
    if (a != 0.0) {
        out *= (1.0 - a);
        out.noalias() += a * (frames_by_sample_.middleCols(t1 * n, n) * coefficients);
    }
}

void NaiveMotionModel::poses_from_coefficients(const Eigen::Ref<const MatX>& coefficients, double t,
                                               Eigen::Ref<MatX> out, BatchWorkspace& /*ws*/, Eigen::Index level) const {
    Eigen::Index t0 = 0, t1 = 0;
    double a = 0.0;
    frame_pair(t, level, t0, t1, a, "NaiveMotionModel::poses");
    const Eigen::Index n = samples();
    if (coefficients.rows() != n || out.rows() != dofs() || out.cols() != coefficients.cols()) {
        throw InvalidArgument("NaiveMotionModel::poses: coefficients must be N = " + std::to_string(n) +
                              " by Q and out D = " + std::to_string(dofs()) + " by Q");
    }
    out.noalias() = frames_by_sample_.middleCols(t0 * n, n) * coefficients;
    if (a != 0.0) {
        out *= (1.0 - a);
        out.noalias() += a * (frames_by_sample_.middleCols(t1 * n, n) * coefficients);
    }
}

}  // namespace mocapdb::synthesis
