#pragma once
// One synthesis as a library step (`mocapdb synth` and the demo): the motion of a set at
// control parameters c from a loaded model (load_model.hpp), its timing and reliability, and, when the
// set's parameters were measured by extractors, the same measurement on the result, so callers can
// tell how close the motion came to what was asked. Nothing is printed or written.
// Errors: those of the model (InvalidArgument for c of the wrong size) and of the extractors.
// Threads: the model is immutable and may be shared; each call is independent.
#include <string>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::workflow {

/// The extractors a set's parameters were measured with (parameter_source "extract:turn,speed"), or
/// none (parameters from a CSV, or none). InvalidArgument for a source naming an unknown extractor.
std::vector<ParameterExtractor> source_extractors(const std::string& parameter_source);

struct SynthOutcome {
    VecX requested;  ///< c
    Clip clip;       ///< the synthesized motion on the set's skeleton
    synthesis::Timing timing;
    double reliability = 0.0;  ///< rho at c (1 at the samples, towards 0 far from them)
    VecX measured;             ///< by the set's extractors; empty when the set's parameters were not extracted
    double seconds = 0.0;      ///< wall time of timing + motion + reliability
};

/// `set` is the model's set (for its parameter source); level 0 = full ranks.
SynthOutcome synthesize(const synthesis::SynthesisModel& model, const MotionSet& set, const VecX& c,
                        Eigen::Index level = 0);

}  // namespace mocapdb::workflow
