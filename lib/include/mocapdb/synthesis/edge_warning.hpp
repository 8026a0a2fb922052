#pragma once
// The prediction variance above which a synthesis of one set is flagged as likely to miss its
// parameters (rho = clamp(1 - variance ratio, 0, 1) below the matching level), calibrated on that set (workflow/edge_calibration.hpp computes it; `compress` stores it with the
// kernel, docs/synthesis.md "When rho warns"). Plain data; describe is pure.
#include <cstddef>
#include <string>

namespace mocapdb::synthesis {

struct EdgeWarning {
    /// Flag a request whose V / total sill (SynthesisModel::variance_ratio) exceeds this; >= 0. The
    /// fixed rule rho < 0.5 is a ratio above 0.5.
    double variance_ratio = 0.5;
    /// Flag a request further than this many SDs beyond the samples' range on a numeric axis
    /// (workflow::beyond_samples_sd); >= 0.
    double beyond_sd = 0.0;
    double tolerance_share = 0.0;  ///< a parameter misses when |measured - requested| > this x its SD
    std::size_t probes = 0;        ///< requests synthesized and measured back to calibrate
    std::size_t misses = 0;        ///< of those, the ones that missed
    double detection = 0.0;        ///< share of the misses the threshold flags (1 when none missed)
    double false_alarms = 0.0;     ///< share of the probes inside the samples' box that hit and are flagged
    /// Whether a request is flagged (either rule).
    bool flags(double ratio, double beyond) const { return ratio > variance_ratio || beyond > beyond_sd; }
};

/// rho at the threshold: clamp(1 - variance_ratio, 0, 1) (0 when the threshold lies beyond rho's range).
double rho_threshold(const EdgeWarning& warning);

/// One line for reports: "rho warns below 0.213 (calibrated on 120 syntheses: flags 27 of the 30 that
/// missed a parameter by over 0.25 SD; 2 % false alarms inside)".
std::string describe(const EdgeWarning& warning);

}  // namespace mocapdb::synthesis
