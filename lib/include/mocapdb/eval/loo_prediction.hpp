#pragma once
// Leave-one-out whole-motion prediction (the geostatistical paper §5.1, Figures 6-7): for every sample
// i, each method is built on the other N - 1 samples (variograms, trends, Tucker basis, timing kernel:
// everything it fits) and the motion synthesized at c_i is compared with sample i.
//
// Error: joint-position distance (cm, forward kinematics, every joint including end sites, canonical
// frame) between the synthesized aligned poses and sample i's aligned poses, frame by frame in ALIGNED
// time (both at the T aligned frames; the synthesized timing is compared separately through the
// duration). Two variants: "motion" error (the canonical frame: the root's trajectory counts) and "pose"
// error (root-relative: both poses with the root's floor position x, z and heading set to 0 in every
// frame, as the pose distance of align/pose_distance.hpp does), which isolates the body's posture from
// how far and where the root travelled. What is NOT redone per fold: the DTW alignment itself (reference sample, warps) was
// computed once with all samples.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/foot_skating.hpp"
#include "mocapdb/eval/synthesis_method.hpp"

namespace mocapdb::eval {

struct LooOptions {
    bool foot_skating = true;           ///< also measure foot skating of each synthesized clip (foot_skating.hpp)
    std::vector<Eigen::Index> samples;  ///< which samples to leave out (empty = all)
    /// Per sample (N lists, or empty = none): the samples left out together with it, its twins
    /// (dataset/sample_twins.hpp): fold i trains on loo_training(N, i, twins).
    std::vector<std::vector<Eigen::Index>> twins;
    bool measure_parameters = false;  ///< measure each synthesized clip with set.extractors (when it has any)
    bool reliability = false;         ///< record each method's reliability rho at the left-out parameters
};

struct LooMethodResult {
    std::string method;
    VecX sample_mean_cm;       ///< per left-out sample: mean joint error over joints and frames (motion)
    VecX sample_max_cm;        ///< per left-out sample: max joint error (motion)
    VecX frame_mean_cm;        ///< T: per aligned frame, mean over samples of the mean joint error (motion)
    VecX frame_max_cm;         ///< T: per aligned frame, max over samples and joints (motion)
    VecX sample_pose_mean_cm;  ///< per left-out sample: mean joint error, root-relative pose
    VecX sample_pose_max_cm;   ///< per left-out sample: max joint error, root-relative pose
    VecX frame_pose_mean_cm;   ///< T: per aligned frame, mean over samples, root-relative pose
    VecX duration_error_s;     ///< per sample: |synthesized duration - sample duration| (s)
    VecX skating_cm_per_s;     ///< per sample: foot skating of the synthesized clip (empty without)
    VecX reliability;          ///< per sample: the method's rho at c_i (empty without, or a fold had none)
    /// Per left-out sample, its P parameters measured back on the synthesized clip (empty without
    /// measure_parameters or extractors); a parameter the clip does not define (a jump without a flight,
    /// a gait measure without a cycle) is an empty optional.
    std::vector<std::vector<std::optional<double>>> measured;
    double mean_cm = 0.0;       ///< mean of sample_mean_cm
    double max_cm = 0.0;        ///< max of sample_max_cm
    double pose_mean_cm = 0.0;  ///< mean of sample_pose_mean_cm
    double pose_max_cm = 0.0;   ///< max of sample_pose_max_cm
    /// Where pose_max_cm occurs: left-out sample index, aligned frame, joint name.
    Eigen::Index pose_worst_sample = -1;
    Eigen::Index pose_worst_frame = -1;
    std::string pose_worst_joint;
    double build_seconds = 0.0;  ///< mean build time per fold
    double synth_seconds = 0.0;  ///< mean time to synthesize one aligned motion
};

struct LooResult {
    std::vector<Eigen::Index> samples;     ///< left-out samples, in order
    std::vector<LooMethodResult> methods;  ///< in the order given
    VecX original_skating_cm_per_s;        ///< per left-out sample, the original's skating (empty without)
};

/// The training samples of the fold that leaves out sample i of n: every sample but i and twins[i]
/// (twins empty or n lists). InvalidArgument for an index out of range.
std::vector<Eigen::Index> loo_training(Eigen::Index n, Eigen::Index i,
                                       const std::vector<std::vector<Eigen::Index>>& twins);

/// Twin lists of the subset `keep` of a set (indices into the subset; twins outside it dropped).
std::vector<std::vector<Eigen::Index>> subset_twins(const std::vector<std::vector<Eigen::Index>>& twins,
                                                    const std::vector<Eigen::Index>& keep);

/// Throws InvalidArgument for fewer than 4 samples, an index out of range, twin lists not one per sample,
/// or a fold left with fewer than 3 training samples. `progress` counts folds.
LooResult leave_one_out(const EvalSet& set, const std::vector<MethodSpec>& methods, const LooOptions& options = {},
                        const ProgressCallback& progress = {});

/// Per aligned frame, mean and max over joints of |p - p_hat| (cm) between two D by T pose sequences of
/// `skeleton`: returns T by 3 (column 0 mean, column 1 max, column 2 the skeleton index of the joint
/// with the max error). root_relative: both with the root's floor
/// position and heading (pose-vector rows 0, 2, 4) set to 0 first (the "pose" error above).
MatX frame_joint_errors(const Skeleton& skeleton, const Eigen::Ref<const MatX>& reference,
                        const Eigen::Ref<const MatX>& approx, bool root_relative = false);

}  // namespace mocapdb::eval
