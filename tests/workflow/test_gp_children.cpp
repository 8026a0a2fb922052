// The children of `mocapdb gp` in-process (workflow/gp_children.hpp, issue #17): a stored set's samples
// (named CLIP:BEGIN-END, with the set's frames) and clip files (named by their stem).
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/workflow/gp_children.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("workflow: gp children from a stored set and from clip files", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase w = make_walk_database("workflow_gp_children", WalkStage::SetCreated);
    const workflow::GpChildren set = workflow::set_children(w.path, "walks");
    REQUIRE(set.clips.size() == 12);
    REQUIRE(set.names.size() == 12);
    const SampleRef& first = w.set.set.samples[0];
    CHECK(set.names[0] == first.clip + ":" + std::to_string(first.begin) + "-" + std::to_string(first.end));
    CHECK(set.clips[0].frame_count() == first.frame_count());
    CHECK_THROWS_AS(workflow::set_children(w.path, "no-such-set"), Error);

    const auto files = walk_files();
    const workflow::GpChildren clips = workflow::clip_file_children({files[0].string(), files[1].string()}, 60.0);
    REQUIRE(clips.names == std::vector<std::string>{"16_11", "16_12"});
    CHECK(clips.clips[0].frame_rate == 60.0);
    CHECK_THROWS_AS(workflow::clip_file_children({"/nonexistent/clip.bvh"}, 0.0), Error);
}
