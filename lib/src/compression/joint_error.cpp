#include "mocapdb/compression/joint_error.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb::compression {
namespace {

MatX sample_slice(const Tensor3& a, Eigen::Index n) {
    const Eigen::Index d = a.dimension(0), t = a.dimension(1);
    return Eigen::Map<const MatX>(a.data() + n * d * t, d, t);
}

void check_same_shape(const Tensor3& reference, const Tensor3& approx) {
    for (int m = 0; m < 3; ++m)
        if (reference.dimension(m) != approx.dimension(m))
            throw InvalidArgument("joint error: the approximation is " + std::to_string(approx.dimension(0)) + " x " +
                                  std::to_string(approx.dimension(1)) + " x " + std::to_string(approx.dimension(2)) +
                                  ", the reference " + std::to_string(reference.dimension(0)) + " x " +
                                  std::to_string(reference.dimension(1)) + " x " +
                                  std::to_string(reference.dimension(2)));
}

}  // namespace

MatX pose_joint_positions(const Skeleton& skeleton, const Eigen::Ref<const MatX>& poses) {
    const FrameMatrix channels = from_pose_vectors(skeleton, poses, Canonicalization{});
    const auto joints = static_cast<Eigen::Index>(skeleton.size());
    MatX out(3 * joints, poses.cols());
    GlobalPose pose;
    for (Eigen::Index f = 0; f < poses.cols(); ++f) {
        forward_kinematics(skeleton, channels.row(f).data(), pose);
        for (Eigen::Index j = 0; j < joints; ++j) out.block<3, 1>(3 * j, f) = pose.positions[static_cast<std::size_t>(j)];
    }
    return out;
}

JointErrorMeter::JointErrorMeter(std::shared_ptr<const Skeleton> skeleton, const Tensor3& reference)
    : skeleton_(std::move(skeleton)), reference_(reference) {
    if (!skeleton_) throw InvalidArgument("JointErrorMeter: no skeleton");
    const PoseLayout layout(*skeleton_);
    if (reference_.dimension(0) != static_cast<Eigen::Index>(layout.dof_count()))
        throw InvalidArgument("JointErrorMeter: the reference has " + std::to_string(reference_.dimension(0)) +
                              " pose values per frame, the skeleton's pose vector has " +
                              std::to_string(layout.dof_count()));
    reference_positions_.reserve(static_cast<std::size_t>(reference_.dimension(2)));
    for (Eigen::Index n = 0; n < reference_.dimension(2); ++n)
        reference_positions_.push_back(pose_joint_positions(*skeleton_, sample_slice(reference_, n)));
}

JointErrorStats JointErrorMeter::measure(const Tensor3& approx) const {
    check_same_shape(reference_, approx);
    JointErrorStats s;
    const Eigen::Index samples = reference_.dimension(2), frames = reference_.dimension(1);
    const auto joints = static_cast<Eigen::Index>(skeleton_->size());

    double dof_sq = 0.0;
    for (Eigen::Index i = 0; i < reference_.size(); ++i) {
        const double e = approx.data()[i] - reference_.data()[i];
        dof_sq += e * e;
    }
    s.dof_rmse = std::sqrt(dof_sq / static_cast<double>(reference_.size()));

    std::vector<double> errors;
    errors.reserve(static_cast<std::size_t>(samples * frames * joints));
    double sum = 0.0, sum_sq = 0.0;
    for (Eigen::Index n = 0; n < samples; ++n) {
        const MatX p = pose_joint_positions(*skeleton_, sample_slice(approx, n));
        const MatX& r = reference_positions_[static_cast<std::size_t>(n)];
        for (Eigen::Index f = 0; f < frames; ++f)
            for (Eigen::Index j = 0; j < joints; ++j) {
                const double e = (p.block<3, 1>(3 * j, f) - r.block<3, 1>(3 * j, f)).norm();
                errors.push_back(e);
                sum += e;
                sum_sq += e * e;
                if (e > s.worst.error_cm || s.worst.sample < 0) {
                    s.worst = {n, f, skeleton_->joint(static_cast<std::size_t>(j)).name, e};
                }
            }
    }
    s.positions = static_cast<Eigen::Index>(errors.size());
    if (errors.empty()) return s;
    const double count = static_cast<double>(errors.size());
    s.mean_cm = sum / count;
    s.rmse_cm = std::sqrt(sum_sq / count);
    s.max_cm = s.worst.error_cm;
    // Nearest-rank percentile: the smallest value with at least 99% of the errors at or below it.
    const auto rank = static_cast<std::size_t>(std::ceil(0.99 * count)) - 1;
    std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(rank), errors.end());
    s.p99_cm = errors[rank];
    return s;
}

bool JointErrorMeter::exceeds(const Tensor3& approx, double max_cm) const {
    check_same_shape(reference_, approx);
    const Eigen::Index samples = reference_.dimension(2), frames = reference_.dimension(1);
    const auto joints = static_cast<Eigen::Index>(skeleton_->size());
    for (Eigen::Index n = 0; n < samples; ++n) {
        const MatX p = pose_joint_positions(*skeleton_, sample_slice(approx, n));
        const MatX& r = reference_positions_[static_cast<std::size_t>(n)];
        for (Eigen::Index f = 0; f < frames; ++f)
            for (Eigen::Index j = 0; j < joints; ++j)
                if ((p.block<3, 1>(3 * j, f) - r.block<3, 1>(3 * j, f)).norm() > max_cm) return true;
    }
    return false;
}

MatX JointErrorMeter::max_error_per_frame(const Tensor3& approx) const {
    check_same_shape(reference_, approx);
    const Eigen::Index samples = reference_.dimension(2), frames = reference_.dimension(1);
    const auto joints = static_cast<Eigen::Index>(skeleton_->size());
    MatX out = MatX::Zero(frames, samples);
    for (Eigen::Index n = 0; n < samples; ++n) {
        const MatX p = pose_joint_positions(*skeleton_, sample_slice(approx, n));
        const MatX& r = reference_positions_[static_cast<std::size_t>(n)];
        for (Eigen::Index f = 0; f < frames; ++f)
            for (Eigen::Index j = 0; j < joints; ++j)
                out(f, n) = std::max(out(f, n), (p.block<3, 1>(3 * j, f) - r.block<3, 1>(3 * j, f)).norm());
    }
    return out;
}

}  // namespace mocapdb::compression
