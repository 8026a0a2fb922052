#pragma once
// Error metrics shared by compression, synthesis and evaluation: how far an approximation of a set
// of pose vectors is from the original, in the pose vector's own units and in centimetres of joint
// position after forward kinematics.
//
// Joint positions are computed the way a user gets them: pose vectors -> channels
// (from_pose_vectors, which projects a rotation onto the joint's channels when it has fewer than
// three) -> forward kinematics, in the canonical frame (a rigid motion of the whole sample, so
// distances are the world distances). Every joint counts, end sites included, on every frame of
// every sample (object space).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::compression {

/// Where the largest joint-position error occurred.
struct WorstJoint {
    Eigen::Index sample = -1;
    Eigen::Index frame = -1;
    std::string joint;
    double error_cm = 0.0;
};

struct JointErrorStats {
    double dof_rmse = 0.0;  ///< RMS of the pose-vector difference over every value (cm and rad mixed)
    double rmse_cm = 0.0;   ///< sqrt(mean |p - p_hat|^2) over joints, frames, samples
    double mean_cm = 0.0;   ///< mean |p - p_hat|
    double max_cm = 0.0;
    double p99_cm = 0.0;  ///< 99th percentile of |p - p_hat| (nearest rank), to float precision
    WorstJoint worst;
    Eigen::Index positions = 0;  ///< number of (joint, frame, sample) positions compared
};

/// Joint positions (cm, canonical frame) of pose vectors: poses is D by F; returns 3J by F (rows
/// 3j..3j+2 hold joint j). Throws InvalidArgument when D does not match the skeleton's layout or a
/// value is not finite.
MatX pose_joint_positions(const Skeleton& skeleton, const Eigen::Ref<const MatX>& poses);

/// An approximation of a D by T by N pose tensor given sample by sample (the whole
/// approximation of 10 000 windows need not be in memory). Called as approx(samples, out): writes the
/// pose vectors of the listed samples side by side into out, resized to D by (T samples.size())
/// (sample samples[i] in columns [i T, (i + 1) T), the tensor's storage order). The meter calls it
/// from several threads at once with different samples, so it must be safe to call concurrently.
using SampleApproximation = std::function<void(const std::vector<Eigen::Index>& samples, MatX& out)>;

/// Compares approximations with one fixed reference (its joint positions are computed once).
/// Immutable after construction; every method is thread-safe, and the measuring ones spread the
/// samples over the machine's cores (run_parallel_tasks); their figures do not depend on the number
/// of threads.
class JointErrorMeter {
public:
    /// How the meter holds its reference tensor.
    enum class Reference {
        Copied,    ///< the meter keeps its own copy
        Borrowed,  ///< the meter keeps a pointer: the caller keeps the tensor alive and unchanged
                   ///< while the meter lives (saves a copy of the set: 0.43 GB at 10 000 windows)
    };
    /// reference: D by T by N pose vectors of `skeleton` (not normalized).
    JointErrorMeter(std::shared_ptr<const Skeleton> skeleton, const Tensor3& reference,
                    Reference hold = Reference::Copied);
    /// The reference given as its weighted, centred tensor x = weighted_centred(poses, mean, weight)
    /// (set_model.hpp), borrowed: the caller keeps x alive and unchanged while the meter lives. The
    /// poses are read back as from_weighted_centred(x, mean, weight) does, a slice at a time: within a
    /// few units in the last place of the poses x was made from (#16: compress then holds the set
    /// once, not twice: 0.48 GB at 11 070 windows). Throws InvalidArgument on a dof-count mismatch or
    /// a weight that is not finite and > 0.
    JointErrorMeter(std::shared_ptr<const Skeleton> skeleton, const Tensor3& weighted_centred, const VecX& mean,
                    const VecX& weight);

    const Skeleton& skeleton() const { return *skeleton_; }

    /// approx: same shape as the reference. Throws InvalidArgument on a shape mismatch or a
    /// non-finite value.
    JointErrorStats measure(const Tensor3& approx) const;
    /// True as soon as one joint of one frame is more than max_cm from the reference (the errors
    /// measure() computes: exceeds(a, e) == (measure(a).max_cm > e)), without keeping the errors:
    /// a failed check usually stops within the first samples. Same requirements as measure().
    bool exceeds(const Tensor3& approx, double max_cm) const;
    /// Per sample and frame: the largest joint error (cm), T by N. Same requirements as measure().
    MatX max_error_per_frame(const Tensor3& approx) const;

    /// measure() of an approximation given sample by sample, unless a joint is more than max_cm
    /// from the reference: then it stops at the first chunk of samples where one is (the decision
    /// of exceeds()) and returns nothing. max_cm: any value, +infinity to always measure.
    /// suspects (optional): samples to check first, typically those where earlier approximations
    /// exceeded (a failing check usually stops after them); the sample found beyond max_cm is added
    /// to it (it keeps at most 64). beyond (optional): a joint beyond max_cm does not stop the
    /// check; every sample is measured and *beyond receives, in increasing order, every sample with
    /// a joint beyond max_cm (empty when there is none; which samples they are does not depend on the
    /// number of threads, unlike the one a stopping check finds first). Memory: the N T J errors as
    /// float, for the percentile (the other figures are summed in double, sample by sample), and a
    /// chunk of samples per thread. Throws InvalidArgument when approx writes a
    /// wrong shape or a non-finite value, and whatever approx throws.
    std::optional<JointErrorStats> measure_within(const SampleApproximation& approx, double max_cm,
                                                  std::vector<Eigen::Index>* suspects = nullptr,
                                                  std::vector<Eigen::Index>* beyond = nullptr) const;

    /// Whether one of `samples` (each in [0, N)) has a joint more than max_cm from the reference,
    /// checked as measure_within() checks every sample (the suspects first, then the samples in
    /// chunks on the machine's cores, stopping at the first chunk with one); only the listed samples
    /// are reconstructed. The answer does not depend on the number of threads. Throws InvalidArgument
    /// on a sample out of range, and as measure_within().
    bool exceeds_on(const SampleApproximation& approx, const std::vector<Eigen::Index>& samples, double max_cm,
                    std::vector<Eigen::Index>* suspects = nullptr) const;

private:
    std::shared_ptr<const Skeleton> skeleton_;
    std::shared_ptr<const Tensor3> owned_;   ///< the copy, when Reference::Copied
    const Tensor3* reference_ = nullptr;     ///< owned_ or the caller's tensor
    std::vector<MatX> reference_positions_;  ///< per sample: 3J by T
    VecX mean_, weight_;                     ///< non-empty: *reference_ is weighted and centred by them

    /// Sample n of the reference poses (D by T): a view of the tensor, or read back into `buffer`.
    Eigen::Map<const MatX> reference_poses(Eigen::Index n, MatX& buffer) const;
    void compute_reference_positions();

    /// A measurement's per-sample results, at each sample's place (defined in joint_error.cpp).
    struct SampleFigures;
    /// Reconstructs and measures samples `ids`. Without `flagged`, returns the first sample with a
    /// joint beyond max_cm (its remaining errors unwritten), else -1; with it, measures them all and
    /// sets flagged[n] for each such sample. figures, when given, receive the samples' results.
    Eigen::Index check_samples(const SampleApproximation& approx, const std::vector<Eigen::Index>& ids, double max_cm,
                               const SampleFigures* figures, char* flagged) const;
    /// Whether one of the `suspects` (samples that failed earlier checks; those outside the set are
    /// skipped) has a joint beyond max_cm; moves that sample to the front of the list.
    bool a_suspect_exceeds(const SampleApproximation& approx, double max_cm, std::vector<Eigen::Index>* suspects) const;
};

}  // namespace mocapdb::compression
