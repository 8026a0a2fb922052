#pragma once
// Building a motion set from stored clips: choose samples (whole clips, gait cycles or windows) and
// measure their control parameters.
#include <functional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/dataset/segmentation.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

/// Auto: flights when a jump length is measured (the jump of each clip, cut the same way around its
/// take-off and landing: flight_window); else gait cycles when the parameters are measured (extractors
/// given) and at least kAutoGaitShare of the selected clips have a gait cycle (locomotion: samples then
/// start and end at the same phase, so aligned frames never blend left-foot-forward with
/// right-foot-forward poses; clips without a cycle are skipped); whole clips otherwise.
enum class Segmentation { Auto, WholeClips, GaitCycles, Windows, Flights };
inline constexpr double kAutoGaitShare = 0.8;

struct SetBuildOptions {
    std::string name;
    Segmentation segmentation = Segmentation::WholeClips;
    GaitCycleOptions gait;          ///< GaitCycles, Auto
    std::size_t window_length = 0;  ///< Windows: frames per sample
    std::size_t window_hop = 0;     ///< Windows: frames between window starts
    FlightWindowOptions flight;     ///< Flights, Auto
    /// Parameters measured per sample; may be empty when the caller supplies them (CSV).
    std::vector<ParameterExtractor> extractors;
    /// Detect and repair solver dropouts in each clip before it is segmented and measured
    /// (dropout_repair.hpp); the runs are recorded in MotionSet::repairs.
    bool repair_dropouts = true;
    DropoutOptions dropout;
    /// Called after each clip (done = clips loaded and measured, total = clips, item = its id). May
    /// be empty.
    ProgressCallback progress;
};

/// Parses "auto", "none", "gait[:N]" (at most N cycles per clip, evenly spread; 1 = the middle one),
/// "window:LENGTH[:HOP]" (frames; HOP defaults to LENGTH) or "flight[:BEFORE[:AFTER]]" (seconds kept
/// before take-off and after landing, default 0.5 each) into `options`. InvalidArgument otherwise.
void parse_segmentation(const std::string& spec, SetBuildOptions& options);

/// Loads one clip at a time (the set builder never holds more than one).
using ClipLoader = std::function<Clip(const std::string& clip_id)>;

/// The set over `clip_ids` (in that order; samples of one clip in time order) with the extractors'
/// parameters (N by P; P = 0 without extractors). With repair_dropouts, each clip's dropouts are
/// repaired first (segmentation and parameters see the repaired frames) and recorded in
/// `repairs` (only for clips that yield a sample); dropouts_checked is set. Clips that yield no sample (too short for a gait
/// cycle or a window) are skipped and listed in `out_skipped` when given. InvalidArgument when no
/// sample at all results, or an extractor's quantity is undefined for a sample (the message names
/// clip and frames). `out_used` (when given) receives the segmentation used (Auto resolved).
MotionSet build_motion_set(const std::vector<std::string>& clip_ids, const ClipLoader& load,
                           const SetBuildOptions& options, std::vector<std::string>* out_skipped = nullptr,
                           Segmentation* out_used = nullptr);

/// Sample `index` of `set` cut from `clip` (the stored clip it names), with the set's recorded
/// repairs of that clip applied: the frames every later step (alignment, evaluation) must use.
/// InvalidArgument when the index is out of range or the sample's frames lie beyond the clip.
Clip sample_frames(const MotionSet& set, std::size_t index, const Clip& clip);

/// "CLIP" for a sample covering its whole clip of `clip_frames` frames, else "CLIP:BEGIN-END".
std::string sample_label(const SampleRef& sample, std::size_t clip_frames);

}  // namespace mocapdb
