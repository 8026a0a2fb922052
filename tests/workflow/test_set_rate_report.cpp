// The rate-distortion step in-process (workflow/set_rate_report.hpp and aligned_set_data.hpp, issue
// #17): the rows on a set of subject 16's walks, the source motion they are compared against, and the
// loader's refusal of a set that is not aligned.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/set_rate_report.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

const WalkDatabase& set_rate_report_walks() {
    static const WalkDatabase w = make_walk_database("workflow_rate", WalkStage::Aligned);
    return w;
}

}  // namespace

TEST_CASE("workflow: load_aligned_set gives the set, its tensor, skeleton and source size", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = set_rate_report_walks();
    const Database db(w.path);
    const workflow::AlignedSetData d = workflow::load_aligned_set(db, "walks");
    CHECK(d.set.samples.size() == 12);
    CHECK(d.aligned.samples() == 12);
    CHECK(d.aligned.frames() == 40);
    REQUIRE(d.skeleton != nullptr);
    CHECK(d.frame_rate == 120.0);
    std::size_t frames = 0;
    for (const SampleRef& s : d.set.samples) frames += s.frame_count();
    CHECK(d.seconds_of_motion == Approx(static_cast<double>(frames) / 120.0));
    CHECK(d.clip_channel_values == frames * d.skeleton->channel_count());

    workflow::SetRequest r;
    r.name = "few";
    r.clips = {"16_11", "16_12", "16_13"};
    r.segment = "none";
    r.extract = {"speed"};
    workflow::create_set(w.path, r);
    CHECK_THROWS_AS(workflow::load_aligned_set(Database(w.path), "few"), InvalidArgument);
    CHECK_THROWS_WITH(workflow::load_aligned_set(Database(w.path), "few"),
                      Contains("set 'few'") && Contains("is not aligned") && !Contains("mocapdb align"));
    // The library names no command; the remedy tells a front end which of its own to suggest.
    try {
        workflow::load_aligned_set(Database(w.path), "few");
        FAIL("an unaligned set was loaded");
    } catch (const Remediable& e) {
        CHECK(e.remedy() == Remedy::AlignFirst);
    }
}

TEST_CASE("workflow: rate_report measures every method on the set at the targets", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = set_rate_report_walks();
    const workflow::AlignedSetData d = workflow::load_aligned_set(Database(w.path), "walks");
    compression::RateOptions options;
    options.max_cm = {1.0};
    options.hooi = false;
    std::size_t rows_done = 0;
    options.progress = [&](const Progress& p) { rows_done = p.done; };
    const workflow::RateOutcome r = workflow::rate_report(d, options);

    const tensor::Dims3 dims{d.aligned.dofs(), 40, 12};
    CHECK(r.report.dims == dims);
    CHECK(r.report.raw_bytes == static_cast<std::uint64_t>(4 * dims[0] * dims[1] * dims[2]));
    CHECK(r.report.side_bytes > 0);  // timing and the 2 parameters per sample
    CHECK(r.clip_bytes == 4 * d.clip_channel_values);
    CHECK(r.seconds == d.seconds_of_motion);
    CHECK(r.joints == PoseLayout(*d.skeleton).rotation_joints().size());
    REQUIRE_FALSE(r.report.rows.empty());
    CHECK(rows_done == r.report.rows.size());
    bool tucker = false;
    for (const compression::RateRow& row : r.report.rows) {
        INFO(row.method << " target " << row.target_cm);
        CHECK(row.bytes > 0);
        if (row.target_cm > 0.0 && row.target_met) CHECK(row.stats.max_cm <= row.target_cm);
        if (row.method == "tucker" && row.target_cm == 1.0) {
            tucker = true;
            CHECK(row.target_met);
            CHECK(row.ratio > 1.0);
        }
    }
    CHECK(tucker);
}
