// The kernel headroom (eval/kernel_headroom.hpp): the same folds, blend and error as the leave-one-out
// of loo_prediction.hpp, so that its bound is comparable with the methods' errors.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/kernel_headroom.hpp"
#include "mocapdb/eval/loo_prediction.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using namespace mocapdb::eval;

TEST_CASE("kernel headroom: a nugget-only kernel is the trend, and the best is the lowest of the grid", "[eval][headroom][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    EvalSetSpec spec;
    spec.name = "walks";
    spec.clips = {"16_11", "16_13", "16_15", "16_17", "16_19", "16_21", "16_23", "16_25"};
    spec.extractors = {"turn", "speed"};
    spec.frames = 10;
    const EvalSet set = build_eval_set(spec, test::datasets_dir() / "cmu-asfamc");
    REQUIRE(set.size() == 8);

    // Filtered kriging with (almost) all of the sill in the nugget blends by the trend's weights: the
    // headroom's folds, scaling, blend and error then reproduce the trend-only method of the LOO.
    MethodSpec trend;
    trend.kind = MethodKind::TrendOnly;
    trend.name = "trend";
    LooOptions lo;
    lo.foot_skating = false;
    const LooResult loo = leave_one_out(set, {trend}, lo);
    KernelHeadroomOptions nugget;
    nugget.exponents = {1.0};
    nugget.ranges = {1.0};
    nugget.nugget_shares = {1.0 - 1e-9};
    nugget.anisotropy = {1.0};
    const KernelHeadroom h = kernel_headroom(set, nugget);
    CHECK(h.kernels == 1);
    CHECK(h.best_pose_mean_cm == Approx(loo.methods[0].pose_mean_cm).epsilon(1e-6));
    CHECK(h.median_pose_mean_cm == h.best_pose_mean_cm);

    // A grid holding that kernel: the best is no worse, and some correlated kernel does better on walks.
    KernelHeadroomOptions grid;
    grid.nugget_shares = {0.0, 0.3, 1.0 - 1e-9};
    grid.anisotropy = {1.0, 2.0};
    const KernelHeadroom g = kernel_headroom(set, grid);
    CHECK(g.kernels == 2 * (4 * 6 * 3 - 6));  // p = 2 without a nugget skipped
    CHECK(g.best_pose_mean_cm < h.best_pose_mean_cm);
    CHECK(g.best_pose_mean_cm <= g.median_pose_mean_cm);
    CHECK(g.best.nugget < 1.0 - 1e-6);

    // The folds can be a subset, and bad grids are refused.
    KernelHeadroomOptions some = nugget;
    some.samples = {0, 3};
    CHECK(kernel_headroom(set, some).best_pose_mean_cm > 0.0);
    some.samples = {8};
    CHECK_THROWS_AS(kernel_headroom(set, some), InvalidArgument);
    KernelHeadroomOptions bad = nugget;
    bad.nugget_shares = {1.0};
    CHECK_THROWS_AS(kernel_headroom(set, bad), InvalidArgument);
    bad = nugget;
    bad.ranges = {};
    CHECK_THROWS_AS(kernel_headroom(set, bad), InvalidArgument);
    bad = nugget;
    bad.exponents = {2.5};
    CHECK_THROWS_AS(kernel_headroom(set, bad), InvalidArgument);
}
