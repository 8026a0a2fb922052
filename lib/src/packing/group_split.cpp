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
    // A run of one clip would spend a whole group's overhead (topology, skeletons, bases, contexts)
    // on it: it joins a neighbouring run of one clip if there is one (two problems solved at once),
    // otherwise the neighbour whose frames are fewer (the first on a tie).
    std::vector<std::uint64_t> sums;
    std::size_t k = 0;
    for (const auto& r : out) {
        std::uint64_t sum = 0;
        for (std::size_t n = 0; n < r.size(); ++n) sum += frames[k++];
        sums.push_back(sum);
    }
    for (std::size_t i = 0; i < out.size() && out.size() > 1;) {
        if (out[i].size() != 1) {
            ++i;
            continue;
        }
        bool left = i > 0 && (i + 1 == out.size() || sums[i - 1] <= sums[i + 1]);
        if (i > 0 && i + 1 < out.size() && (out[i - 1].size() == 1) != (out[i + 1].size() == 1))
            left = out[i - 1].size() == 1;
        const std::size_t into = left ? i - 1 : i + 1;
        if (left) out[into].push_back(out[i].front());
        else out[into].insert(out[into].begin(), out[i].front());
        sums[into] += sums[i];
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(i));
        sums.erase(sums.begin() + static_cast<std::ptrdiff_t>(i));
        if (left) i = into;  // the grown run is checked again (it has two clips now)
    }
    return out;
}

}  // namespace mocapdb::packing
