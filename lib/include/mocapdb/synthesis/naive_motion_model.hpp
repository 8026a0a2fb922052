#pragma once
// The naive baseline of the multilinear paper: kriging directly on the uncompressed aligned tensor A
// (D by T by N). The coefficient vector of a motion is the kriging weight vector w(c) itself, and a pose
//     q(c, t) = sum_i w_i(c) ((1 - a) A(:, t0, i) + a A(:, t0 + 1, i))
// costs 2 D N multiply-adds (D N at an integer frame). The variogram is estimated on the distances
// ||X_i - X_j||_F between the weighted, centred samples X = (A - mean) w, which equal the compressed
// model's core-slice distances at full ranks: at full ranks both models give the same motions.
#include <memory>
#include <string>

#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb {}

namespace mocapdb::synthesis {

class NaiveMotionModel final : public SynthesisModel {
public:
    /// weight: D per-dof weights > 0 (compression::position_error_weights, as the compressed model);
    /// they only shape the variogram's distances. options.levels must be empty.
    NaiveMotionModel(const AlignedSet& aligned, const MotionSet& set, std::shared_ptr<const Skeleton> skeleton,
                     double frame_rate, const VecX& weight, const SynthesisOptions& options = {});

    const char* kind() const override { return "naive"; }
    Eigen::Index levels() const override { return 1; }
    tensor::Ranks level_ranks(Eigen::Index level) const override;
    Eigen::Index coefficient_size() const override { return samples(); }
    std::size_t memory_bytes() const override;

    void pose_from_coefficients(const Eigen::Ref<const VecX>& coefficients, double t, Eigen::Ref<VecX> out,
                                Workspace& ws, Eigen::Index level = 0) const override;
    void poses_from_coefficients(const Eigen::Ref<const MatX>& coefficients, double t, Eigen::Ref<MatX> out,
                                 BatchWorkspace& ws, Eigen::Index level = 0) const override;

private:
    void coefficients_from_weights(const Eigen::Ref<const VecX>& w, Eigen::Ref<VecX> out) const override;
    void coefficients_from_weights_batch(const Eigen::Ref<const MatX>& w, MatX& out) const override;

    MatX frames_by_sample_;  ///< D by (T N): block t (columns t N .. t N + N - 1) = A(:, t, :)
};

}  // namespace mocapdb::synthesis
