// `mocapdb info`'s summary in-process (workflow/database_summary.hpp, issue #17): totals over the clips,
// skeletons, sets, and each clip's packed-tier entry once the database is packed.
#include <catch2/catch.hpp>

#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/workflow/database_summary.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("workflow: the summary of a database, before and after packing", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase w = make_walk_database("workflow_summary", WalkStage::Compressed);
    const workflow::DatabaseSummary s = workflow::summarize_database(w.path);
    REQUIRE(s.clips.size() == 12);
    REQUIRE(s.packed_clips.size() == 12);
    CHECK_FALSE(s.packed.has_value());
    for (const auto& p : s.packed_clips) CHECK_FALSE(p.has_value());
    std::size_t frames = 0;
    std::uint64_t stored = 0;
    for (const ClipRecord& c : s.clips) {
        frames += c.frames;
        stored += c.stored_bytes;
    }
    CHECK(s.total_frames == frames);
    CHECK(s.total_stored_bytes == stored);
    CHECK(s.total_seconds == Approx(w.imported.summary.seconds));
    REQUIRE(s.skeletons.size() == 1);
    CHECK(s.skeletons[0].joints > 20);
    CHECK(s.skeletons[0].source_file == "16.asf");
    REQUIRE(s.sets.size() == 1);
    CHECK(s.sets[0].name == "walks");
    CHECK(s.sets[0].aligned);
    CHECK(s.sets[0].model);
    CHECK(s.file_bytes > stored / 2);
    CHECK(s.format_version >= 1);

    workflow::PackDatabaseOptions po;
    po.max_error_cm = 1.0;
    const workflow::PackDatabaseOutcome po_out = workflow::pack_database(w.path, po);
    CHECK(po_out.ratio_float32() == Approx(static_cast<double>(po_out.float32_bytes) / static_cast<double>(po_out.tier.bytes)));
    CHECK(po_out.bytes_per_second() == Approx(static_cast<double>(po_out.tier.bytes) / po_out.motion_seconds));
    REQUIRE(!po_out.tier.groups.empty());
    CHECK(po_out.group_ratio_float32(0) > 1.0);
    const workflow::DatabaseSummary packed = workflow::summarize_database(w.path);
    REQUIRE(packed.packed.has_value());
    for (std::size_t i = 0; i < packed.clips.size(); ++i) {
        REQUIRE(packed.packed_clips[i].has_value());
        CHECK(packed.packed_clips[i]->clip.id == packed.clips[i].id);
        CHECK(packed.packed_clips[i]->clip.max_cm <= 1.0);
        CHECK(!packed.packed_clips[i]->group.empty());
    }
}
