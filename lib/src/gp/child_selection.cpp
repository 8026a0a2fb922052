#include "mocapdb/gp/child_selection.hpp"

#include <algorithm>
#include <random>

#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

std::string subject_of(const std::string& name) {
    const std::size_t us = name.find('_');
    if (us == 0 || us == std::string::npos) return {};
    return name.substr(0, us);
}

std::vector<std::string> distinct_subjects(const std::vector<std::string>& names) {
    std::vector<std::string> out;
    for (const auto& n : names) {
        const std::string s = subject_of(n);
        if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
    }
    return out;
}

std::vector<std::size_t> groups_by_subject(const std::vector<std::string>& names) {
    std::vector<std::string> subjects;
    std::vector<std::size_t> groups;
    for (const auto& n : names) {
        const std::string s = subject_of(n);
        if (s.empty())
            throw InvalidArgument("child '" + n + "': no subject in its name (expected a CMU name like 02_01)");
        const auto it = std::find(subjects.begin(), subjects.end(), s);
        groups.push_back(static_cast<std::size_t>(it - subjects.begin()));
        if (it == subjects.end()) subjects.push_back(s);
    }
    return groups;
}

std::optional<std::size_t> find_child(const std::vector<std::string>& names, const std::string& which) {
    if (which.empty()) return 0;
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == which || names[i].rfind(which + ":", 0) == 0) return i;
    try {
        std::size_t pos = 0;
        const unsigned long v = std::stoul(which, &pos);
        if (pos == which.size() && v < names.size()) return v;
    } catch (const std::exception&) {}
    return std::nullopt;
}

std::optional<std::size_t> group_of_subject(const std::vector<std::string>& names,
                                            const std::vector<std::size_t>& groups, const std::string& subject) {
    for (std::size_t r = 0; r < names.size() && r < groups.size(); ++r)
        if (subject_of(names[r]) == subject) return groups[r];
    return std::nullopt;
}

std::vector<bool> random_observed_frames(std::size_t frames, std::size_t observed, std::uint64_t seed) {
    if (observed > frames)
        throw InvalidArgument("observed frames: " + std::to_string(observed) + " of only " + std::to_string(frames));
    std::mt19937_64 rng(seed);
    std::vector<std::size_t> idx(frames);
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    std::shuffle(idx.begin(), idx.end(), rng);
    std::vector<bool> mask(frames, false);
    for (std::size_t i = 0; i < observed; ++i) mask[idx[i]] = true;
    return mask;
}

}  // namespace mocapdb::gp
