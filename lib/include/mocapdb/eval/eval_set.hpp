#pragma once
// The motion sets of the evaluation, built in memory from CMU ASF/AMC files: samples (whole
// clips or gait cycles), control parameters measured by the extractors of param_extractors.hpp, and
// the DTW-aligned D x T x N pose tensor.
//
// One set has one skeleton. Clips of several subjects (e.g. forward jumps of subjects 13, 16 and 105)
// share the set through the FIRST clip's skeleton: all CMU ASF skeletons have the same joints and
// channels (checked: InvalidArgument otherwise), and a pose vector holds joint rotations, so the other
// subjects' channels are replayed on the first subject's bones. Their parameters are measured on their
// own skeletons, before the swap.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/dataset/segmentation.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb::eval {

struct EvalSetSpec {
    std::string name;
    std::string description;              ///< one line for reports
    std::vector<std::string> clips;       ///< CMU trial ids ("16_15"), in sample order
    bool gait_cycles = false;             ///< false: whole clips; true: gait cycles (segmentation.hpp)
    std::size_t max_cycles_per_clip = 0;  ///< gait: keep at most this many cycles per clip, evenly spread (0 = all)
    bool flight_windows = false;          ///< true: the jump of each clip (segmentation.hpp: flight_window)
    std::vector<std::string> extractors;  ///< ParameterExtractor specs ("turn", "speed", "jump", ...)
    Eigen::Index frames = 60;             ///< aligned frames T
};

struct EvalSet {
    EvalSetSpec spec;
    MotionSet set;                             ///< samples and N by P parameters
    std::vector<std::string> labels;           ///< per sample, "CLIP" or "CLIP:BEGIN-END"
    std::vector<std::string> clip_ids;         ///< distinct clips used, in order
    std::vector<std::string> skipped;          ///< clips that gave no sample
    std::vector<Clip> samples;                 ///< per sample, its frames on the set's skeleton
    std::shared_ptr<const Skeleton> skeleton;  ///< the first clip's
    std::string skeleton_source;               ///< e.g. "13.asf"
    std::vector<ParameterExtractor> extractors;
    AlignedSet aligned;
    double frame_rate = 120.0;

    Eigen::Index size() const { return static_cast<Eigen::Index>(samples.size()); }
};

/// Reads the clips from `cmu_dir` (NN_MM.amc with NN.asf beside it), repairs their solver dropouts
/// (dropout_repair.hpp; recorded in set.repairs), builds samples and parameters and aligns them (dtw, reference = median-length sample). Throws IoError / ParseError for unreadable
/// files, InvalidArgument for incompatible skeletons, undefined parameters or fewer than 3 samples.
EvalSet build_eval_set(const EvalSetSpec& spec, const std::filesystem::path& cmu_dir);

/// The set restricted to the samples `keep` (indices, any order, no repeats): samples, parameters and
/// the aligned tensor's slices and warps (NOT re-aligned: the DTW reference and the mean / scale stay
/// those of the full set).
EvalSet subset(const EvalSet& set, const std::vector<Eigen::Index>& keep);

}  // namespace mocapdb::eval
