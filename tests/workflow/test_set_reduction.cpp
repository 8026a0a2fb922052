// Sample reduction and synthesis warnings in-process (workflow/set_reduction.hpp,
// workflow/synthesis_warnings.hpp, issue #17) on subject 16's walks: the greedy removal, the reduced set
// stored and aligned like the original, and the low-reliability judgement far from the samples.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "mocapdb/workflow/set_reduction.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("workflow: reduce a set by leave-one-out reliability and store the kept samples", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase w = make_walk_database("workflow_reduction", WalkStage::Compressed);
    workflow::ReductionRequest request;
    request.set = "walks";
    request.tau = 0.5;
    const workflow::ReductionOutcome out = workflow::reduce_set(w.path, request);
    const auto& r = out.result;
    CHECK(out.set.samples.size() == 12);
    CHECK(out.labels.size() == 12);
    CHECK(r.kept.size() + r.removed.size() == 12);
    CHECK(out.model_kind == "tucker");
    for (double rho : r.removed_reliability) CHECK(rho >= request.tau);
    if (r.stopped_on_threshold) CHECK(r.max_reliability.back() < request.tau);

    request.naive = true;
    const workflow::ReductionOutcome naive = workflow::reduce_set(w.path, request);
    CHECK(naive.model_kind == "naive");

    const MotionSet reduced = workflow::reduced_set(out.set, r.kept, "walks-small");
    REQUIRE(reduced.samples.size() == r.kept.size());
    for (std::size_t k = 0; k < r.kept.size(); ++k) {
        CHECK(reduced.samples[k].clip == out.set.samples[static_cast<std::size_t>(r.kept[k])].clip);
        CHECK(reduced.parameters.row(static_cast<Eigen::Index>(k)) == out.set.parameters.row(r.kept[k]));
    }
    CHECK(reduced.parameter_source == out.set.parameter_source);

    if (r.kept.size() >= 2) {
        CHECK(workflow::store_reduced_set(w.path, out, "walks-small", false));
        const Database db(w.path);
        CHECK(db.load_set("walks-small").samples.size() == r.kept.size());
        const auto aligned = db.load_aligned("walks-small");
        REQUIRE(aligned);
        CHECK(aligned->frames() == 40);
        CHECK(aligned->samples() == static_cast<Eigen::Index>(r.kept.size()));
    }
    CHECK_THROWS_AS(workflow::store_reduced_set(w.path, out, "walks", false), InvalidArgument);
    workflow::ReductionOutcome one = out;
    one.result.kept.resize(1);
    CHECK_THROWS_AS(workflow::store_reduced_set(w.path, one, "walks-one", false), InvalidArgument);
}

TEST_CASE("workflow: synthesis warnings judge reliability and the kernel", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase w = make_walk_database("workflow_warnings", WalkStage::Compressed);
    const Database db(w.path);
    const auto model = workflow::load_motion_model(db, "walks");
    const VecX near = model->sample_parameters().row(0).transpose();
    VecX far = workflow::samples_mean(*model);
    far(1) += 100.0 * (model->sample_parameters().col(1).maxCoeff() - model->sample_parameters().col(1).minCoeff());
    // The set's calibrated threshold (compress): flagged where the variance ratio exceeds it.
    const MotionSet set = db.load_set("walks");
    const workflow::SynthesisWarnings wn = workflow::synthesis_warnings(*model, set, near);
    const workflow::SynthesisWarnings wf = workflow::synthesis_warnings(*model, set, far);
    CHECK(wn.calibrated);
    CHECK(wn.rho == model->reliability(near));
    CHECK(wn.beyond_sd == 0.0);
    CHECK(wn.low_reliability == workflow::edge_warning(*model).flags(model->variance_ratio(near), 0.0, wn.nearby_misses));
    CHECK_FALSE(wn.low_reliability);
    CHECK(wf.low_reliability);
    CHECK(wf.rho == 0.0);
    CHECK_FALSE((wn.regularized && wn.jittered));
}
