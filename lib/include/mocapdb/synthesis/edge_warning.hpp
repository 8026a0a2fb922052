#pragma once
// Where a synthesis of one set is flagged as likely to miss its parameters, calibrated on that set's own
// syntheses (workflow/edge_calibration.hpp computes it; `compress` stores it with the kernel;
// docs/synthesis.md "When rho warns"): a prediction variance above a level (rho = clamp(1 - variance
// ratio, 0, 1) below the matching one), a distance beyond the samples, or misses among the nearest
// calibration requests. Plain data; describe is pure.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"

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
    /// The vote rule: flag a request when at least `votes` of its `neighbours` nearest calibration requests
    /// (workflow::nearby_misses) missed; votes = 0: no vote rule (a calibration stored without it).
    std::size_t neighbours = 0;
    std::size_t votes = 0;
    MatX probe_requests;                     ///< the calibration's requests, one row each (the set's units)
    std::vector<std::uint8_t> probe_missed;  ///< per row: 1 when that request missed

    /// Whether a request is flagged (any rule); nearby: misses among its `neighbours` nearest probes.
    bool flags(double ratio, double beyond, std::size_t nearby) const {
        return ratio > variance_ratio || beyond > beyond_sd || (votes > 0 && nearby >= votes);
    }
};

/// rho at the threshold: clamp(1 - variance_ratio, 0, 1) (0 when the threshold lies beyond rho's range).
double rho_threshold(const EdgeWarning& warning);

/// One line for reports: "rho warns below 0.213 (calibrated on 120 syntheses: flags 27 of the 30 that
/// missed a parameter by over 0.25 SD; 2 % false alarms inside)".
std::string describe(const EdgeWarning& warning);

}  // namespace mocapdb::synthesis
