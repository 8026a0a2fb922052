// The summary of a set's dropout repairs (dataset/dropout_repair.hpp, issue #17): the clips once each in
// record order and the longest run, as `set create` reports them.
#include <catch2/catch.hpp>

#include "mocapdb/dataset/dropout_repair.hpp"

using namespace mocapdb;

TEST_CASE("repair summary: distinct clips in order and the longest run", "[dataset]") {
    const std::vector<RepairedFrames> repairs{
        {"16_15", "lhumerus", 0, 2}, {"16_15", "lhand", 0, 7}, {"16_23", "rhumerus", 0, 3}, {"16_15", "lthumb", 3, 5}};
    const RepairSummary s = summarize_repairs(repairs);
    CHECK(s.clips == std::vector<std::string>{"16_15", "16_23"});
    CHECK(s.longest_run == 7);
    const RepairSummary none = summarize_repairs({});
    CHECK(none.clips.empty());
    CHECK(none.longest_run == 0);
}
