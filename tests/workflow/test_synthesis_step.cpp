// The synthesis step in-process (workflow/synthesis_step.hpp, issue #17): a motion of the set's
// skeleton at a sample's parameters measures near them, with reliability 1 there (exact kriging); far
// outside the samples the reliability drops; the set's extractors are found from its parameter source.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

const WalkDatabase& synthesis_step_walks() {
    static const WalkDatabase w = make_walk_database("workflow_synth", WalkStage::Compressed);
    return w;
}

}  // namespace

TEST_CASE("workflow: source_extractors reads a set's parameter source", "[workflow]") {
    const auto ex = workflow::source_extractors("extract:turn,speed");
    REQUIRE(ex.size() == 2);
    CHECK(ex[0].names() == std::vector<std::string>{"turn"});
    CHECK(ex[1].names() == std::vector<std::string>{"speed"});
    CHECK(workflow::source_extractors("csv:params.csv").empty());
    CHECK(workflow::source_extractors("").empty());
    CHECK_THROWS_AS(workflow::source_extractors("extract:turn,wobble"), InvalidArgument);
}

TEST_CASE("workflow: synthesize at a sample's parameters gives its motion back, measured", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = synthesis_step_walks();
    const Database db(w.path);
    const MotionSet set = db.load_set("walks");
    REQUIRE(set.parameter_source == "extract:turn,speed");
    const auto model = workflow::load_motion_model(db, "walks");
    const auto skeleton = db.load_skeleton(db.find_clip("16_11")->skeleton);

    for (const Eigen::Index n : {Eigen::Index{2}, Eigen::Index{7}}) {
        const VecX c = set.parameters.row(n).transpose();
        const workflow::SynthOutcome o = workflow::synthesize(*model, set, c);
        INFO("sample " << n << ": turn " << c(0) << " rad, speed " << c(1) << " cm/s");
        CHECK(o.requested == c);
        REQUIRE(o.clip.frame_count() >= 2);
        REQUIRE(o.clip.skeleton != nullptr);
        CHECK(o.clip.skeleton->size() == skeleton->size());
        CHECK(o.clip.skeleton->channel_count() == skeleton->channel_count());
        CHECK(o.clip.frame_rate == 120.0);
        // Filtered kriging (issue #15) treats the walks' nugget as noise: rho at a sample is below 1
        // (1 - the nugget's share of the sill at most), but well above the warning threshold.
        CHECK(o.reliability > 0.5);
        CHECK(o.reliability < 1.0);
        CHECK(o.seconds > 0.0);
        // The result's own turn and speed, by the set's extractors, are the sample's.
        REQUIRE(o.measured.size() == 2);
        INFO("measured turn " << o.measured(0) << ", speed " << o.measured(1));
        CHECK(std::abs(o.measured(0) - c(0)) <= 0.05);
        CHECK(std::abs(o.measured(1) - c(1)) <= 0.10 * c(1));
        // Its duration is that of the sample (the timing is kriged from the samples' warps).
        const double sample_s = static_cast<double>(set.samples[static_cast<std::size_t>(n)].frame_count()) / 120.0;
        CHECK(o.clip.duration() == Approx(sample_s).epsilon(0.15));
    }

    // Exact kriging (the nugget not filtered): rho is 1 at every sample.
    synthesis::SynthesisOptions exact;
    exact.kriging.filter_nugget = false;
    const auto exact_model = workflow::load_motion_model(db, "walks", exact);
    for (const Eigen::Index n : {Eigen::Index{0}, Eigen::Index{7}, Eigen::Index{11}})
        CHECK(workflow::synthesize(*exact_model, set, set.parameters.row(n).transpose()).reliability ==
              Approx(1.0).margin(1e-9));

    // Far beyond the samples' speeds: extrapolated, and the reliability says so.
    VecX far = set.parameters.colwise().mean().transpose();
    far(1) = 3.0 * set.parameters.col(1).maxCoeff();
    const workflow::SynthOutcome outside = workflow::synthesize(*model, set, far);
    CHECK(outside.reliability < 0.5);
    CHECK(outside.clip.frame_count() >= 2);

    VecX wrong(3);
    wrong << 0.0, 100.0, 1.0;
    CHECK_THROWS_AS(workflow::synthesize(*model, set, wrong), InvalidArgument);
}
