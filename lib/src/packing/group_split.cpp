#include "mocapdb/packing/group_split.hpp"

#include <cstdint>

#include "mocapdb/core/error.hpp"

namespace mocapdb::packing {

std::vector<std::vector<std::size_t>> split_by_frames(const std::vector<std::size_t>& members,
                                                      const std::vector<std::size_t>& frames, std::size_t max_frames) {
    if (max_frames == 0) throw InvalidArgument("split_by_frames: max_frames must be >= 1");
    if (members.size() != frames.size())
        throw InvalidArgument("split_by_frames: " + std::to_string(members.size()) + " members but " +
                              std::to_string(frames.size()) + " frame counts");
    std::uint64_t total = 0;
    for (std::size_t f : frames) total += f;
    const std::uint64_t parts = (total + max_frames - 1) / max_frames;
    if (parts <= 1) return {members};
    // Runs close once they would pass the average; equal shares keep every run below max_frames.
    const std::uint64_t target = (total + parts - 1) / parts;
    std::vector<std::vector<std::size_t>> out(1);
    std::uint64_t run = 0;
    for (std::size_t i = 0; i < members.size(); ++i) {
        if (!out.back().empty() && run + frames[i] > target) {
            out.emplace_back();
            run = 0;
        }
        out.back().push_back(members[i]);
        run += frames[i];
    }
    return out;
}

}  // namespace mocapdb::packing
