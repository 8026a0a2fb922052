#pragma once
// Choosing children of replicate data by name (`mocapdb gp`): the CMU subject of a child's
// name, groups of children by subject (the middle layer of a three-layer model), a child by name or
// index, the group of a subject, and which frames of a child are observed (a seeded random choice).
// Pure functions. Errors: InvalidArgument as stated. Threads: no shared state.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mocapdb::gp {

/// The subject of a CMU-named child ("02_01", "02_01:0-120" -> "02"); empty when the name has none.
std::string subject_of(const std::string& child_name);

/// The distinct subjects of the names, in order of first appearance.
std::vector<std::string> distinct_subjects(const std::vector<std::string>& child_names);

/// One group per child: the index of its subject among the subjects in order of first appearance.
/// InvalidArgument when a name has no subject.
std::vector<std::size_t> groups_by_subject(const std::vector<std::string>& child_names);

/// The child named `which` (exactly, or "which:..." for a segment of it), else `which` as an index
/// from 0; the first child when `which` is empty; nothing when none matches.
std::optional<std::size_t> find_child(const std::vector<std::string>& child_names, const std::string& which);

/// The group of the first child of `subject` (groups as groups_by_subject); nothing when no child is
/// of that subject.
std::optional<std::size_t> group_of_subject(const std::vector<std::string>& child_names,
                                            const std::vector<std::size_t>& groups, const std::string& subject);

/// `observed` of `frames` flags set, chosen by a shuffle seeded with `seed` (reproducible).
/// InvalidArgument when observed > frames.
std::vector<bool> random_observed_frames(std::size_t frames, std::size_t observed, std::uint64_t seed);

}  // namespace mocapdb::gp
