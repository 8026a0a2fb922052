// The verdicts' derived figures on hand-made results: a figure that does not exist for its input (a
// percentage of a zero best value, a gain without a trend-only method, the mean of no values) is an
// empty optional, and the others are the values computed by hand.
#include <catch2/catch.hpp>

#include "mocapdb/eval/verdicts.hpp"

using namespace mocapdb;
using namespace mocapdb::eval;

namespace {

// A leave-one-out result of one method over two left-out samples.
LooMethodResult verdict_loo_method(const std::string& name, double pose_mean, const VecX& duration_error) {
    LooMethodResult m;
    m.method = name;
    m.pose_mean_cm = pose_mean;
    m.pose_max_cm = 2.0 * pose_mean;
    m.mean_cm = pose_mean;
    m.max_cm = 2.0 * pose_mean;
    m.duration_error_s = duration_error;
    return m;
}

MethodSpec verdict_method(MethodKind kind, const std::string& name) {
    MethodSpec m;
    m.kind = kind;
    m.name = name;
    return m;
}

}  // namespace

TEST_CASE("verdicts: figures without a value are empty", "[eval][verdicts]") {
    SetResults r;
    r.has_loo = true;
    r.methods = {verdict_method(MethodKind::NaiveKriging, "kriging"), verdict_method(MethodKind::Rbf, "rbf")};
    r.loo.samples = {0, 1};
    // Kriging is best everywhere (no split by sample position needed); every duration error is 0, and
    // RBF has no duration errors at all.
    r.loo.methods = {verdict_loo_method("kriging", 1.0, VecX::Zero(2)), verdict_loo_method("rbf", 2.0, VecX())};
    EvalResults e;
    e.sets.push_back(r);
    const Verdicts v = judge(e);
    REQUIRE(v.sets.size() == 1);
    const std::vector<MetricVerdict>& metrics = v.sets[0].metrics;
    REQUIRE(metrics.size() == 5);  // pose mean and max, motion mean and max, duration (no skating measured)
    for (const MetricVerdict& m : metrics) {
        INFO(static_cast<int>(m.metric));
        CHECK(m.best.method == "kriging");
        CHECK(m.outcome == Outcome::KrigingWins);
        if (m.metric == Metric::LooDuration) {
            CHECK(m.best.value == 0.0);
            CHECK_FALSE(m.kriging_worse_percent.has_value());  // a percentage of 0
        } else {
            CHECK(m.kriging_worse_percent.value() == 0.0);
        }
    }

    // Without a trend-only method there is no gain over it; with one, 1 - pose mean / its pose mean.
    for (const std::optional<double>& g : gain_over_trend(r)) CHECK_FALSE(g.has_value());
    r.methods.push_back(verdict_method(MethodKind::TrendOnly, "trend"));
    r.loo.methods.push_back(verdict_loo_method("trend", 4.0, VecX::Zero(2)));
    const std::vector<std::optional<double>> gains = gain_over_trend(r);
    REQUIRE(gains.size() == 3);
    CHECK(gains[0].value() == 0.75);
    CHECK(gains[1].value() == 0.5);
    CHECK(gains[2].value() == 0.0);

    CHECK_FALSE(mean_if_any(VecX()).has_value());
    CHECK(mean_if_any(VecX::Constant(3, 2.5)).value() == 2.5);
}
