#pragma once
// The compressed synthesis model (the multilinear paper): a set's Tucker model
//     X = (A - mean) w  ~  G x_1 U_dof x_2 U_time x_3 U_sample
// plus universal kriging of the sample-mode coefficient rows u_i (rows of U_sample, N by R3). A pose
// at control parameters c and fractional aligned frame t is
//     q(c, t) = mean + (G x_1 U_dof x_2 u_time(t) x_3 u(c)) / w,
//     u(c) = sum_i w_i(c) u_i,  u_time(t) = (1 - a) U_time(t0, :) + a U_time(t0 + 1, :),
// with the kriging weights w(c) of synthesis_model.hpp (variogram on the core-slice distances
// ||G x_3 (u_i - u_j)||_F). A level of detail uses the leading (r1, r2, r3) block (tensor/tucker.hpp).
// Cost of one pose from a prepared coefficient vector: r1 r2 r3 + r1 r2 + D r1 multiply-adds (or
// D r2 r3, whichever is less; tensor::PoseEvaluator).
#include <memory>
#include <string>

#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb {}

namespace mocapdb::synthesis {

class MotionModel final : public SynthesisModel {
public:
    /// model: the set's SetModel (dims D x T x N of `timing`); timing: the aligned set's warps and shape
    /// (the model does not use the aligned tensor's values: Database::load_aligned_timing reads no more);
    /// set: the N by P parameters; skeleton: the set's; frame_rate > 0 of the synthesized clips.
    /// Throws InvalidArgument on mismatching shapes, a bad level, or too few samples (N >= 2).
    /// The model is taken by value: move a loaded one in (its core can be tens of MB).
    MotionModel(compression::SetModel model, const AlignedTiming& timing, const MotionSet& set,
                std::shared_ptr<const Skeleton> skeleton, double frame_rate, const SynthesisOptions& options = {});
    /// The same from a whole aligned set, which is validated first (validate(AlignedSet), the tensor's
    /// values included); the model equals the one built from timing_of(aligned).
    MotionModel(compression::SetModel model, const AlignedSet& aligned, const MotionSet& set,
                std::shared_ptr<const Skeleton> skeleton, double frame_rate, const SynthesisOptions& options = {});

    const char* kind() const override { return "tucker"; }
    Eigen::Index levels() const override { return static_cast<Eigen::Index>(evaluators_.size()); }
    tensor::Ranks level_ranks(Eigen::Index level) const override;
    Eigen::Index coefficient_size() const override { return u_sample_.cols(); }
    std::size_t memory_bytes() const override;

    void pose_from_coefficients(const Eigen::Ref<const VecX>& coefficients, double t, Eigen::Ref<VecX> out,
                                Workspace& ws, Eigen::Index level = 0) const override;
    void poses_from_coefficients(const Eigen::Ref<const MatX>& coefficients, double t, Eigen::Ref<MatX> out,
                                 BatchWorkspace& ws, Eigen::Index level = 0) const override;

    const compression::SetModel& set_model() const { return model_; }

private:
    void coefficients_from_weights(const Eigen::Ref<const VecX>& w, Eigen::Ref<VecX> out) const override;
    void coefficients_from_weights_batch(const Eigen::Ref<const MatX>& w, MatX& out) const override;

    compression::SetModel model_;
    MatX u_sample_;  ///< N by R3
    VecX inv_weight_;
    std::vector<tensor::Ranks> level_ranks_;
    std::vector<tensor::PoseEvaluator> evaluators_;
};

}  // namespace mocapdb::synthesis
