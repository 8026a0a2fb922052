// Synthesis models over SynthesisOptions::max_exact_samples use local kriging (docs/synthesis-scale.md):
// built without any N x N system, equal to the exact model when the neighbourhood holds every sample,
// exact at the samples with a small one, on every path of the public API (weights, coefficients, poses
// single and batched, timing, rho), with a categorical parameter; what cannot apply is refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/procedural/parametric_set.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"

using namespace mocapdb;
using namespace mocapdb::synthesis;

namespace {

// 45 procedural reaches (angle x height) with a categorical parameter "side" (left: angle < 0).
struct LocalReaches {
    MotionSet set;
    std::vector<Clip> clips;
    AlignedSet aligned;
    compression::SetModel model;
};

const LocalReaches& local_reaches() {
    static const LocalReaches r = [] {
        procedural::ReachGrid grid;
        grid.angle.count = 9;
        grid.height.count = 5;
        procedural::ParametricSet p = procedural::generate_reach_set(grid);
        LocalReaches out;
        out.set.name = "reach";
        out.set.parameter_names = {"angle", "height"};
        out.set.parameter_units = {"deg", "cm"};
        out.set.parameters = p.parameters.leftCols(2);
        std::vector<std::string> side;
        for (std::size_t i = 0; i < p.clips.size(); ++i) {
            out.set.samples.push_back({p.clips[i].name, 0, p.clips[i].frame_count()});
            side.push_back(p.parameters(static_cast<Eigen::Index>(i), 0) < 0.0 ? "left" : "right");
        }
        add_categorical_parameter(out.set, "side", side);
        out.clips = std::move(p.clips);
        AlignOptions o;
        o.frames = 16;
        out.aligned = align_samples(out.clips, o);
        const VecX weight = compression::position_error_weights(*out.clips.front().skeleton);
        out.model = compression::fit_set_model(out.aligned.tensor, weight, {12, 8, 20}, tensor::TuckerMethod::Hosvd);
        return out;
    }();
    return r;
}

std::unique_ptr<MotionModel> reach_model(const SynthesisOptions& o) {
    const LocalReaches& r = local_reaches();
    return std::make_unique<MotionModel>(r.model, r.aligned, r.set, r.clips.front().skeleton, 120.0, o);
}

// Requests over the parameter box at both sides (angle, height, side level).
MatX requests(int count) {
    std::mt19937 rng(38);
    std::uniform_real_distribution<double> angle(-100.0, 100.0), height(50.0, 170.0);
    MatX c(count, 3);
    for (int q = 0; q < count; ++q) c.row(q) << angle(rng), height(rng), static_cast<double>(q % 2);
    return c;
}

SynthesisOptions local_options(std::size_t k) {
    SynthesisOptions o;
    o.exponent = 1.5;  // the same variogram in both models without the leave-one-out search's cost
    o.max_exact_samples = 10;
    o.local_neighbours = k;
    return o;
}

double max_abs(const MatX& a) { return a.size() == 0 ? 0.0 : a.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("a model over the bound whose neighbourhood holds every sample equals the exact model", "[synthesis]") {
    SynthesisOptions exact_o;
    exact_o.exponent = 1.5;
    const auto exact = reach_model(exact_o);
    const auto local = reach_model(local_options(1000));
    REQUIRE(exact->samples() == 45);
    REQUIRE(exact->local_kernel() == nullptr);
    REQUIRE(local->local_kernel() != nullptr);
    CHECK(local->report().local_neighbours == 45);
    CHECK(exact->report().local_neighbours == 0);
    CHECK_THROWS_AS(local->kernel(), InvalidArgument);
    CHECK(local->report().model.to_string() == exact->report().model.to_string());
    CHECK(local->memory_bytes() < exact->memory_bytes());

    const MatX c = requests(12);
    Workspace wa, wb;
    VecX a(exact->samples()), b(exact->samples());
    VecX ua(exact->coefficient_size()), ub(exact->coefficient_size());
    for (Eigen::Index q = 0; q < c.rows(); ++q) {
        const VecX cq = c.row(q).transpose();
        exact->weights(cq, a, wa);
        local->weights(cq, b, wb);
        CHECK(max_abs(a - b) < 1e-9);
        exact->coefficients(cq, ua, wa);
        local->coefficients(cq, ub, wb);
        CHECK(max_abs(ua - ub) < 1e-9 * std::max(1.0, ua.norm()));
        CHECK(max_abs(exact->pose(cq, 7.5) - local->pose(cq, 7.5)) < 1e-7);
        CHECK(std::abs(exact->reliability(cq) - local->reliability(cq)) < 1e-9);
        CHECK(max_abs(exact->timing(cq).increments - local->timing(cq).increments) < 1e-9);
    }
    CHECK(max_abs(exact->reliability_batch(c) - local->reliability_batch(c)) < 1e-9);
    BatchWorkspace ba, bb;
    MatX pa(exact->dofs(), c.rows()), pb(exact->dofs(), c.rows());
    exact->poses(c, 3.0, pa, ba);
    local->poses(c, 3.0, pb, bb);
    CHECK(max_abs(pa - pb) < 1e-7);
    const VecX c0 = c.row(0).transpose();
    const MatX ma = exact->motion_poses(c0), mb = local->motion_poses(c0);
    REQUIRE(ma.cols() == mb.cols());
    CHECK(max_abs(ma - mb) < 1e-7);

    // The naive model too (its coefficients are the weights).
    const LocalReaches& r = local_reaches();
    const VecX weight = compression::position_error_weights(*r.clips.front().skeleton);
    const NaiveMotionModel naive_exact(r.aligned, r.set, r.clips.front().skeleton, 120.0, weight, exact_o);
    const NaiveMotionModel naive_local(r.aligned, r.set, r.clips.front().skeleton, 120.0, weight, local_options(1000));
    REQUIRE(naive_local.local_kernel() != nullptr);
    CHECK(max_abs(naive_exact.pose(c0, 5.0) - naive_local.pose(c0, 5.0)) < 1e-7);
}

TEST_CASE("a model over the bound with a small neighbourhood interpolates its samples on every path", "[synthesis]") {
    SynthesisOptions o = local_options(8);
    o.kriging.filter_nugget = false;  // exact interpolation at the samples
    const auto local = reach_model(o);
    REQUIRE(local->local_kernel() != nullptr);
    CHECK(local->report().local_neighbours == 8);
    CHECK_FALSE(local->report().system_precomputed);
    const LocalReaches& r = local_reaches();
    const MatX& u = r.model.tucker.U[2];
    Workspace ws;
    VecX coefficients(local->coefficient_size());
    VecX w(local->samples());
    for (const Eigen::Index j : {Eigen::Index{0}, Eigen::Index{22}, Eigen::Index{44}}) {
        const VecX cj = r.set.parameters.row(j).transpose();
        local->coefficients(cj, coefficients, ws);
        CHECK(max_abs(coefficients - u.row(j).transpose()) < 1e-8);
        CHECK(local->reliability(cj) > 1.0 - 1e-9);
        // the sample's own timing
        const VecX inc = r.aligned.inverse_warp_increments().col(j);
        CHECK(max_abs(local->timing(cj).increments - inc) < 1e-8);
    }
    const MatX c = requests(10);
    BatchWorkspace bws;
    MatX batch(local->dofs(), c.rows());
    local->poses(c, 4.25, batch, bws);
    for (Eigen::Index q = 0; q < c.rows(); ++q) {
        const VecX cq = c.row(q).transpose();
        local->weights(cq, w, ws);
        CHECK(std::abs(w.sum() - 1.0) < 1e-10);
        CHECK(max_abs(batch.col(q) - local->pose(cq, 4.25)) < 1e-9);
        const double rho = local->reliability(cq);
        CHECK((rho >= 0.0 && rho <= 1.0));
    }
    // A request's neighbourhood is its own side's samples (the level indicators are 2 apart), and its
    // weights reproduce the per-level trend (the global one: sum_i w_i level_i = the request's level).
    for (const double side : {0.0, 1.0}) {
        const VecX c_side = (VecX(3) << -60.0 + 120.0 * side, 110.0, side).finished();
        VecX cn;
        local->scaling().apply_point(c_side, cn);
        const Eigen::VectorXi nb = local->local_kernel()->neighbourhood(cn);
        for (Eigen::Index j = 0; j < nb.size(); ++j) CHECK(r.set.parameters(nb(j), 2) == side);
        local->weights(c_side, w, ws);
        CHECK(std::abs(w.dot(r.set.parameters.col(2)) - side) < 1e-9);
    }
}

TEST_CASE("what local kriging cannot serve is refused, and compress stores no system above the bound",
          "[synthesis]") {
    SynthesisOptions separate = local_options(8);
    separate.timing_kernel = SynthesisOptions::TimingKernel::Separate;
    CHECK_THROWS_AS(reach_model(separate), InvalidArgument);
    SynthesisOptions rbf = local_options(8);
    rbf.predictor = Predictor::Rbf;
    CHECK_THROWS_AS(reach_model(rbf), InvalidArgument);
    SynthesisOptions zero = local_options(8);
    zero.local_neighbours = 0;
    CHECK_THROWS_AS(reach_model(zero), InvalidArgument);
    SynthesisOptions trend = local_options(8);
    trend.predictor = Predictor::Trend;
    const auto t = reach_model(trend);
    CHECK(t->reliability(VecX((VecX(3) << 10.0, 100.0, 1.0).finished())) >= 0.0);

    const LocalReaches& r = local_reaches();
    const KernelFit above = fit_kernel(r.model, r.aligned, r.set, local_options(8));
    CHECK(above.system == nullptr);
    SynthesisOptions below = local_options(8);
    below.max_exact_samples = 45;
    const KernelFit exact = fit_kernel(r.model, r.aligned, r.set, below);
    CHECK(exact.system != nullptr);
    // A stored fit of the same key is used by the local model (no refit), without its system.
    SynthesisOptions with_fit = local_options(8);
    with_fit.kernel_fit = above;
    const auto m = reach_model(with_fit);
    CHECK(m->report().kernel_precomputed);
    CHECK(m->local_kernel() != nullptr);
}
