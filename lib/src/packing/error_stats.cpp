#include "mocapdb/packing/error_stats.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"

namespace mocapdb::packing {
namespace {
constexpr std::size_t kBins = 8192;
}

ErrorAccumulator::ErrorAccumulator(double range_cm) : range_(range_cm), histogram_(kBins, 0) {
    if (!(range_cm > 0) || !std::isfinite(range_cm)) throw InvalidArgument("ErrorAccumulator: range must be > 0");
}

void ErrorAccumulator::add(double d) {
    max_ = std::max(max_, d);
    sum_sq_ += static_cast<long double>(d) * d;
    ++n_;
    const auto bin = static_cast<std::size_t>(std::min(d / range_ * kBins, double(kBins - 1)));
    ++histogram_[bin];
}

void ErrorAccumulator::merge(const ErrorAccumulator& o) {
    if (o.range_ != range_) throw InvalidArgument("ErrorAccumulator::merge: different ranges");
    max_ = std::max(max_, o.max_);
    sum_sq_ += o.sum_sq_;
    n_ += o.n_;
    for (std::size_t i = 0; i < kBins; ++i) histogram_[i] += o.histogram_[i];
}

ErrorStats ErrorAccumulator::stats() const {
    ErrorStats s;
    s.max_cm = max_;
    s.positions = n_;
    if (n_ == 0) return s;
    s.rmse_cm = static_cast<double>(std::sqrt(sum_sq_ / static_cast<long double>(n_)));
    const auto target = static_cast<std::uint64_t>(std::ceil(0.99 * static_cast<double>(n_)));
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < kBins; ++i) {
        seen += histogram_[i];
        if (seen >= target) {
            s.p99_cm = std::min(max_, (static_cast<double>(i) + 1.0) * range_ / kBins);
            break;
        }
    }
    return s;
}

void add_position_errors(const Eigen::Ref<const MatX>& source, const Eigen::Ref<const MatX>& decoded,
                         ErrorAccumulator& acc) {
    if (source.rows() != decoded.rows() || source.cols() != decoded.cols() || source.rows() % 3 != 0)
        throw InvalidArgument("add_position_errors: shapes differ or rows are not 3 per joint");
    for (Eigen::Index f = 0; f < source.cols(); ++f)
        for (Eigen::Index j = 0; j < source.rows(); j += 3)
            acc.add((source.block<3, 1>(j, f) - decoded.block<3, 1>(j, f)).norm());
}

}  // namespace mocapdb::packing
