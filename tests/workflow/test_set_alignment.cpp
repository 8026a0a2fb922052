// The alignment step in-process (workflow/set_alignment.hpp, issue #17): the D × T × N tensor of a set
// of subject 16's walks stored, its labels, distance and phase check; a chosen reference; the errors,
// with the stored alignment untouched by a failed step.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

const WalkDatabase& set_alignment_walks() {
    static const WalkDatabase w = make_walk_database("workflow_align", WalkStage::SetCreated);
    return w;
}

}  // namespace

TEST_CASE("workflow: align_set stores the aligned tensor of the set", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = set_alignment_walks();
    const std::size_t n = w.set.set.samples.size();
    REQUIRE(n == 12);

    workflow::AlignRequest r;
    r.set = "walks";
    r.frames = 40;
    std::size_t reads = 0, steps = 0;
    r.read_progress = [&](const Progress& p) {
        ++reads;
        CHECK(p.total == n);
    };
    r.progress = [&](const Progress&) { ++steps; };
    const workflow::AlignOutcome o = workflow::align_set(w.path, r);
    CHECK(reads == n);
    CHECK(steps >= n);
    CHECK(o.aligned.method == "dtw");
    CHECK(o.aligned.frames() == 40);
    CHECK(o.aligned.samples() == static_cast<Eigen::Index>(n));
    const Database db(w.path);
    const auto skeleton = db.load_skeleton(db.find_clip("16_11")->skeleton);
    CHECK(o.aligned.dofs() == static_cast<Eigen::Index>(PoseLayout(*skeleton).dof_count()));
    REQUIRE(o.labels.size() == n);
    CHECK(o.labels.front() == "16_11");  // whole clips: the label is the clip id
    CHECK(o.labels.back() == "16_22");
    CHECK(std::isfinite(o.distance));
    CHECK(o.distance > 0.0);
    CHECK(o.distance < 20.0);  // cm: walks of one subject, warped onto one another
    // Walks have feet: the forward-foot check ran.
    REQUIRE(o.phase.has_value());
    CHECK(o.phase->share.size() == 40);
    CHECK(o.phase->min <= o.phase->mean);
    CHECK(o.phase->mean <= 1.0);
    CHECK(o.phase->min >= 0.5);

    const auto stored = db.load_aligned("walks");
    REQUIRE(stored.has_value());
    CHECK(stored->method == "dtw");
    CHECK(stored->reference == o.aligned.reference);
    REQUIRE(stored->frames() == 40);
    const Eigen::Map<const VecX> a(o.aligned.tensor.data(), o.aligned.tensor.size());
    const Eigen::Map<const VecX> b(stored->tensor.data(), stored->tensor.size());
    CHECK(a.isApprox(b, 1e-12));
}

TEST_CASE("workflow: align_set with a chosen reference, linear, and its errors", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = set_alignment_walks();
    workflow::AlignRequest r;
    r.set = "walks";
    r.frames = 24;
    r.reference = "16_15";
    const workflow::AlignOutcome o = workflow::align_set(w.path, r);
    REQUIRE(o.aligned.reference < o.labels.size());
    CHECK(o.labels[o.aligned.reference] == "16_15");
    CHECK(o.aligned.frames() == 24);

    r.method = "linear";
    r.reference.clear();
    const workflow::AlignOutcome linear = workflow::align_set(w.path, r);
    CHECK(linear.aligned.method == "linear");
    CHECK(Database(w.path).load_aligned("walks")->method == "linear");

    // Errors leave the stored alignment as it was.
    const auto bytes = database_disk_bytes(w.path);
    r.reference = "16_99";
    CHECK_THROWS_AS(workflow::align_set(w.path, r), InvalidArgument);
    CHECK_THROWS_WITH(workflow::align_set(w.path, r), Contains("set 'walks' has no sample '16_99'"));
    r.reference.clear();
    r.set = "runs";
    CHECK_THROWS_WITH(workflow::align_set(w.path, r), Contains("runs"));
    CHECK(database_disk_bytes(w.path) == bytes);
    CHECK(Database(w.path).load_aligned("walks")->frames() == 24);
}

TEST_CASE("workflow: align_set tells samples cut at one gait phase from whole clips (the phase hint's case)",
          "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = set_alignment_walks();
    workflow::AlignRequest r;
    r.set = "walks";
    r.frames = 24;
    // Whole walks start wherever the capture started: the hint to cut them at one phase applies.
    CHECK_FALSE(workflow::align_set(w.path, r).cut_at_gait_phase);

    // The same clips cut into gait cycles (set create --segment gait): every sample starts at a left-foot
    // pass, so the hint must not suggest cutting them so again.
    workflow::SetRequest cycles;
    cycles.name = "cycles";
    cycles.clips = {"16_*"};
    cycles.segment = "gait:2";
    cycles.extract = {"speed"};
    workflow::create_set(w.path, cycles);
    r.set = "cycles";
    const workflow::AlignOutcome o = workflow::align_set(w.path, r);
    CHECK(o.aligned.samples() >= 12);
    REQUIRE(o.phase.has_value());
    CHECK(o.cut_at_gait_phase);
}
