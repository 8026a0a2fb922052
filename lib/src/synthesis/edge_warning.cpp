#include "mocapdb/synthesis/edge_warning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mocapdb::synthesis {

double rho_threshold(const EdgeWarning& w) { return std::clamp(1.0 - w.variance_ratio, 0.0, 1.0); }

std::string describe(const EdgeWarning& w) {
    char buf[400], votes[96] = "";
    const auto flagged = static_cast<long long>(std::lround(w.detection * static_cast<double>(w.misses)));
    if (w.votes > 0)
        std::snprintf(votes, sizeof votes, ", or where %zu of the %zu nearest calibration requests missed", w.votes,
                      w.neighbours);
    std::snprintf(buf, sizeof buf,
                  "warns where the prediction variance exceeds %.3f of the sill (rho below %.3f), %.2f SD beyond "
                  "the samples%s (calibrated on %zu syntheses: flags %lld of the %zu that missed a parameter by over "
                  "%.2f SD; %.0f %% false alarms inside)",
                  w.variance_ratio, rho_threshold(w), w.beyond_sd, votes, w.probes, flagged, w.misses,
                  w.tolerance_share, 100.0 * w.false_alarms);
    return buf;
}

}  // namespace mocapdb::synthesis
