#pragma once
// Joint-position error statistics of a lossy copy against the source: max, p99 and RMSE in cm over
// every joint and end site (world frame) of every frame.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mocapdb/core/types.hpp"

namespace mocapdb::packing {

struct ErrorStats {
    double max_cm = 0.0;
    double p99_cm = 0.0;  ///< 99th percentile (histogram estimate, resolution range_cm / 8192)
    double rmse_cm = 0.0;
    std::size_t positions = 0;  ///< joint positions measured (frames x joints incl. end sites)
};

/// Accumulates distances; the percentile is read from a histogram over [0, range_cm] (distances
/// beyond it count in the last bin, the max stays exact). Merge accumulators of the same range.
class ErrorAccumulator {
public:
    explicit ErrorAccumulator(double range_cm = 1.0);
    void add(double distance_cm);
    void merge(const ErrorAccumulator& other);
    ErrorStats stats() const;

private:
    double range_;
    double max_ = 0.0;
    long double sum_sq_ = 0.0;
    std::size_t n_ = 0;
    std::vector<std::uint64_t> histogram_;
};

/// Adds the distances between the joint positions (3·J by F, from joint_positions) of `source` and
/// `decoded` (same shape; InvalidArgument otherwise).
void add_position_errors(const Eigen::Ref<const MatX>& source, const Eigen::Ref<const MatX>& decoded,
                         ErrorAccumulator& accumulator);

}  // namespace mocapdb::packing
