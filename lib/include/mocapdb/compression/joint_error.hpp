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
#include <memory>
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
    double dof_rmse = 0.0;   ///< RMS of the pose-vector difference over every value (cm and rad mixed)
    double rmse_cm = 0.0;    ///< sqrt(mean |p - p_hat|^2) over joints, frames, samples
    double mean_cm = 0.0;    ///< mean |p - p_hat|
    double max_cm = 0.0;
    double p99_cm = 0.0;     ///< 99th percentile of |p - p_hat| (nearest rank)
    WorstJoint worst;
    Eigen::Index positions = 0;  ///< number of (joint, frame, sample) positions compared
};

/// Joint positions (cm, canonical frame) of pose vectors: poses is D by F; returns 3J by F (rows
/// 3j..3j+2 hold joint j). Throws InvalidArgument when D does not match the skeleton's layout or a
/// value is not finite.
MatX pose_joint_positions(const Skeleton& skeleton, const Eigen::Ref<const MatX>& poses);

/// Compares approximations with one fixed reference (its joint positions are computed once).
/// Immutable after construction; measure() is thread-safe.
class JointErrorMeter {
public:
    /// reference: D by T by N pose vectors of `skeleton` (not normalized).
    JointErrorMeter(std::shared_ptr<const Skeleton> skeleton, const Tensor3& reference);

    const Skeleton& skeleton() const { return *skeleton_; }
    const Tensor3& reference() const { return reference_; }

    /// approx: same shape as the reference. Throws InvalidArgument on a shape mismatch or a
    /// non-finite value.
    JointErrorStats measure(const Tensor3& approx) const;
    /// True as soon as one joint of one frame is more than max_cm from the reference (the errors
    /// measure() computes: exceeds(a, e) == (measure(a).max_cm > e)), without keeping the errors:
    /// a failed check usually stops within the first samples. Same requirements as measure().
    bool exceeds(const Tensor3& approx, double max_cm) const;
    /// Per sample and frame: the largest joint error (cm), T by N. Same requirements as measure().
    MatX max_error_per_frame(const Tensor3& approx) const;

private:
    std::shared_ptr<const Skeleton> skeleton_;
    Tensor3 reference_;
    std::vector<MatX> reference_positions_;  ///< per sample: 3J by T
};

}  // namespace mocapdb::compression
