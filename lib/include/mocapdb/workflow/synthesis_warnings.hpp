#pragma once
// What a synthesis deserves a warning for (`mocapdb synth`, `query`, the demo): a prediction variance
// or a distance beyond the samples above the set's thresholds (calibrated on the set by `compress`,
// edge_calibration.hpp; else rho below kLowReliability),
// parameters measured back further from the request than their tolerance, a coefficient kernel whose
// variogram fit is not clean (synthesis::fit_status_warning), and a kriging system that had to be
// regularized or jittered (beyond rounding). The judgement only; the wording is the caller's.
// Threads: reads the model only.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"

namespace mocapdb::workflow {

/// Below this reliability a synthesis is extrapolated (the threshold of a set without a calibration).
inline constexpr double kLowReliability = 0.5;

/// Where `model`'s syntheses are flagged: its kernel's calibration (KernelFit::edge_warning), else the
/// fixed rule (a variance ratio above 1 - kLowReliability, i.e. rho < kLowReliability; no distance rule).
synthesis::EdgeWarning edge_warning(const synthesis::SynthesisModel& model);

/// A parameter measured back further from the request than its tolerance (or not measurable).
struct ParameterMiss {
    std::size_t parameter = 0;
    double requested = 0.0;
    std::optional<double> measured;  ///< none: the extractor is undefined on the result
    double tolerance = 0.0;          ///< the calibration's tolerance share x the parameter's SD
};

struct SynthesisWarnings {
    double rho = 1.0;                  ///< at the request
    double variance_ratio = 0.0;       ///< at the request
    double beyond_sd = 0.0;            ///< at the request (edge_calibration.hpp beyond_samples_sd)
    synthesis::EdgeWarning threshold;  ///< edge_warning(model)
    bool calibrated = false;           ///< the thresholds are the set's calibration
    /// Misses among the calibration's requests nearest to this one (edge_calibration.hpp nearby_misses).
    std::size_t nearby_misses = 0;
    bool low_reliability = false;       ///< threshold.flags(variance_ratio, beyond_sd, nearby_misses)
    std::vector<ParameterMiss> misses;  ///< (with an outcome) the parameters that missed
    std::string kernel_fit;             ///< the fit's warning ("" when clean)
    bool regularized = false;           ///< the covariance matrix's eigenvalues were clamped
    bool jittered = false;              ///< a jitter above 1e-8 of the total sill was added to its diagonal
    /// The request is flagged as likely (or measured) to miss its parameters.
    bool flagged() const { return low_reliability || !misses.empty(); }
};

/// At control parameters c (P values, the set's units) of `set`, the model's set.
SynthesisWarnings synthesis_warnings(const synthesis::SynthesisModel& model, const MotionSet& set, const VecX& c);
/// The same for a synthesized motion of `set`, with the parameters it missed.
SynthesisWarnings synthesis_warnings(const synthesis::SynthesisModel& model, const SynthOutcome& outcome,
                                     const MotionSet& set);

}  // namespace mocapdb::workflow
