#pragma once
// One synthesis as a library step (`mocapdb synth` and the demo): the motion of a set at
// control parameters c from a loaded model (load_model.hpp), its timing and reliability, and every
// extractor that applies measured back on the result (applicable_extractors), so callers can tell how
// close the motion came to what was asked. Nothing is printed or written.
// Errors: those of the model (InvalidArgument for c of the wrong size) and of the extractors.
// Threads: the model is immutable and may be shared; each call is independent.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::workflow {

/// The extractors a set's parameters were measured with (the "extract:turn,speed" part of its
/// parameter_source, parts separated by "; "), or none (parameters from a CSV, categories, or none).
/// InvalidArgument for a source naming an unknown extractor.
std::vector<ParameterExtractor> source_extractors(const std::string& parameter_source);

/// The extractors measured back on a synthesized motion of `set`: the locomotion ones, defined for
/// any motion (displacement, turn, speed, and bearing where the root travels), then the set's own
/// others (jump, reach).
std::vector<ParameterExtractor> applicable_extractors(const MotionSet& set);

/// One measured quantity: an extractor's column (ParameterExtractor::names / units).
struct Measurement {
    std::string name;
    std::string unit;
    double value = 0.0;
};

struct SynthOutcome {
    VecX requested;  ///< c
    Clip clip;       ///< the synthesized motion on the set's skeleton
    synthesis::Timing timing;
    double reliability = 0.0;  ///< rho at c (1 at the samples, towards 0 far from them)
    /// Every applicable extractor's columns measured on the clip (an extractor undefined on it, e.g. a
    /// bearing when the root does not travel, is left out).
    std::vector<Measurement> measurements;
    /// Per set parameter, the measurement of the extractor column it was measured by (none for a
    /// parameter from a CSV or a category): P entries.
    std::vector<std::optional<double>> parameter_measured;
    VecX measured;         ///< parameter_measured when every parameter has one, else empty
    double seconds = 0.0;  ///< wall time of timing + motion + reliability
};

/// `set` is the model's set (for its parameter source); level 0 = full ranks.
SynthOutcome synthesize(const synthesis::SynthesisModel& model, const MotionSet& set, const VecX& c,
                        Eigen::Index level = 0);

}  // namespace mocapdb::workflow
