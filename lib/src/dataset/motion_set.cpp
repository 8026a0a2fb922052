#include "mocapdb/dataset/motion_set.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"

namespace mocapdb {

void validate(const MotionSet& set) {
    const std::string who = "motion set '" + set.name + "'";
    if (set.name.empty()) throw InvalidArgument("motion set: empty name");
    if (set.samples.empty()) throw InvalidArgument(who + ": no samples");
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        const SampleRef& s = set.samples[i];
        if (s.clip.empty()) throw InvalidArgument(who + ": sample " + std::to_string(i) + " names no clip");
        if (s.end < s.begin + 2)
            throw InvalidArgument(who + ": sample " + std::to_string(i) + " (" + s.clip + " [" +
                                  std::to_string(s.begin) + ", " + std::to_string(s.end) +
                                  ")) has fewer than 2 frames");
    }
    const auto n = static_cast<Eigen::Index>(set.samples.size());
    const auto p = static_cast<Eigen::Index>(set.parameter_names.size());
    if (set.parameter_units.size() != set.parameter_names.size())
        throw InvalidArgument(who + ": " + std::to_string(set.parameter_names.size()) + " parameter names but " +
                              std::to_string(set.parameter_units.size()) + " units");
    if (set.parameters.rows() != n || set.parameters.cols() != p)
        throw InvalidArgument(who + ": parameter matrix is " + std::to_string(set.parameters.rows()) + " by " +
                              std::to_string(set.parameters.cols()) + ", expected " + std::to_string(n) + " by " +
                              std::to_string(p) + " (samples by parameters)");
    if (!set.parameters.allFinite()) throw InvalidArgument(who + ": non-finite control parameter");
    if (set.parameter_periods.size() != 0 && (set.parameter_periods.size() != p || !set.parameter_periods.allFinite() ||
                                              (set.parameter_periods.array() < 0.0).any()))
        throw InvalidArgument(who + ": parameter periods must be empty or " + std::to_string(p) +
                              " finite values >= 0 (0 = not periodic)");
}

void set_parameter_period(MotionSet& set, const std::string& name, double period) {
    const std::string who = "motion set '" + set.name + "'";
    if (!(period >= 0.0) || !std::isfinite(period))
        throw InvalidArgument(who + ": the period of parameter '" + name +
                              "' must be finite and > 0 (0 = not periodic)");
    const auto it = std::find(set.parameter_names.begin(), set.parameter_names.end(), name);
    if (it == set.parameter_names.end()) {
        std::string names;
        for (const std::string& n : set.parameter_names) names += (names.empty() ? "" : ", ") + n;
        throw InvalidArgument(who + ": no parameter '" + name +
                              "' to make periodic (its parameters: " + (names.empty() ? "none" : names) + ")");
    }
    const auto p = static_cast<Eigen::Index>(set.parameter_names.size());
    if (set.parameter_periods.size() != p) set.parameter_periods = VecX::Zero(p);
    set.parameter_periods(static_cast<Eigen::Index>(it - set.parameter_names.begin())) = period;
    if (!(set.parameter_periods.array() > 0.0).any()) set.parameter_periods.resize(0);
}

void check_distinguishable(const MotionSet& set) {
    const std::string who = "motion set '" + set.name + "'";
    if (set.samples.size() < 2)
        throw Refused<InvalidArgument>(Remedy::Segmentation,
                                       who + ": " + std::to_string(set.samples.size()) +
                                           " sample; a set needs at least 2 (select more clips or segment finer)");
    if (set.parameters.cols() == 0) return;
    const auto first = set.parameters.row(0);
    for (Eigen::Index i = 1; i < set.parameters.rows(); ++i)
        if (set.parameters.row(i) != first) return;
    throw InvalidArgument(who +
                          ": every sample has the same parameters, so synthesis could not tell them apart "
                          "(give parameters that differ between the samples)");
}

}  // namespace mocapdb
