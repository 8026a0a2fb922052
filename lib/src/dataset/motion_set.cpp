#include "mocapdb/dataset/motion_set.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <regex>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/csv_table.hpp"
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
    if (set.parameter_levels.empty()) return;
    if (set.parameter_levels.size() != static_cast<std::size_t>(p))
        throw InvalidArgument(who + ": parameter levels must be empty or " + std::to_string(p) + " lists");
    for (std::size_t k = 0; k < set.parameter_levels.size(); ++k) {
        const std::vector<std::string>& levels = set.parameter_levels[k];
        if (levels.empty()) continue;
        const std::string param = who + ": categorical parameter '" + set.parameter_names[k] + "'";
        if (levels.size() < 2 || std::set<std::string>(levels.begin(), levels.end()).size() != levels.size())
            throw InvalidArgument(param + " needs at least 2 distinct level names");
        if (set.parameter_periods.size() != 0 && set.parameter_periods(static_cast<Eigen::Index>(k)) > 0.0)
            throw InvalidArgument(param + " cannot be periodic");
        const auto col = set.parameters.col(static_cast<Eigen::Index>(k));
        for (Eigen::Index i = 0; i < col.size(); ++i)
            if (col(i) != std::floor(col(i)) || col(i) < 0.0 || col(i) >= static_cast<double>(levels.size()))
                throw InvalidArgument(param + ", sample " + std::to_string(i) + ": " + std::to_string(col(i)) +
                                      " is not a level index in [0, " + std::to_string(levels.size()) + ")");
    }
}

bool is_categorical(const MotionSet& set, std::size_t p) {
    return p < set.parameter_levels.size() && !set.parameter_levels[p].empty();
}

std::vector<int> parameter_level_counts(const MotionSet& set) {
    std::vector<int> counts;
    for (const auto& levels : set.parameter_levels) counts.push_back(static_cast<int>(levels.size()));
    if (std::all_of(counts.begin(), counts.end(), [](int l) { return l == 0; })) counts.clear();
    return counts;
}

Eigen::Index level_index(const MotionSet& set, std::size_t p, const std::string& level) {
    if (!is_categorical(set, p))
        throw InvalidArgument("motion set '" + set.name + "': parameter " + std::to_string(p) + " is not categorical");
    const std::vector<std::string>& levels = set.parameter_levels[p];
    const auto it = std::find(levels.begin(), levels.end(), level);
    if (it != levels.end()) return static_cast<Eigen::Index>(it - levels.begin());
    std::string known;
    for (const std::string& l : levels) known += (known.empty() ? "" : ", ") + l;
    throw InvalidArgument("motion set '" + set.name + "': parameter '" + set.parameter_names[p] + "' has no level '" +
                          level + "' (its levels: " + known + ")");
}

void add_categorical_parameter(MotionSet& set, const std::string& name, const std::vector<std::string>& levels) {
    const std::string who = "motion set '" + set.name + "'";
    const auto n = static_cast<Eigen::Index>(set.samples.size());
    if (levels.size() != set.samples.size())
        throw InvalidArgument(who + ": " + std::to_string(levels.size()) + " levels of parameter '" + name + "' for " +
                              std::to_string(set.samples.size()) + " samples");
    if (std::find(set.parameter_names.begin(), set.parameter_names.end(), name) != set.parameter_names.end())
        throw InvalidArgument(who + ": a parameter named '" + name + "' exists already");
    std::map<std::string, std::size_t> count;
    for (const std::string& l : levels) ++count[l];
    if (count.size() < 2)
        throw InvalidArgument(who + ": categorical parameter '" + name + "' has " + std::to_string(count.size()) +
                              " level ('" + (levels.empty() ? "" : levels[0]) +
                              "' for every sample); it needs at least 2 to tell samples apart");
    for (const auto& [level, k] : count)
        if (k < kMinSamplesPerLevel)
            throw InvalidArgument(who + ": level '" + level + "' of categorical parameter '" + name + "' has " +
                                  std::to_string(k) + " sample; each level needs at least " +
                                  std::to_string(kMinSamplesPerLevel) + " (select more clips of it or segment finer)");
    const auto p = set.parameters.cols();
    if (set.parameters.rows() != n) set.parameters.resize(n, p);  // no parameter yet (a set of whole clips)
    std::vector<std::string> names;
    for (auto& entry : count) {  // sorted (std::map); the count becomes the level's index
        entry.second = names.size();
        names.push_back(entry.first);
    }
    set.parameters.conservativeResize(n, p + 1);
    for (Eigen::Index i = 0; i < n; ++i)
        set.parameters(i, p) = static_cast<double>(count.at(levels[static_cast<std::size_t>(i)]));
    set.parameter_levels.resize(static_cast<std::size_t>(p));
    set.parameter_levels.push_back(names);
    set.parameter_names.push_back(name);
    set.parameter_units.emplace_back();
    if (set.parameter_periods.size() != 0) {
        set.parameter_periods.conservativeResize(p + 1);
        set.parameter_periods(p) = 0.0;
    }
}

std::vector<std::string> levels_from_clip_names(const MotionSet& set, const std::string& pattern) {
    std::regex re;
    try {
        re = std::regex(pattern, std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
        throw InvalidArgument("category pattern '" + pattern + "' is not a valid regular expression (" + e.what() +
                              ")");
    }
    if (re.mark_count() < 1)
        throw InvalidArgument("category pattern '" + pattern +
                              "' has no group: its first (parenthesized) group gives the level");
    std::vector<std::string> out;
    for (const SampleRef& s : set.samples) {
        std::smatch m;
        if (!std::regex_search(s.clip, m, re) || !m[1].matched || m[1].length() == 0)
            throw InvalidArgument("category pattern '" + pattern + "' does not match clip '" + s.clip +
                                  "' (or its first group is empty): every clip of the set needs a level");
        out.push_back(m[1].str());
    }
    return out;
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

// ---- requests (parameter_request and its messages) ----

namespace {

// One item's value for parameter p.
double request_value(const MotionSet& set, std::size_t p, const std::string& word) {
    if (is_categorical(set, p)) return static_cast<double>(level_index(set, p, word));
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (word.empty() || end != word.c_str() + word.size() || !std::isfinite(v))
        throw InvalidArgument("parameter '" + set.parameter_names[p] + "': '" + word +
                              "' is not a finite number (expected: " + describe_parameters(set) + ")");
    return v;
}

}  // namespace

std::string describe_parameters(const MotionSet& set) {
    std::string s;
    for (std::size_t k = 0; k < set.parameter_names.size(); ++k) {
        if (k) s += ", ";
        s += set.parameter_names[k];
        if (is_categorical(set, k)) {
            std::string levels;
            for (const std::string& l : set.parameter_levels[k]) levels += (levels.empty() ? "" : "|") + l;
            s += " {" + levels + "}";
        } else if (k < set.parameter_units.size() && !set.parameter_units[k].empty()) {
            s += " [" + set.parameter_units[k] + "]";
        }
    }
    return s;
}

std::string parameter_value_text(const MotionSet& set, std::size_t p, double value) {
    if (is_categorical(set, p) && value >= 0.0 && value < static_cast<double>(set.parameter_levels[p].size()))
        return set.parameter_levels[p][static_cast<std::size_t>(value)];
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", value);
    return buf;
}

VecX parameter_request(const MotionSet& set, const std::vector<std::string>& items) {
    const std::size_t p = set.parameter_names.size();
    const bool named =
        std::any_of(items.begin(), items.end(), [](const std::string& s) { return s.find('=') != std::string::npos; });
    VecX c(static_cast<Eigen::Index>(p));
    if (!named) {
        if (items.size() != p)
            throw InvalidArgument("expected " + std::to_string(p) + " values (" + describe_parameters(set) + "), got " +
                                  std::to_string(items.size()));
        for (std::size_t k = 0; k < p; ++k)
            c(static_cast<Eigen::Index>(k)) = request_value(set, k, trim_blanks(items[k]));
        return c;
    }
    std::vector<bool> given(p, false);
    for (const std::string& item : items) {
        const auto eq = item.find('=');
        if (eq == std::string::npos)
            throw InvalidArgument("'" + trim_blanks(item) + "' has no name: give every value as NAME=VALUE or none (" +
                                  describe_parameters(set) + ")");
        const std::string name = trim_blanks(item.substr(0, eq));
        const auto it = std::find(set.parameter_names.begin(), set.parameter_names.end(), name);
        if (it == set.parameter_names.end())
            throw InvalidArgument("the set has no parameter '" + name +
                                  "' (its parameters: " + describe_parameters(set) + ")");
        const auto k = static_cast<std::size_t>(it - set.parameter_names.begin());
        if (given[k]) throw InvalidArgument("parameter '" + name + "' is given twice");
        given[k] = true;
        c(static_cast<Eigen::Index>(k)) = request_value(set, k, trim_blanks(item.substr(eq + 1)));
    }
    for (std::size_t k = 0; k < p; ++k)
        if (!given[k])
            throw InvalidArgument("no value for parameter '" + set.parameter_names[k] +
                                  "' (expected: " + describe_parameters(set) + ")");
    return c;
}

}  // namespace mocapdb
