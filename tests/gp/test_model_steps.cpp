// The steps of `mocapdb gp` in-process (gp/child_selection.hpp, gp/model_steps.hpp, issue #17): children
// chosen by CMU name and subject, a reproducible observed-frame mask, interpolating a child of three
// CMU walks from its siblings, sampling new children, the replicate experiment and the model summary.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/child_selection.hpp"
#include "mocapdb/gp/model_steps.hpp"
#include "mocapdb/gp/motion_data.hpp"
#include "mocapdb/workflow/gp_children.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;

TEST_CASE("gp child selection: subjects, groups, children by name or index, observed frames", "[gp]") {
    const std::vector<std::string> names{"02_01", "02_02:0-120", "16_15", "35_01", "16_16"};
    CHECK(subject_of("02_01:0-120") == "02");
    CHECK(subject_of("walk").empty());
    CHECK(subject_of("_01").empty());
    CHECK(distinct_subjects(names) == std::vector<std::string>{"02", "16", "35"});
    CHECK(groups_by_subject(names) == std::vector<std::size_t>{0, 0, 1, 2, 1});
    CHECK_THROWS_AS(groups_by_subject({"02_01", "walk"}), InvalidArgument);
    CHECK(find_child(names, "") == std::optional<std::size_t>(0));
    CHECK(find_child(names, "02_02") == std::optional<std::size_t>(1));  // a segment of clip 02_02
    CHECK(find_child(names, "35_01") == std::optional<std::size_t>(3));
    CHECK(find_child(names, "4") == std::optional<std::size_t>(4));
    CHECK_FALSE(find_child(names, "5").has_value());
    CHECK_FALSE(find_child(names, "4x").has_value());
    CHECK_FALSE(find_child(names, "99_01").has_value());
    const auto groups = groups_by_subject(names);
    CHECK(group_of_subject(names, groups, "16") == std::optional<std::size_t>(1));
    CHECK_FALSE(group_of_subject(names, groups, "99").has_value());

    const std::vector<bool> mask = random_observed_frames(20, 8, 1);
    REQUIRE(mask.size() == 20);
    CHECK(std::count(mask.begin(), mask.end(), true) == 8);
    CHECK(mask == random_observed_frames(20, 8, 1));   // reproducible
    CHECK(mask != random_observed_frames(20, 8, 2));
    CHECK_THROWS_AS(random_observed_frames(5, 6, 1), InvalidArgument);
}

namespace {

MotionData three_walks() {
    const auto dir = mocapdb::test::datasets_dir() / "cmu-asfamc";
    const workflow::GpChildren children = workflow::clip_file_children(
        {(dir / "02_01.amc").string(), (dir / "02_02.amc").string(), (dir / "35_01.amc").string()}, 0.0);
    MotionDataOptions o;
    o.frames = 20;
    o.include_joints = {"lfemur", "ltibia"};
    return prepare_motion_data(children.clips, children.names, o);
}

FitOptions short_fit() {
    FitOptions f;
    f.max_iterations = 40;
    return f;
}

}  // namespace

TEST_CASE("gp steps on three CMU walks: fit, interpolate a child, sample, summary", "[gp][shared]") {
    MOCAPDB_REQUIRE_SHARED(mocapdb::test::datasets_dir() / "cmu-asfamc" / "35_01.amc");
    const MotionData md = three_walks();
    REQUIRE(md.child_names == std::vector<std::string>{"02_01", "02_02", "35_01"});
    ModelSpec spec;
    spec.kernel = KernelType::Matern32;

    const FitResult f = fit_model(md.data, spec, short_fit());
    CHECK(std::isfinite(f.log_likelihood));
    const ModelSummary s = summarize_model(f.model);
    REQUIRE(s.parent.size() == 1);
    CHECK(s.group.empty());
    REQUIRE(s.child.size() == 1);
    CHECK(s.child[0].kernel == KernelType::Matern32);
    CHECK(s.child[0].lengthscale_s == Approx(std::exp(f.model.child.terms[0].log_lengthscale)));
    CHECK(s.child[0].mean_b_diagonal > 0.0);
    CHECK(s.noise_min <= s.noise_mean);
    CHECK(s.noise_mean <= s.noise_max);
    CHECK(s.noise_min > 0.0);

    const ChildInterpolation in = interpolate_child(md.data, 1, 8, spec, short_fit(), 1);
    CHECK(in.observed == random_observed_frames(20, 8, 1));
    CHECK(in.scores.points == (20 - 8) * md.data.outputs());
    CHECK(std::isfinite(in.scores.mse));
    REQUIRE(in.prediction.mean.rows() == static_cast<Eigen::Index>(md.data.outputs()));
    REQUIRE(in.prediction.mean.cols() == 20);
    // At the observed frames the posterior follows the child's own values closely.
    double observed_error = 0.0, unobserved_error = 0.0;
    for (Eigen::Index t = 0; t < 20; ++t) {
        const double e = (in.prediction.mean.col(t) - md.data.children[1].col(t)).squaredNorm();
        (in.observed[static_cast<std::size_t>(t)] ? observed_error : unobserved_error) += e;
    }
    CHECK(observed_error / 8.0 < unobserved_error / 12.0);
    CHECK_THROWS_AS(interpolate_child(md.data, 1, 19, spec, short_fit(), 1), InvalidArgument);
    CHECK_THROWS_AS(interpolate_child(md.data, 3, 8, spec, short_fit(), 1), InvalidArgument);

    SampleOptions so;
    so.seed = 3;
    const NewChildren drawn = sample_new_children(md.data, spec, short_fit(), 2, so);
    REQUIRE(drawn.samples.size() == 2);
    CHECK(drawn.samples[0].rows() == drawn.trend.rows());
    CHECK(drawn.samples[0].cols() == 20);
    CHECK(drawn.fit.log_likelihood == f.log_likelihood);  // same data and options: the same fit
    CHECK(drawn.samples[0] != drawn.samples[1]);
    const Clip trend = reassemble_clip(md, drawn.trend, "trend");
    CHECK(trend.frame_count() == 20);
}

TEST_CASE("gp replicate experiment: split into training children and real motions", "[gp][shared]") {
    MOCAPDB_REQUIRE_SHARED(mocapdb::test::datasets_dir() / "cmu-asfamc" / "35_01.amc");
    const MotionData md = three_walks();
    const ReplicateSplit split = split_replicates(md.data, 2);
    REQUIRE(split.training.child_count() == 2);
    REQUIRE(split.real.size() == 1);
    CHECK(split.real[0] == md.data.children[2]);
    CHECK(split.training.times == md.data.times);
    CHECK_THROWS_AS(split_replicates(md.data, 4), InvalidArgument);

    const ReplicateSplit all_training = split_replicates(md.data, 3);
    ExperimentOptions o;
    o.runs = 1;
    o.fit = short_fit();
    const ReplicateExperiment e = run_replicate_experiment(all_training.training, all_training.real, 0, {10, 5}, 3, o);
    REQUIRE(e.interpolation.rows.size() == 2);
    CHECK(e.interpolation.rows[0].observed == 10);
    CHECK(e.interpolation.rows[1].observed == 5);
    CHECK_FALSE(e.synthesis.has_value());  // no real motions to score against
}
