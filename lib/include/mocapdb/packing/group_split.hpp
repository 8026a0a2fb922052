#pragma once
// Cutting a large group of clips (one topology and frame rate, packing::group_clips) into groups of
// bounded size, so that packing holds one bounded group at a time whatever the collection's size.
#include <cstddef>
#include <vector>

namespace mocapdb::packing {

/// Source frames per packed group at most, by default (about 36 minutes at 120 Hz; packing holds a
/// group's clips, pose vectors and FK positions, about 1 kB per frame on a 31-joint rig).
inline constexpr std::size_t kMaxGroupFrames = std::size_t{1} << 18;

/// Cuts `members` (indices, in order; frames[i] is the frame count of member i) into runs of whole
/// clips of about equal frames: about ceil(total / max_frames) runs, none above max_frames except
/// where a run of one clip was merged into a neighbour. No run holds a single clip unless there is
/// only one member (a one-clip run would pay a whole group's overhead): it joins a neighbouring
/// one-clip run, else the neighbour with fewer frames, so such a run may pass max_frames by that clip
/// (or by a clip longer than max_frames).
/// One run (the input) when the total fits. InvalidArgument when max_frames is 0 or the sizes differ.
std::vector<std::vector<std::size_t>> split_by_frames(const std::vector<std::size_t>& members,
                                                      const std::vector<std::size_t>& frames, std::size_t max_frames);

}  // namespace mocapdb::packing
