#pragma once
// Motion clips as GP training data (thesis §5.1.2) and back: pick dofs of the pose vector, subsample
// every child to N frames over a common duration, min–max normalize, and reassemble predictions or
// samples into full clips (for BVH export).
//
// Details: docs/headers/gp.md (mocapdb/gp/motion_data.hpp).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/gp/hierarchical_gp.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb::gp {

/// The joints the thesis rejected by hand (CMU ASF names).
std::vector<std::string> thesis_excluded_joints();

struct MotionDataOptions {
    std::size_t frames = 90;  ///< N subsampled frames per child (≥ 2)
    /// Seconds from each child's start; default (and upper bound): the shortest child's duration.
    std::optional<double> duration;
    std::vector<std::string> exclude_joints = thesis_excluded_joints();  ///< names absent are ignored
    /// When non-empty: only these joints' dofs (the root's name selects the 6 root dofs).
    std::vector<std::string> include_joints;
    bool drop_constant = true;
    double constant_tolerance = 1e-6;
    bool drop_noisy = true;  ///< drop dofs with log SNR < 0
};

struct MotionData {
    HgpData data;  ///< D selected dofs, normalized to [0, 1], N frames, t in seconds
    std::vector<std::string> child_names;
    std::vector<std::size_t> dofs;       ///< selected pose-vector rows
    std::vector<std::string> dof_names;  ///< their names ("root.tx", "lfemur.1", ...)
    VecX minimum;                        ///< D values: normalized = (x − minimum) / range
    VecX range;
    std::vector<double> log_snr;               ///< per pose-vector row (all rows)
    std::vector<std::string> dropped;          ///< "NAME: reason" for every dof not selected
    MatX template_pose;                        ///< full pose vectors (pose size by N): the children's mean
    std::shared_ptr<const Skeleton> skeleton;  ///< the first child's (used for reassembly)
    double frame_rate = 0.0;                   ///< of the subsampled frames, (N − 1) / duration
};

/// Names of the pose-vector rows of a skeleton: "ROOT.tx/ty/tz", "ROOT.rx/ry/rz", then "JOINT.0/1/2".
std::vector<std::string> pose_dof_names(const Skeleton& skeleton);

/// Builds the training data from the children's clips (≥ 1). InvalidArgument when the clips' joint
/// structures differ (names of the rotation joints), a clip has fewer than 2 frames, options are out of
/// range, or no dof survives the selection.
MotionData prepare_motion_data(const std::vector<Clip>& children, const std::vector<std::string>& names,
                               const MotionDataOptions& options = {});

/// Normalized (D by N) → the selected dofs in pose-vector units (D by N).
MatX denormalize(const MotionData& data, const MatX& normalized);

/// A full clip from normalized values of the selected dofs (D by N): the unselected dofs take the
/// children's mean (template_pose), the pose vectors are inverted on the first child's skeleton in the
/// canonical frame, at data.frame_rate.
Clip reassemble_clip(const MotionData& data, const MatX& normalized, const std::string& name);

}  // namespace mocapdb::gp
