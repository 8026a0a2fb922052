// Leave-one-out on a user's set (eval/set_evaluation.hpp, issue #38 item 5): folds leave a sample's twins
// out with it (the training indices, and the error a duplicated clip would otherwise hide), and the
// evaluation's figures hang together (the chosen column is made of the methods' own fold errors).
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/set_evaluation.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::eval;

TEST_CASE("set evaluation: a fold's training set leaves the sample's twins out", "[eval][twins]") {
    const std::vector<std::vector<Eigen::Index>> twins = {{3}, {}, {4}, {0}, {2}, {}};
    CHECK(loo_training(6, 0, twins) == std::vector<Eigen::Index>{1, 2, 4, 5});
    CHECK(loo_training(6, 1, twins) == std::vector<Eigen::Index>{0, 2, 3, 4, 5});
    CHECK(loo_training(6, 4, twins) == std::vector<Eigen::Index>{0, 1, 3, 5});
    CHECK(loo_training(6, 4, {}) == std::vector<Eigen::Index>{0, 1, 2, 3, 5});
    CHECK_THROWS_AS(loo_training(6, 6, twins), InvalidArgument);
    CHECK_THROWS_AS(loo_training(5, 0, twins), InvalidArgument);
    // The subset {0, 2, 3, 5}: 0 and 3 stay twins (now 0 and 2); 2's twin 4 is gone.
    const auto sub = subset_twins(twins, {0, 2, 3, 5});
    CHECK(sub == std::vector<std::vector<Eigen::Index>>{{2}, {}, {0}, {}});
    CHECK(evenly_spread(10, 4) == std::vector<Eigen::Index>{1, 3, 6, 8});
    CHECK(evenly_spread(3, 40) == std::vector<Eigen::Index>{0, 1, 2});
}

TEST_CASE("set evaluation: a clip imported twice is found and left out with its twin", "[eval][twins][shared]") {
    const auto cmu = test::datasets_dir() / "cmu-asfamc";
    MOCAPDB_REQUIRE_SHARED(cmu);
    test::TempDir dir("set-eval");
    std::filesystem::copy_file(cmu / "16.asf", dir / "16.asf");
    EvalSetSpec spec;
    spec.name = "walks";
    for (int t = 11; t <= 17; ++t) {
        const std::string id = "16_" + std::to_string(t);
        std::filesystem::copy_file(cmu / (id + ".amc"), dir / (id + ".amc"));
        spec.clips.push_back(id);
    }
    std::filesystem::copy_file(cmu / "16_15.amc", dir / "16_95.amc");  // the same clip under another name
    spec.clips.push_back("16_95");
    spec.extractors = {"speed", "turn"};
    spec.frames = 30;
    const EvalSet set = build_eval_set(spec, dir.path());
    REQUIRE(set.size() == 8);
    const Eigen::Index original = 4, copy = 7;  // 16_15 and 16_95
    REQUIRE(set.labels[static_cast<std::size_t>(original)] == "16_15");

    const SampleTwins twins = find_sample_twins(set.set, [&](std::size_t i) { return set.samples[i]; });
    REQUIRE(twins.groups == std::vector<std::vector<std::size_t>>{{4, 7}});

    // Without the twin rule the copy answers for the original; with it, the fold is a real prediction.
    const std::vector<MethodSpec> kriging = {set_methods({0, 0, 0})[0]};
    LooOptions plain;
    plain.foot_skating = false;
    plain.samples = {original};
    LooOptions apart = plain;
    apart.twins.assign(8, {});
    apart.twins[static_cast<std::size_t>(original)] = {copy};
    apart.twins[static_cast<std::size_t>(copy)] = {original};
    const double leaked = leave_one_out(set, kriging, plain).methods[0].pose_mean_cm;
    const double honest = leave_one_out(set, kriging, apart).methods[0].pose_mean_cm;
    INFO("pose error with the copy in training " << leaked << " cm, without " << honest << " cm");
    CHECK(honest > 0.5);
    CHECK(leaked < 0.5 * honest);

    SetEvaluationOptions options;
    options.max_folds = 5;
    options.inner_folds = 4;
    std::uint64_t last_done = 0, last_total = 0;
    const SetEvaluation e = evaluate_set(set, set_methods({0, 0, 0}), options, [&](const Progress& p) {
        last_done = p.done;
        last_total = p.total;
    });
    CHECK(last_done == 10);
    CHECK(last_total == 10);
    CHECK(e.folds == std::vector<Eigen::Index>{0, 2, 4, 5, 7});
    CHECK(e.twins.groups == twins.groups);
    REQUIRE(e.methods.size() == 3);
    CHECK(e.parameters_measured);
    REQUIRE(e.hit_tolerance.size() == 2);
    for (const std::optional<double>& t : e.hit_tolerance) CHECK(t.value() > 0.0);  // both parameters vary
    for (const MethodEvaluation& m : e.methods) {
        INFO(m.spec.name);
        CHECK(m.loo.sample_pose_mean_cm.size() == 5);
        CHECK(m.loo.pose_mean_cm > 0.0);
        CHECK(m.loo.pose_mean_cm < 30.0);
        REQUIRE(m.hit_rate);
        CHECK(*m.hit_rate >= 0.0);
        CHECK(*m.hit_rate <= 1.0);
        CHECK(*m.hit_rate == Approx(m.hits.mean()));
        REQUIRE(m.loo.measured.size() == 5);
        for (const auto& fold : m.loo.measured) {
            REQUIRE(fold.size() == 2);
            for (const std::optional<double>& v : fold) CHECK((v && std::isfinite(*v)));  // walks: speed, turn
        }
    }
    // Kriging has a reliability (here 0 at every left-out walk of this small set: Pearson is then
    // undefined, empty); RBF and the trend have none.
    const VecX& rho = e.methods[0].loo.reliability;
    REQUIRE(rho.size() == 5);
    CHECK(rho.minCoeff() >= 0.0);
    CHECK(rho.maxCoeff() <= 1.0);
    const std::optional<double> r = e.methods[0].rho_pose_pearson;
    CHECK((r ? std::abs(*r) <= 1.0 : rho.maxCoeff() == rho.minCoeff()));
    CHECK(e.methods[1].loo.reliability.size() == 0);
    CHECK_FALSE(e.methods[1].rho_pose_pearson.has_value());
    CHECK_FALSE(e.methods[2].rho_pose_pearson.has_value());
    // The chosen column is, fold by fold, the picked method's own outer error.
    const ChosenEvaluation& c = e.chosen;
    REQUIRE(c.picks.size() == 5);
    std::size_t counted = 0;
    for (std::size_t n : c.counts) counted += n;
    CHECK(counted == 5);
    REQUIRE(c.pick_names.size() == 5);
    for (Eigen::Index k = 0; k < 5; ++k) {
        const std::size_t q = c.picks[static_cast<std::size_t>(k)];
        if (q < e.methods.size()) {
            CHECK(c.pose_mean_cm(k) == e.methods[q].loo.sample_pose_mean_cm(k));
            CHECK(c.pick_names[static_cast<std::size_t>(k)] == e.methods[q].spec.name);
        } else {  // an average of two or three: its own fold, within its members' range
            CHECK_THAT(c.pick_names[static_cast<std::size_t>(k)], Catch::StartsWith("average of "));
            CHECK(std::isfinite(c.pose_mean_cm(k)));
        }
    }
    for (const MethodEvaluation& m : e.methods) CHECK(m.loo.pose_mean_cm >= e.methods[c.best].loo.pose_mean_cm);
    REQUIRE(c.diff_se_cm);
    CHECK(std::isfinite(*c.diff_se_cm));
    REQUIRE(c.hit_rate);
    CHECK(*c.hit_rate >= 0.0);
    CHECK(*c.hit_rate <= 1.0);
    CHECK(e.not_evaluated.size() == 1);  // MOHGP (evaluate_set: no stored model to speak of)

    // One fold: a correlation over folds and the paired standard error do not exist; hit rates do.
    SetEvaluationOptions one;
    one.max_folds = 1;
    one.inner_folds = 3;
    const SetEvaluation single = evaluate_set(set, set_methods({0, 0, 0}), one);
    REQUIRE(single.folds.size() == 1);
    CHECK(single.methods[0].loo.reliability.size() == 1);  // kriging still has its rho
    for (const MethodEvaluation& m : single.methods) {
        INFO(m.spec.name);
        CHECK_FALSE(m.rho_pose_pearson.has_value());
        REQUIRE(m.hit_rate);
        CHECK((*m.hit_rate == 0.0 || *m.hit_rate == 1.0));
    }
    CHECK_FALSE(single.chosen.diff_se_cm.has_value());
    CHECK(single.chosen.hit_rate.has_value());

    SetEvaluationOptions bad;
    bad.max_folds = 0;
    CHECK_THROWS_AS(evaluate_set(set, set_methods({0, 0, 0}), bad), InvalidArgument);
}
