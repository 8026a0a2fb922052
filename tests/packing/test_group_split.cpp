// split_by_frames: a group cut into runs of whole clips, in order, within the frame budget (the bound
// on pack's memory) except for a one-clip run merged into a neighbour, and never a run of one clip
// when there are several (a whole group's overhead for one clip, issue 36).
#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <random>

#include "mocapdb/core/error.hpp"
#include "mocapdb/packing/group_split.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;

TEST_CASE("split_by_frames keeps order, whole clips and the budget", "[packing]") {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 200; ++trial) {
        const std::size_t n = 1 + rng() % 40;
        std::vector<std::size_t> members(n), frames(n);
        std::iota(members.begin(), members.end(), std::size_t{100});
        for (std::size_t& f : frames) f = 1 + rng() % 5000;
        const std::size_t budget = 1 + rng() % 20000;
        const auto runs = split_by_frames(members, frames, budget);
        std::vector<std::size_t> joined;
        std::size_t k = 0;
        const std::size_t longest = *std::max_element(frames.begin(), frames.end());
        for (const auto& run : runs) {
            REQUIRE_FALSE(run.empty());
            if (n > 1) CHECK(run.size() >= 2);
            std::size_t sum = 0;
            for (std::size_t m : run) {
                joined.push_back(m);
                sum += frames[k++];
            }
            // A run within the budget, grown by at most a one-clip run on each side (or made of them).
            CHECK(sum <= std::max(budget, longest) + 2 * longest);
        }
        CHECK(joined == members);
        const std::size_t total = std::accumulate(frames.begin(), frames.end(), std::size_t{0});
        if (total <= budget) CHECK(runs.size() == 1);
    }
}

TEST_CASE("split_by_frames: equal shares, a clip longer than the budget alone, bad arguments", "[packing]") {
    CHECK(split_by_frames({0, 1, 2, 3}, {100, 100, 100, 100}, 200) ==
          std::vector<std::vector<std::size_t>>{{0, 1}, {2, 3}});
    // One-clip runs join the neighbour with fewer frames (here all three end up together).
    CHECK(split_by_frames({0, 1, 2}, {10, 500, 10}, 100) == std::vector<std::vector<std::size_t>>{{0, 1, 2}});
    // Two neighbouring one-clip runs pair up rather than both joining the smaller neighbour.
    CHECK(split_by_frames({0, 1, 2, 3}, {87, 74, 222, 236}, 309) ==
          std::vector<std::vector<std::size_t>>{{0, 1}, {2, 3}});
    // A remainder of one clip joins its neighbour instead of forming a group of its own.
    CHECK(split_by_frames({0, 1, 2, 3, 4}, {100, 100, 100, 100, 10}, 200) ==
          std::vector<std::vector<std::size_t>>{{0, 1}, {2, 3, 4}});
    CHECK(split_by_frames({0, 1, 2, 3}, {100, 100, 100, 10}, 300) ==
          std::vector<std::vector<std::size_t>>{{0, 1}, {2, 3}});
    CHECK(split_by_frames({7}, {900}, 100) == std::vector<std::vector<std::size_t>>{{7}});
    CHECK(split_by_frames({}, {}, 10) == std::vector<std::vector<std::size_t>>{{}});
    CHECK_THROWS_AS(split_by_frames({0}, {1}, 0), InvalidArgument);
    CHECK_THROWS_AS(split_by_frames({0, 1}, {1}, 10), InvalidArgument);
}
