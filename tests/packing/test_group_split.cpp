// split_by_frames: a group cut into runs of whole clips, in order, none above the frame budget
// unless a single clip is (the bound on pack's memory).
#include <catch2/catch.hpp>

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
        for (const auto& run : runs) {
            REQUIRE_FALSE(run.empty());
            std::size_t sum = 0;
            for (std::size_t m : run) {
                joined.push_back(m);
                sum += frames[k++];
            }
            CHECK((sum <= budget || run.size() == 1));
        }
        CHECK(joined == members);
        const std::size_t total = std::accumulate(frames.begin(), frames.end(), std::size_t{0});
        if (total <= budget) CHECK(runs.size() == 1);
    }
}

TEST_CASE("split_by_frames: equal shares, a clip longer than the budget alone, bad arguments", "[packing]") {
    CHECK(split_by_frames({0, 1, 2, 3}, {100, 100, 100, 100}, 200) ==
          std::vector<std::vector<std::size_t>>{{0, 1}, {2, 3}});
    CHECK(split_by_frames({0, 1, 2}, {10, 500, 10}, 100) == std::vector<std::vector<std::size_t>>{{0}, {1}, {2}});
    CHECK(split_by_frames({}, {}, 10) == std::vector<std::vector<std::size_t>>{{}});
    CHECK_THROWS_AS(split_by_frames({0}, {1}, 0), InvalidArgument);
    CHECK_THROWS_AS(split_by_frames({0, 1}, {1}, 10), InvalidArgument);
}
