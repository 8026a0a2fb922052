#pragma once
// What a synthesis deserves a warning for (`mocapdb synth`, `query`, the demo): a
// reliability below kLowReliability (the motion is extrapolated), a coefficient kernel whose variogram
// fit is not clean (synthesis::fit_status_warning), and a kriging system that had to be regularized or
// jittered (beyond rounding). The judgement only; the wording of the warnings is the caller's.
// Threads: reads the model only.
#include <string>

#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::workflow {

/// Below this reliability a synthesis is extrapolated.
inline constexpr double kLowReliability = 0.5;

inline bool is_low_reliability(double rho) { return rho < kLowReliability; }

struct SynthesisWarnings {
    bool low_reliability = false;  ///< rho < kLowReliability
    std::string kernel_fit;        ///< the fit's warning ("" when clean)
    bool regularized = false;      ///< the covariance matrix's eigenvalues were clamped
    bool jittered = false;         ///< a jitter above 1e-8 of the total sill was added to its diagonal
};

SynthesisWarnings synthesis_warnings(const synthesis::SynthesisModel& model, double rho);

}  // namespace mocapdb::workflow
