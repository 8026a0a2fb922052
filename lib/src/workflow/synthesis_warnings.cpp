#include "mocapdb/workflow/synthesis_warnings.hpp"

#include <limits>

#include "mocapdb/workflow/edge_calibration.hpp"

namespace mocapdb::workflow {

synthesis::EdgeWarning edge_warning(const synthesis::SynthesisModel& model) {
    if (const auto& w = model.kernel_fit().edge_warning) return *w;
    synthesis::EdgeWarning fixed;
    fixed.variance_ratio = 1.0 - kLowReliability;
    fixed.beyond_sd = std::numeric_limits<double>::infinity();
    return fixed;
}

SynthesisWarnings synthesis_warnings(const synthesis::SynthesisModel& model, const MotionSet& set, const VecX& c) {
    SynthesisWarnings w;
    w.rho = model.reliability(c);
    w.variance_ratio = model.variance_ratio(c);
    w.beyond_sd = beyond_samples_sd(set, c);
    w.threshold = edge_warning(model);
    w.calibrated = model.kernel_fit().edge_warning.has_value();
    w.nearby_misses = nearby_misses(w.threshold, set, c);
    w.low_reliability = w.threshold.flags(w.variance_ratio, w.beyond_sd, w.nearby_misses);
    w.kernel_fit = synthesis::fit_status_warning(model.kernel_fit());
    const kriging::KrigingStatus& st = model.report().status;
    w.regularized = st.factorization == kriging::FactorizationStatus::Regularized;
    w.jittered = !w.regularized && st.factorization == kriging::FactorizationStatus::Jittered &&
                 st.jitter > 1e-8 * model.report().model.total_sill();
    return w;
}

SynthesisWarnings synthesis_warnings(const synthesis::SynthesisModel& model, const SynthOutcome& outcome,
                                     const MotionSet& set) {
    SynthesisWarnings w = synthesis_warnings(model, set, outcome.requested);
    const auto& edge = model.kernel_fit().edge_warning;
    const double share = edge ? edge->tolerance_share : EdgeCalibrationOptions{}.tolerance_share;
    const std::vector<std::optional<double>> tolerance = parameter_tolerance(set, share);
    for (const std::size_t p : missed_parameters(outcome, set, tolerance))
        w.misses.push_back(
            {p, outcome.requested(static_cast<Eigen::Index>(p)), outcome.parameter_measured[p], *tolerance[p]});
    return w;
}

}  // namespace mocapdb::workflow
