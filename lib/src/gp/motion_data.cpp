#include "mocapdb/gp/motion_data.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb::gp {

std::vector<std::string> thesis_excluded_joints() {
    return {"lclavicle", "rclavicle", "lwrist", "rwrist", "lhand", "rhand",
            "lfingers",  "rfingers",  "lthumb", "rthumb", "ltoes", "rtoes"};
}

std::vector<std::string> pose_dof_names(const Skeleton& skeleton) {
    const PoseLayout layout(skeleton);
    std::vector<std::string> names;
    const auto& joints = layout.rotation_joints();
    const std::string root = skeleton.joint(joints.front()).name;
    for (const char* s : {"tx", "ty", "tz", "rx", "ry", "rz"}) names.push_back(root + "." + s);
    for (std::size_t k = 1; k < joints.size(); ++k)
        for (int c = 0; c < 3; ++c) names.push_back(skeleton.joint(joints[k]).name + "." + std::to_string(c));
    return names;
}

namespace {

std::vector<std::string> rotation_joint_names(const Skeleton& s) {
    std::vector<std::string> n;
    const PoseLayout layout(s);
    for (std::size_t j : layout.rotation_joints()) n.push_back(s.joint(j).name);
    return n;
}

/// Joint name owning pose row `row`.
std::string joint_of_row(const std::vector<std::string>& joint_names, std::size_t row) {
    return row < 6 ? joint_names.front() : joint_names[1 + (row - 6) / 3];
}

/// Pose vectors resampled at `times` (seconds from the clip start) by linear interpolation.
MatX resample(const MatX& poses, double rate, const VecX& times) {
    MatX out(poses.rows(), times.size());
    const Eigen::Index last = poses.cols() - 1;
    for (Eigen::Index i = 0; i < times.size(); ++i) {
        const double x = std::clamp(times[i] * rate, 0.0, static_cast<double>(last));
        const Eigen::Index f0 = std::min<Eigen::Index>(static_cast<Eigen::Index>(std::floor(x)), last);
        const Eigen::Index f1 = std::min<Eigen::Index>(f0 + 1, last);
        const double w = x - static_cast<double>(f0);
        out.col(i) = (1.0 - w) * poses.col(f0) + w * poses.col(f1);
    }
    return out;
}

}  // namespace

MotionData prepare_motion_data(const std::vector<Clip>& children, const std::vector<std::string>& names,
                               const MotionDataOptions& options) {
    if (children.empty()) throw InvalidArgument("prepare_motion_data: no children");
    if (names.size() != children.size()) throw InvalidArgument("prepare_motion_data: one name per child expected");
    if (options.frames < 2) throw InvalidArgument("prepare_motion_data: need ≥ 2 frames per child");
    const std::vector<std::string> joints = rotation_joint_names(*children.front().skeleton);
    double shortest = 1e300;
    for (std::size_t r = 0; r < children.size(); ++r) {
        validate(children[r]);
        if (children[r].frame_count() < 2)
            throw InvalidArgument("prepare_motion_data: child " + names[r] + " has fewer than 2 frames");
        if (rotation_joint_names(*children[r].skeleton) != joints)
            throw InvalidArgument("prepare_motion_data: child " + names[r] +
                                  "'s skeleton has other rotation joints than " + names.front() + "'s");
        shortest = std::min(shortest, children[r].duration());
    }
    double duration = shortest;
    if (options.duration) {
        if (!(*options.duration > 0.0)) throw InvalidArgument("prepare_motion_data: duration must be > 0");
        duration = std::min(duration, *options.duration);
    }
    MotionData out;
    out.skeleton = children.front().skeleton;
    out.child_names = names;
    const Eigen::Index n = static_cast<Eigen::Index>(options.frames);
    out.data.times = VecX::LinSpaced(n, 0.0, duration);
    out.frame_rate = static_cast<double>(n - 1) / duration;

    // Full pose vectors, branches of the first frame chosen near the first child's first frame.
    std::vector<MatX> full;
    VecX reference;
    for (const Clip& c : children) {
        const MatX p = to_pose_vectors(c, canonicalization_of(c), reference);
        if (reference.size() == 0) reference = p.col(0);
        full.push_back(resample(p, c.frame_rate, out.data.times));
    }
    const Eigen::Index rows = full.front().rows();
    out.template_pose = MatX::Zero(rows, n);
    for (const MatX& p : full) out.template_pose += p;
    out.template_pose /= static_cast<double>(full.size());

    const std::vector<std::string> dof_names = pose_dof_names(*out.skeleton);
    out.log_snr.assign(static_cast<std::size_t>(rows), 0.0);
    for (Eigen::Index row = 0; row < rows; ++row) {
        const std::string joint = joint_of_row(joints, static_cast<std::size_t>(row));
        const std::string& dn = dof_names[static_cast<std::size_t>(row)];
        double lo = 1e300, hi = -1e300, signal = 0.0, noise = 0.0;
        for (const MatX& p : full) {
            const VecX x = p.row(row).transpose();
            lo = std::min(lo, x.minCoeff());
            hi = std::max(hi, x.maxCoeff());
            signal += (x.array() - x.mean()).square().sum() / static_cast<double>(n);
            const VecX dx = x.tail(n - 1) - x.head(n - 1);
            noise += 0.5 * (dx.array() - dx.mean()).square().sum() / static_cast<double>(n - 1);
        }
        const double snr = noise > 0.0 ? std::log(signal / noise) : (signal > 0.0 ? 1e300 : -1e300);
        out.log_snr[static_cast<std::size_t>(row)] = snr;
        const bool listed_in = options.include_joints.empty() ||
                               std::find(options.include_joints.begin(), options.include_joints.end(), joint) !=
                                   options.include_joints.end();
        const bool listed_out = std::find(options.exclude_joints.begin(), options.exclude_joints.end(), joint) !=
                                options.exclude_joints.end();
        if (!listed_in || (options.include_joints.empty() && listed_out)) {
            out.dropped.push_back(dn + ": joint not selected");
            continue;
        }
        if (options.drop_constant && hi - lo <= options.constant_tolerance) {
            out.dropped.push_back(dn + ": constant");
            continue;
        }
        if (options.drop_noisy && snr < 0.0) {
            out.dropped.push_back(dn + ": log SNR " + std::to_string(snr) + " < 0");
            continue;
        }
        out.dofs.push_back(static_cast<std::size_t>(row));
        out.dof_names.push_back(dn);
    }
    if (out.dofs.empty()) throw InvalidArgument("prepare_motion_data: no dof left after the selection");
    const Eigen::Index d = static_cast<Eigen::Index>(out.dofs.size());
    out.minimum.resize(d);
    out.range.resize(d);
    for (Eigen::Index i = 0; i < d; ++i) {
        double lo = 1e300, hi = -1e300;
        for (const MatX& p : full) {
            lo = std::min(lo, p.row(static_cast<Eigen::Index>(out.dofs[static_cast<std::size_t>(i)])).minCoeff());
            hi = std::max(hi, p.row(static_cast<Eigen::Index>(out.dofs[static_cast<std::size_t>(i)])).maxCoeff());
        }
        out.minimum[i] = lo;
        out.range[i] = hi > lo ? hi - lo : 1.0;
    }
    for (const MatX& p : full) {
        MatX y(d, n);
        for (Eigen::Index i = 0; i < d; ++i)
            y.row(i) =
                (p.row(static_cast<Eigen::Index>(out.dofs[static_cast<std::size_t>(i)])).array() - out.minimum[i]) /
                out.range[i];
        out.data.children.push_back(y);
    }
    return out;
}

MatX denormalize(const MotionData& data, const MatX& normalized) {
    if (normalized.rows() != data.minimum.size())
        throw InvalidArgument("denormalize: expected " + std::to_string(data.minimum.size()) + " rows, found " +
                              std::to_string(normalized.rows()));
    MatX out(normalized.rows(), normalized.cols());
    for (Eigen::Index i = 0; i < normalized.rows(); ++i)
        out.row(i) = normalized.row(i).array() * data.range[i] + data.minimum[i];
    return out;
}

Clip reassemble_clip(const MotionData& data, const MatX& normalized, const std::string& name) {
    if (normalized.cols() != data.template_pose.cols())
        throw InvalidArgument("reassemble_clip: expected " + std::to_string(data.template_pose.cols()) +
                              " frames, found " + std::to_string(normalized.cols()));
    MatX full = data.template_pose;
    const MatX values = denormalize(data, normalized);
    for (Eigen::Index i = 0; i < values.rows(); ++i)
        full.row(static_cast<Eigen::Index>(data.dofs[static_cast<std::size_t>(i)])) = values.row(i);
    Clip clip;
    clip.skeleton = data.skeleton;
    clip.frame_rate = data.frame_rate;
    clip.channels = from_pose_vectors(*data.skeleton, full, Canonicalization{});
    clip.name = name;
    return clip;
}

}  // namespace mocapdb::gp
