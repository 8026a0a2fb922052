#include "mocapdb/synthesis/motion_model.hpp"

#include <string>
#include <utility>

#include "mocapdb/core/error.hpp"

namespace mocapdb::synthesis {
namespace {

/// Checks the model against the aligned tensor; returns the key of its kernel inputs (kernel_fit.hpp).
std::uint64_t checked_key(const compression::SetModel& model, const AlignedTiming& aligned, const MotionSet& set,
                          const SynthesisOptions& options) {
    compression::check(model, "synthesis model");
    const tensor::Dims3 dims = model.tucker.dims();
    if (dims[0] != aligned.dofs() || dims[1] != aligned.frames() || dims[2] != aligned.samples()) {
        throw InvalidArgument("synthesis model: the model is " + std::to_string(dims[0]) + "x" +
                              std::to_string(dims[1]) + "x" + std::to_string(dims[2]) + " but the aligned tensor " +
                              std::to_string(aligned.dofs()) + "x" + std::to_string(aligned.frames()) + "x" +
                              std::to_string(aligned.samples()) + " (dofs x frames x samples): recompress the set");
    }
    return kernel_key(model, set, options);
}

}  // namespace

MotionModel::MotionModel(compression::SetModel model, const AlignedSet& aligned, const MotionSet& set,
                         std::shared_ptr<const Skeleton> skeleton, double frame_rate, const SynthesisOptions& options)
    : MotionModel(std::move(model), checked_timing(aligned), set, std::move(skeleton), frame_rate, options) {}

MotionModel::MotionModel(compression::SetModel model, const AlignedTiming& aligned, const MotionSet& set,
                         std::shared_ptr<const Skeleton> skeleton, double frame_rate, const SynthesisOptions& options)
    : SynthesisModel(
          aligned, set, std::move(skeleton), frame_rate, [&model] { return core_slice_values(model); },
          checked_key(model, aligned, set, options), options, "synthesis model"),
      model_(std::move(model)),
      u_sample_(model_.tucker.U[2]),
      inv_weight_(model_.weight.cwiseInverse()) {
    const tensor::Ranks& full = model_.tucker.ranks;
    level_ranks_.push_back(full);
    for (const tensor::Ranks& lod : options.levels) {
        for (int m = 0; m < 3; ++m) {
            if (lod[static_cast<std::size_t>(m)] < 1 ||
                lod[static_cast<std::size_t>(m)] > full[static_cast<std::size_t>(m)]) {
                throw InvalidArgument("synthesis model: level-of-detail ranks " + std::to_string(lod[0]) + "x" +
                                      std::to_string(lod[1]) + "x" + std::to_string(lod[2]) +
                                      " must lie within 1 and the model's ranks " + std::to_string(full[0]) + "x" +
                                      std::to_string(full[1]) + "x" + std::to_string(full[2]));
            }
        }
        level_ranks_.push_back(lod);
    }
    for (const tensor::Ranks& lod : level_ranks_) evaluators_.emplace_back(model_.tucker, lod);
    // Kriging: coefficients(c) = U_sample^T w(c) as one R3 by (N + K) product (kriging_predictor.hpp).
    // (The local kriging has no global operator to fold: coefficients() goes through its sparse weights.)
    if (report_.predictor == Predictor::Kriging && !local_kernel())
        folded_ = kriging::KrigingPredictor::build(kriging_, u_sample_);
}

tensor::Ranks MotionModel::level_ranks(Eigen::Index level) const {
    if (level < 0 || level >= levels())
        throw InvalidArgument("MotionModel::level_ranks: level " + std::to_string(level) + " outside [0, " +
                              std::to_string(levels() - 1) + "]");
    return level_ranks_[static_cast<std::size_t>(level)];
}

std::size_t MotionModel::memory_bytes() const {
    std::size_t bytes = SynthesisModel::memory_bytes();
    const auto add = [&bytes](Eigen::Index values) { bytes += static_cast<std::size_t>(values) * sizeof(double); };
    const tensor::TuckerModel& t = model_.tucker;
    add(t.core.size());
    for (const MatX& u : t.U) add(u.size());
    add(model_.mean.size() + model_.weight.size() + inv_weight_.size() + u_sample_.size());
    add(folded_.folded_operator().size());
    for (const tensor::Ranks& r : level_ranks_) {
        // PoseEvaluator: the smaller of its two precomputations (Auto order)
        const Eigen::Index dof_first = dofs() * r[1] * r[2];
        const Eigen::Index core_first = r[0] * r[1] * r[2] + dofs() * r[0];
        add(std::min(dof_first, core_first));
    }
    return bytes;
}

void MotionModel::coefficients_from_weights(const Eigen::Ref<const VecX>& w, Eigen::Ref<VecX> out) const {
    out.noalias() = u_sample_.transpose() * w;
}

void MotionModel::coefficients_from_weights_batch(const Eigen::Ref<const MatX>& w, MatX& out) const {
    if (out.rows() != u_sample_.cols() || out.cols() != w.cols()) out.resize(u_sample_.cols(), w.cols());
    out.noalias() = u_sample_.transpose() * w;
}

void MotionModel::pose_from_coefficients(const Eigen::Ref<const VecX>& coefficients, double t, Eigen::Ref<VecX> out,
                                         Workspace& ws, Eigen::Index level) const {
    Eigen::Index t0 = 0, t1 = 0;
    double a = 0.0;
    frame_pair(t, level, t0, t1, a, "MotionModel::pose");
    if (coefficients.size() != u_sample_.cols() || out.size() != dofs()) {
        throw InvalidArgument("MotionModel::pose: coefficients must have R3 = " + std::to_string(u_sample_.cols()) +
                              " entries and out D = " + std::to_string(dofs()) + ", got " +
                              std::to_string(coefficients.size()) + " and " + std::to_string(out.size()));
    }
    const MatX& ut = model_.tucker.U[1];
    if (ws.u_time.size() != ut.cols()) ws.u_time.resize(ut.cols());
    if (a == 0.0) {
        ws.u_time = ut.row(t0);
    } else {
        ws.u_time = (1.0 - a) * ut.row(t0) + a * ut.row(t1);
    }
    const Eigen::Map<const Eigen::RowVectorXd> u(coefficients.data(), coefficients.size());
    evaluators_[static_cast<std::size_t>(level)].evaluate(ws.u_time, u, out, ws.pose);
    out.array() = out.array() * inv_weight_.array() + model_.mean.array();
}

void MotionModel::poses_from_coefficients(const Eigen::Ref<const MatX>& coefficients, double t, Eigen::Ref<MatX> out,
                                          BatchWorkspace& ws, Eigen::Index level) const {
    Eigen::Index t0 = 0, t1 = 0;
    double a = 0.0;
    frame_pair(t, level, t0, t1, a, "MotionModel::poses");
    if (coefficients.rows() != u_sample_.cols() || out.rows() != dofs() || out.cols() != coefficients.cols()) {
        throw InvalidArgument("MotionModel::poses: coefficients must be R3 = " + std::to_string(u_sample_.cols()) +
                              " by Q and out D = " + std::to_string(dofs()) + " by Q");
    }
    const tensor::Ranks& r = level_ranks_[static_cast<std::size_t>(level)];
    const tensor::Ranks& full = model_.tucker.ranks;
    const MatX& ut = model_.tucker.U[1];
    if (ws.u_time.size() != r[1]) ws.u_time.resize(r[1]);
    ws.u_time = (1.0 - a) * ut.row(t0).head(r[1]) + a * ut.row(t1).head(r[1]);
    // Gt(i, k) = sum_j u_time(j) G(i, j, k) over the level's block, then diag(1/w) U_dof Gt: D by r3.
    if (ws.core_time.rows() != r[0] || ws.core_time.cols() != r[2]) ws.core_time.resize(r[0], r[2]);
    MatX& gt = ws.core_time;
    gt.setZero();
    const double* g = model_.tucker.core.data();
    for (Eigen::Index k = 0; k < r[2]; ++k)
        for (Eigen::Index j = 0; j < r[1]; ++j) {
            const double s = ws.u_time(j);
            const double* col = g + full[0] * j + full[0] * full[1] * k;
            for (Eigen::Index i = 0; i < r[0]; ++i) gt(i, k) += s * col[i];
        }
    if (ws.frame_matrix.rows() != dofs() || ws.frame_matrix.cols() != r[2]) ws.frame_matrix.resize(dofs(), r[2]);
    ws.frame_matrix.noalias() = model_.tucker.U[0].leftCols(r[0]) * gt;
    ws.frame_matrix = inv_weight_.asDiagonal() * ws.frame_matrix;
    out.noalias() = ws.frame_matrix * coefficients.topRows(r[2]);
    out.colwise() += model_.mean;
}

}  // namespace mocapdb::synthesis
