// The evaluation as library steps (issue #17): the run plans, the methods compared on a set, a small
// run of every experiment on six of subject 16's walks with its stage events, and the verdicts and
// measurements the report prints, checked against the results they were drawn from.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/evaluation.hpp"
#include "mocapdb/eval/evaluation_plan.hpp"
#include "mocapdb/eval/verdicts.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using namespace mocapdb::eval;

TEST_CASE("evaluation plans: every mode names its sets and a runtime set among them", "[eval]") {
    for (EvalMode mode : {EvalMode::Full, EvalMode::Quick, EvalMode::Tiny}) {
        INFO(to_string(mode));
        const EvalPlan plan = make_eval_plan(mode);
        REQUIRE(!plan.sets.empty());
        bool runtime_found = false;
        for (const auto& s : plan.sets) {
            CHECK(!s.spec.clips.empty());
            CHECK(s.loo_stride >= 1);
            runtime_found = runtime_found || s.spec.name == plan.runtime_set;
        }
        CHECK(runtime_found);
    }
    CHECK(make_eval_plan(EvalMode::Full).sets.size() == 5);
    CHECK(make_eval_plan(EvalMode::Quick).sets.size() == 1);
    CHECK(make_eval_plan(EvalMode::Tiny).sets[0].spec.clips.size() == 9);
    CHECK(std::string(to_string(EvalMode::Quick)) == "quick");
}

namespace {

EvalPlan small_plan() {
    EvalPlan plan = make_eval_plan(EvalMode::Tiny);
    EvalPlan::SetPlan& sp = plan.sets.at(0);
    sp.spec.name = "walks6";
    sp.spec.clips = {"16_11", "16_13", "16_15", "16_17", "16_19", "16_21"};
    sp.spec.frames = 10;
    sp.loo_stride = 2;
    sp.reduction = false;
    plan.tucker_targets = {3.0};
    plan.constraint.points_per_axis_2d = 3;
    plan.runtime_set = "walks6";
    plan.runtime.sizes = {5, 6, 9};  // 9 is clamped to the set's 6 samples
    return plan;
}

}  // namespace

TEST_CASE("evaluation run: every experiment on six walks, stage events, verdicts and measurements", "[eval][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const EvalPlan plan = small_plan();
    std::vector<EvalStage> started, done;
    EvalObserver observer;
    observer.stage_started = [&](EvalStage stage, const std::string& set) {
        CHECK(set == "walks6");
        started.push_back(stage);
        return ProgressCallback{};
    };
    observer.stage_done = [&](const EvalStageDone& d) {
        REQUIRE(d.set != nullptr);
        CHECK(d.seconds >= 0.0);
        CHECK((d.results != nullptr) == (d.stage != EvalStage::BuildSet && d.stage != EvalStage::Runtime));
        done.push_back(d.stage);
    };
    const EvalResults e = run_evaluation(plan, test::datasets_dir() / "cmu-asfamc", describe_run("test", EvalMode::Tiny), observer);
    CHECK(done == std::vector<EvalStage>{EvalStage::BuildSet, EvalStage::LeaveOneOut, EvalStage::KernelHeadroom,
                                         EvalStage::NestedChoice, EvalStage::Constraint, EvalStage::EdgeWarning,
                                         EvalStage::Compression, EvalStage::Runtime});
    CHECK(started == std::vector<EvalStage>{EvalStage::LeaveOneOut, EvalStage::KernelHeadroom, EvalStage::NestedChoice,
                                            EvalStage::Constraint, EvalStage::EdgeWarning, EvalStage::Compression,
                                            EvalStage::Runtime});
    // The edge warning was calibrated on one draw and judged on another of the same sizes.
    REQUIRE(e.sets.front().has_edge);
    const EdgeEvaluation& edge_eval = e.sets.front().edge;
    CHECK(edge_eval.calibration.probes == edge_eval.options.inside + edge_eval.options.beyond);
    CHECK(edge_eval.fresh_inside + edge_eval.fresh_beyond == edge_eval.calibration.probes);
    CHECK(edge_eval.calibrated.detection >= 0.0);
    CHECK(edge_eval.calibrated.detection <= 1.0);
    CHECK(edge_eval.calibrated.false_alarms <= 1.0);
    CHECK(e.info.command == "test");
    CHECK(e.info.mode == "tiny");
    CHECK(e.info.wall_seconds > 0.0);
    CHECK(e.info.cpu_seconds > 0.0);

    REQUIRE(e.sets.size() == 1);
    const SetResults& r = e.sets[0];
    const EvalSet& set = *r.set;
    REQUIRE(set.size() == 6);
    // Methods: per-pose, per-element, one Tucker target, the N/3 Tucker, naive, rbf, nn, trend.
    REQUIRE(r.methods.size() == 8);
    CHECK(r.tucker_targets_cm == std::vector<double>{3.0, 3.0});
    CHECK(r.methods[3].name == "tucker-R3=N/3");
    CHECK(r.methods[3].ranks[2] <= 2);
    CHECK(r.has_loo);
    CHECK(r.loo.samples == std::vector<Eigen::Index>{0, 2, 4});
    CHECK(r.has_headroom);
    CHECK(r.headroom.kernels == 8);  // the tiny grid: 2 exponents x 2 ranges x 2 nugget shares
    CHECK(r.headroom.best_pose_mean_cm <= r.headroom.median_pose_mean_cm);
    // The predictor synthesis chooses, by nested cross-validation over the leave-one-out's folds.
    REQUIRE(r.has_nested);
    CHECK(r.nested.folds.size() == r.loo.samples.size());
    REQUIRE(r.nested.methods.size() == 3);
    CHECK(r.nested.chosen.picks.size() == 3);
    REQUIRE(r.nested.chosen.counts.size() == 4);  // kriging, rbf, trend, averages
    // The learned-metric kriging over the same folds: walks have two numeric parameters, so ARD (the
    // first axis kept, the second scaled within the grid).
    REQUIRE(r.nested.learned_metric.has_value());
    CHECK(r.nested.learned_metric->kind == "ard");
    CHECK(r.nested.learned_metric->pose_mean_cm.size() == 3);
    CHECK(std::isfinite(r.nested.learned_metric->pose_mean));
    REQUIRE(r.nested.learned_metric->factors.size() == 3);
    for (const VecX& f : r.nested.learned_metric->factors) {
        REQUIRE(f.size() == 2);
        CHECK(f(0) == 1.0);
        CHECK(f(1) >= 0.25);
        CHECK(f(1) <= 4.0);
    }
    CHECK(r.nested.chosen.counts[0] + r.nested.chosen.counts[1] + r.nested.chosen.counts[2] +
              r.nested.chosen.counts[3] ==
          3);
    CHECK(r.has_constraint);
    CHECK(r.constraint.grid.rows() == 9);
    CHECK_FALSE(r.has_reduction);
    CHECK(r.has_compression);
    CHECK(e.runtime_set == "walks6");
    for (const auto& row : e.runtime) CHECK((row.samples == 5 || row.samples == 6));

    // Verdicts: the best is the lowest value of its metric, the best kriging the lowest of the kriging
    // methods, and the outcome follows from the two.
    const Verdicts v = judge(e);
    REQUIRE(v.sets.size() == 1);
    const SetVerdicts& sv = v.sets[0];
    CHECK(sv.results == &r);
    REQUIRE(sv.metrics.size() == 8);  // 6 leave-one-out (with foot skating) + 2 constraint
    int losses = 0, ties = 0;
    for (const MetricVerdict& m : sv.metrics) {
        CHECK(m.best.value <= m.best_kriging.value);
        CHECK(m.best_kriging.kriging);
        if (m.best.kriging) CHECK(m.outcome == Outcome::KrigingWins);
        if (m.outcome == Outcome::Loses) {
            ++losses;
            CHECK(m.best_kriging.value - m.best.value > 0.05 * m.best_kriging.value);
            CHECK(m.best_kriging.value - m.best.value > tie_floor(m.metric));
            REQUIRE(m.kriging_worse_percent);
            CHECK(*m.kriging_worse_percent == Approx(100.0 * (m.best_kriging.value - m.best.value) / m.best.value));
            CHECK(*m.kriging_worse_percent > 5.0);
        }
        if (m.outcome == Outcome::Tie) ++ties;
        if (m.metric == Metric::LooPoseMean) {
            double lowest = INFINITY;
            for (const auto& lm : r.loo.methods) lowest = std::min(lowest, lm.pose_mean_cm);
            CHECK(m.best.value == lowest);
            CHECK(m.split.has_value() == !m.best.kriging);
        }
        if (m.metric == Metric::ConstraintReliableRmse) CHECK(m.threshold == plan.constraint.thresholds.back());
    }
    for (const CompressionVerdict& c : sv.compression) {
        CHECK(c.best.ratio >= c.tucker.ratio);
        CHECK(c.tucker.method == "tucker");
        if (!c.tucker_wins) ++losses;
    }
    REQUIRE(v.runtime.has_value());
    CHECK(v.runtime->samples == 6);
    REQUIRE(v.runtime->fastest_build.has_value());
    CHECK(v.runtime->fastest_build->build_seconds <= v.runtime->slowest_kriging_build->build_seconds);
    losses += (v.runtime->build_loses ? 1 : 0) + (v.runtime->synthesis_loses ? 1 : 0);
    CHECK(v.losses == losses);
    CHECK(v.ties == ties);
    CHECK(v.comparisons == static_cast<int>(sv.metrics.size() + sv.compression.size()) + 2);

    // Measurements the report prints.
    const std::vector<std::optional<double>> gains = gain_over_trend(r);
    REQUIRE(gains.size() == r.loo.methods.size());
    for (const std::optional<double>& g : gains) CHECK(g.has_value());  // the plan has a trend-only method
    CHECK(gains.back().value() == Approx(0.0).margin(1e-12));           // the trend-only method against itself
    const auto ranges = parameter_ranges(set);
    REQUIRE(ranges.size() == 2);
    CHECK(ranges[1].first == set.set.parameters.col(1).minCoeff());
    CHECK(ranges[1].first < ranges[1].second);
    const auto durations = duration_range(set);
    CHECK(durations.first > 0.3);
    CHECK(durations.first <= durations.second);
    const std::vector<bool> edge = edge_samples(set);
    int on_edge = 0, inside = 0;
    const VecX& values = r.loo.methods[0].sample_pose_mean_cm;
    const double edge_mean = split_mean(r.loo, values, edge, true, on_edge);
    const double inside_mean = split_mean(r.loo, values, edge, false, inside);
    CHECK(on_edge + inside == 3);
    CHECK((on_edge * edge_mean + inside * inside_mean) / 3.0 == Approx(values.mean()));
    for (const auto& m : r.constraint.methods) {
        int points = 0;
        for (const auto& [centre, error] : error_by_reliability(m, 10)) {
            CHECK(centre > 0.0);
            CHECK(centre < 1.0);
            CHECK(error >= 0.0);
            ++points;
        }
        CHECK(points >= 1);
    }
    CHECK_FALSE(mean_if_any(VecX()).has_value());
    CHECK(reduction_at_tau(r) == ReductionAtTau::NoCurve);  // the plan ran no reduction
}

TEST_CASE("evaluation refuses a missing clip folder", "[eval]") {
    CHECK_THROWS_AS(run_evaluation(make_eval_plan(EvalMode::Tiny), "/nonexistent/cmu-asfamc", {}), InvalidArgument);
}
