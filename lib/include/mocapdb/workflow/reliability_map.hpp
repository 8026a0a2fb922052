#pragma once
// The reliability of synthesis over a 2-D slice of a set's control space as a library step (issue
// #17; `mocapdb reliability` and the demo): rho at every cell of a grid through fixed values of the
// other parameters, and the share of the slice the model can be trusted on. Nothing is printed; the
// heat map (labels, sample marks, SVG) is the caller's.
// Errors: InvalidArgument from the model when `base` has the wrong size. Threads: as the model.
#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::workflow {

/// rho at or above this counts as trusted (fraction_trusted).
inline constexpr double kTrustedReliability = 0.85;

/// One axis of a 2-D slice of the control space: `count` values from lo to hi, in the set's units.
struct SliceAxis {
    Eigen::Index axis = 0;  ///< parameter index
    double lo = 0, hi = 0;
    Eigen::Index count = 0;
    double at(Eigen::Index i) const {
        return count > 1 ? lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(count - 1) : lo;
    }
};

struct ReliabilityMap {
    MatX queries;                                         ///< gx.count · gy.count by P, x fastest
    VecX rho;                                             ///< per query
    MatX values;                                          ///< rho as gy.count rows by gx.count columns
    double fraction_trusted = 0.0;                        ///< share of cells with rho >= kTrustedReliability
    double rho_min = 0.0, rho_mean = 0.0, rho_max = 0.0;  ///< over the cells
};

/// The samples' mean parameters: where a slice crosses the axes it does not show, by default.
VecX samples_mean(const synthesis::SynthesisModel& model);

/// rho over the slice gx × gy through `base` (the other axes' values; P entries).
ReliabilityMap reliability_map(const synthesis::SynthesisModel& model, const SliceAxis& gx, const SliceAxis& gy,
                               const VecX& base);

}  // namespace mocapdb::workflow
