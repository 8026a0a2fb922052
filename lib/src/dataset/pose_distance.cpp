#include "mocapdb/dataset/pose_distance.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/root_trajectory.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb::align {

MatX pose_features(const Clip& clip) {
    MatX p = joint_positions(clip);
    const VecX heading = root_headings(clip);
    const auto joints = p.rows() / 3;
    for (Eigen::Index f = 0; f < p.cols(); ++f) {
        const Vec3 root(p(0, f), 0.0, p(2, f));
        const Mat3 r = Eigen::AngleAxisd(-heading[f], Vec3::UnitY()).toRotationMatrix();
        for (Eigen::Index j = 0; j < joints; ++j) p.block<3, 1>(3 * j, f) = r * (p.block<3, 1>(3 * j, f) - root);
    }
    return p;
}

MatX pose_distance_matrix(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b) {
    if (a.rows() != b.rows() || a.rows() % 3 != 0 || a.rows() == 0)
        throw InvalidArgument("pose_distance_matrix: feature rows differ or are not 3 per joint (" +
                              std::to_string(a.rows()) + " vs " + std::to_string(b.rows()) + ")");
    // ‖x − y‖² = ‖x‖² + ‖y‖² − 2 xᵀy, as one matrix product.
    const VecX na = a.colwise().squaredNorm().transpose();
    const VecX nb = b.colwise().squaredNorm().transpose();
    MatX d(a.cols(), b.cols());
    d.noalias() = -2.0 * a.transpose() * b;
    d.colwise() += na;
    d.rowwise() += nb.transpose();
    const double joints = static_cast<double>(a.rows() / 3);
    return (d.array().max(0.0) / joints).sqrt().matrix();
}

double pose_distance(const Eigen::Ref<const VecX>& a, const Eigen::Ref<const VecX>& b) {
    if (a.size() != b.size() || a.size() % 3 != 0 || a.size() == 0)
        throw InvalidArgument("pose_distance: feature sizes differ or are not 3 per joint");
    return std::sqrt((a - b).squaredNorm() / static_cast<double>(a.size() / 3));
}

}  // namespace mocapdb::align
