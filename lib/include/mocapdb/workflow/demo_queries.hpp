#pragma once
// The choices and measurements of `mocapdb demo`: where to synthesize (between samples,
// at the cells of the procedural reach grid, and the least trusted point outside the samples), what
// the parameters of a synthesized motion are measured with (the set's extractors, extractors named
// like its CSV parameters, or where the procedural reach lands) and that measurement, and the padded
// axes of the reliability map. Nothing is printed. Errors: none beyond those of the called steps.
// Threads: no shared state; the model is only read.
#include <string>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/skeleton.hpp"
#include "mocapdb/procedural/parametric_set.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"
#include "mocapdb/workflow/reliability_map.hpp"

namespace mocapdb::workflow {

/// New parameter vectors inside the sampled region: the midpoint of a sample and its nearest neighbour
/// (in normalized parameters) for `count` samples spread over the set; never a sample, no pair twice.
std::vector<VecX> between_samples(const MatX& samples, std::size_t count);

/// Centres of up to five cells of the procedural reach grid (angle x height): targets between four
/// samples. Empty when an axis has fewer than 2 values.
std::vector<VecX> reach_cell_centres(const procedural::ReachGrid& grid);

/// Whether `c` lies in the samples' bounding box (bounds included).
bool inside_box(const MatX& samples, const VecX& c);

/// Of the 2P points one sampled range beyond the samples along each axis (both sides, from the
/// samples' mean), the one `model` trusts least (lowest rho; the first of equals).
VecX least_trusted_outside(const synthesis::SynthesisModel& model);

enum class DemoMeasure { None, Extractors, ReachTarget };

struct DemoMeasurement {
    DemoMeasure kind = DemoMeasure::None;
    std::vector<ParameterExtractor> extractors;  ///< Extractors
    std::string extractor_names;                 ///< the set's parameter source, or "extract:NAME,..."
};

/// How the demo measures a synthesized motion of `set`: the set's own extractors; else extractors
/// named exactly like every one of its parameters (a CSV of turn/speed); else, for parameters named
/// angle/height/distance on a skeleton with the humanoid's right hand end site, where the reach lands;
/// else nothing.
DemoMeasurement choose_measurement(const MotionSet& set, const Skeleton& skeleton);

/// The reach's target as reached by `clip` (procedural::reach_hold_point), per name: bearing around the
/// vertical axis through the origin ("angle", deg, + = left), height above the floor ("height", cm) and
/// horizontal distance from that axis ("distance", cm). Empty without a hold or for another name.
VecX measure_reach_target(const Clip& clip, const std::vector<std::string>& names);

/// The measured parameters of a synthesized clip (empty when nothing measures them, or the clip is
/// shorter than 2 frames for the extractors).
VecX measure_synthesis(const DemoMeasurement& measurement, const Clip& clip, const std::vector<std::string>& names);

/// A map axis over parameter `axis` covering the samples and `points`, padded by 15 % of that span on
/// both sides, with `count` values.
SliceAxis padded_axis(const MatX& samples, const std::vector<VecX>& points, Eigen::Index axis, Eigen::Index count);

}  // namespace mocapdb::workflow
