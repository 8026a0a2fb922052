// Synthesis at control parameters (issue #6, acceptance 1) on subject 16's walks: interpolation at the
// samples, full ranks = the aligned samples, naive = compressed at full ranks, smoothness in c,
// reliability, BVH export, batched and concurrent queries.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <memory>
#include <thread>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::synthesis;

namespace {

// Subject 16's walks (straight and turning), dtw-aligned to a few frames, with measured turn and speed.
struct Walks {
    std::vector<Clip> clips;
    MotionSet set;
    AlignedSet aligned;
    std::shared_ptr<const Skeleton> skeleton;
    VecX weight;
};

const Walks& walks() {
    static const Walks w = [] {
        Walks r;
#ifdef MOCAPDB_SANITIZED_BUILD
        const std::vector<int> trials{11, 13, 15, 17, 19, 21, 23, 47};
        const Eigen::Index frames = 16;
#else
        const std::vector<int> trials{11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 47};
        const Eigen::Index frames = 24;
#endif
        test::Subject16Set loaded = test::subject16_set(trials, frames);
        r.clips = std::move(loaded.clips);
        r.set = std::move(loaded.set);
        r.aligned = std::move(loaded.aligned);
        r.skeleton = r.clips.front().skeleton;
        r.weight = compression::position_error_weights(*r.skeleton);
        return r;
    }();
    return w;
}

tensor::Ranks full_ranks(const AlignedSet& a) { return {a.dofs(), a.frames(), a.samples()}; }

// Exact interpolation (the nugget a jump at the samples, not noise): the algebra these tests pin.
// The default filters the nugget (test_continuity.cpp).
SynthesisOptions exact_options() {
    SynthesisOptions o;
    o.kriging.filter_nugget = false;
    return o;
}

double relative(const VecX& a, const VecX& b) { return (a - b).norm() / std::max(b.norm(), 1e-300); }

VecX pose_of(const Tensor3& t, Eigen::Index frame, Eigen::Index sample) {
    VecX q(t.dimension(0));
    for (Eigen::Index k = 0; k < q.size(); ++k) q(k) = t(k, frame, sample);
    return q;
}

// Midpoints of each sample and its nearest neighbour (normalized parameters): between the samples.
MatX nearest_midpoints(const MatX& p) {
    const MatX xn = kriging::ControlScaling::from_data(p).apply(p);
    MatX q(p.rows(), p.cols());
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
        Eigen::Index nearest = i == 0 ? 1 : 0;
        for (Eigen::Index j = 0; j < p.rows(); ++j)
            if (j != i && (xn.row(i) - xn.row(j)).norm() < (xn.row(i) - xn.row(nearest)).norm()) nearest = j;
        q.row(i) = 0.5 * (p.row(i) + p.row(nearest));
    }
    return q;
}

// Midpoints of consecutive samples in parameter space: between the samples, not on them.
MatX between_samples(const MatX& p) {
    MatX q(p.rows() - 1, p.cols());
    for (Eigen::Index i = 0; i + 1 < p.rows(); ++i) q.row(i) = 0.5 * (p.row(i) + p.row(i + 1));
    return q;
}

}  // namespace

TEST_CASE("synthesis at a sample's parameters reproduces the model's reconstruction", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const Eigen::Index n = w.aligned.samples(), t_count = w.aligned.frames();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, {20, 8, n - 2}, tensor::TuckerMethod::Hosvd);
    SynthesisOptions options = exact_options();
    options.levels = {{10, 4, 5}};
    const MotionModel model(sm, w.aligned, w.set, w.skeleton, 120.0, options);
    REQUIRE(model.coefficient_size() == n - 2);
    REQUIRE(model.levels() == 2);
    const Tensor3 recon = sm.reconstruct();
    const Tensor3 recon_lod = sm.reconstruct({10, 4, 5});
    Workspace ws;
    VecX q(model.dofs());
    double worst = 0.0, worst_lod = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
        const VecX c = w.set.parameters.row(i).transpose();
        for (Eigen::Index t = 0; t < t_count; ++t) {
            model.pose(c, static_cast<double>(t), q, ws);
            worst = std::max(worst, relative(q, pose_of(recon, t, i)));
            model.pose(c, static_cast<double>(t), q, ws, 1);
            worst_lod = std::max(worst_lod, relative(q, pose_of(recon_lod, t, i)));
        }
        CHECK(model.reliability(c) == Approx(1.0).margin(1e-9));

        // The sample's own timing: the synthesized clip has the sample's frame count, its warp is the
        // sample's, and its poses are the reconstruction shown at the sample's frames.
        const Timing timing = model.timing(c);
        CHECK(timing.clamped == 0);
        CHECK((timing.warp - w.aligned.warps.col(i)).cwiseAbs().maxCoeff() < 1e-8);
        CHECK(timing.frame_count() == static_cast<Eigen::Index>(w.clips[static_cast<std::size_t>(i)].frame_count()));
    }
    INFO("worst relative difference " << worst << ", at a level of detail " << worst_lod);
    CHECK(worst <= 1e-8);
    CHECK(worst_lod <= 1e-8);
}

TEST_CASE("at full ranks the synthesis reproduces the aligned samples and agrees with the naive model",
          "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const Eigen::Index n = w.aligned.samples(), t_count = w.aligned.frames();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, full_ranks(w.aligned), tensor::TuckerMethod::Hosvd);
    const MotionModel model(sm, w.aligned, w.set, w.skeleton, 120.0, exact_options());
    const NaiveMotionModel naive(w.aligned, w.set, w.skeleton, 120.0, w.weight, exact_options());
    CHECK(std::string(naive.kind()) == "naive");
    CHECK(model.report().model.paper_p() == naive.report().model.paper_p());

    Workspace ws;
    VecX q(model.dofs()), qn(model.dofs());
    double worst = 0.0, worst_naive = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
        const VecX c = w.set.parameters.row(i).transpose();
        for (Eigen::Index t = 0; t < t_count; ++t) {
            const VecX a = pose_of(w.aligned.tensor, t, i);
            model.pose(c, static_cast<double>(t), q, ws);
            naive.pose(c, static_cast<double>(t), qn, ws);
            worst = std::max(worst, relative(q, a));
            worst_naive = std::max(worst_naive, relative(qn, a));
        }
    }
    INFO("compressed " << worst << ", naive " << worst_naive);
    CHECK(worst <= 1e-8);
    CHECK(worst_naive <= 1e-10);

    // Between the samples (fractional frames too) both give the same motion.
    const MatX mid = between_samples(w.set.parameters);
    double worst_between = 0.0;
    for (Eigen::Index k = 0; k < mid.rows(); ++k) {
        const VecX c = mid.row(k).transpose();
        for (double t : {0.0, 3.5, static_cast<double>(t_count - 1) * 0.5, static_cast<double>(t_count - 1)}) {
            model.pose(c, t, q, ws);
            naive.pose(c, t, qn, ws);
            worst_between = std::max(worst_between, relative(q, qn));
        }
        CHECK(model.reliability(c) == Approx(naive.reliability(c)).margin(1e-6));
        CHECK(model.timing(c).warp.isApprox(naive.timing(c).warp, 1e-8));
    }
    INFO("compressed vs naive between the samples: " << worst_between);
    CHECK(worst_between <= 1e-6);
}

TEST_CASE("synthesized poses vary smoothly with the control parameters", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const Eigen::Index n = w.aligned.samples();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, {24, 10, n - 1}, tensor::TuckerMethod::Hosvd);
    const MotionModel model(sm, w.aligned, w.set, w.skeleton, 120.0);
    const MatX mid = between_samples(w.set.parameters);
    const double t = 0.4 * static_cast<double>(w.aligned.frames() - 1);
    Workspace ws;
    VecX qp(model.dofs()), qm(model.dofs());
    // Continuous and differentiable in c, by central differences D(s) = (q(c + s e) - q(c - s e)) / 2s with
    // steps h, h/2, h/4 (h = 1e-3 standard deviations of the axis):
    //  - the quotients converge: |D(h/2) - D(h/4)| <= 0.75 |D(h) - D(h/2)|. The ratio is 1/4 where the pose
    //    is C2 and at most 1/2 where the steps straddle a point where its second derivative jumps; a jump
    //    J in the pose makes D grow like J / 2s (ratio 2), a kink or an infinite slope gives a ratio >= 1;
    //  - to one derivative: |D(h) - D(h/2)| <= 1 % of |D(h)| (a jump J gives about J / 2h, all of |D|).
    // Not C2: the kernel's variogram may be spherical (p = 0, in the paper's grid), whose gamma'' jumps from
    // -3 sill / range^2 to 0 at distance = range, so the pose is only C1 on the sphere of that radius around
    // each sample, and quotients straddling it differ by (h / 8) |jump of q''|, O(h) instead of O(h^2).
    // (With the sanitizer build's 8 walks the leave-one-out grid picks a spherical kernel whose range, half
    // the largest lag, is half the distance of samples 0 and 1: query 0, their midpoint, sits on the kink,
    // and D(h), D(h/2) differ by 0.2 % of |D|, D(h/2), D(h/4) by half that.)
    const auto quotient = [&](const VecX& c0, Eigen::Index axis, double step) {
        VecX c = c0;
        c(axis) += step;
        model.pose(c, t, qp, ws);
        c(axis) -= 2.0 * step;
        model.pose(c, t, qm, ws);
        return VecX((qp - qm) / (2.0 * step));
    };
    for (Eigen::Index k = 0; k < mid.rows(); ++k) {
        for (Eigen::Index axis = 0; axis < model.parameters(); ++axis) {
            const VecX c = mid.row(k).transpose();
            const double h = 1e-3 * model.scaling().scale(axis);
            const VecX d_h = quotient(c, axis, h), d_h2 = quotient(c, axis, 0.5 * h), d_h4 = quotient(c, axis, 0.25 * h);
            const double slope = d_h.norm(), coarse = (d_h - d_h2).norm(), fine = (d_h2 - d_h4).norm();
            INFO("query " << k << " axis " << axis << ": |dq/dc| " << slope << ", |D(h) - D(h/2)| " << coarse
                          << ", |D(h/2) - D(h/4)| " << fine << ", model " << model.report().model.to_string());
            CHECK(d_h.allFinite());
            CHECK(d_h4.allFinite());
            // Floors: rounding (and a cancellation of the O(h) and O(h^2) terms) when both are tiny.
            CHECK(fine <= 0.75 * coarse + 1e-4 * slope + 1e-9);
            CHECK(coarse <= 1e-2 * slope + 1e-9);
        }
    }
}

TEST_CASE("reliability is 1 at the samples and falls off away from them", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const NaiveMotionModel model(w.aligned, w.set, w.skeleton, 120.0, w.weight, exact_options());
    const VecX at_samples = model.reliability_batch(w.set.parameters);
    CHECK((at_samples.array() - 1.0).abs().maxCoeff() < 1e-9);
    const MatX mid = between_samples(w.set.parameters);
    const VecX between = model.reliability_batch(mid);
    CHECK((between.array() >= 0.0).all());
    CHECK((between.array() <= 1.0).all());
    CHECK(between.minCoeff() < 1.0 - 1e-6);
    // Far outside the samples (many variogram ranges, in normalized units) the reliability tends to 0.
    const kriging::VariogramModel& vm = model.report().model;
    INFO("variogram " << vm.to_string());
    // gamma reaches 99.9 % of the sill at range * ln(1000)^(1/p) (stable) or the range (spherical).
    const double reach = vm.paper_p() == 0.0 ? vm.range : vm.range * std::pow(std::log(1000.0), 1.0 / vm.paper_p());
    VecX far = w.set.parameters.colwise().mean().transpose();
    far(0) += 2.0 * (reach + 10.0) * model.scaling().scale(0);
    CHECK(model.reliability(far) < 0.05);
    for (Eigen::Index k = 0; k < mid.rows(); ++k) CHECK(model.reliability(mid.row(k).transpose()) == Approx(between(k)));
}

TEST_CASE("synthesized motion exports to BVH and reloads", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, {30, 12, w.aligned.samples() - 1}, tensor::TuckerMethod::Hosvd);
    const MotionModel model(sm, w.aligned, w.set, w.skeleton, 120.0);
    const VecX c = between_samples(w.set.parameters).row(2).transpose();
    const Clip clip = model.motion(c);
    const Timing timing = model.timing(c);
    REQUIRE(clip.frame_count() == static_cast<std::size_t>(timing.frame_count()));
    CHECK((timing.increments.array() > 0.0).all());
    // The duration lies within the samples' durations (kriging blends the timing).
    double shortest = 1e300, longest = 0.0;
    for (const Clip& s : w.clips) {
        shortest = std::min(shortest, static_cast<double>(s.frame_count()));
        longest = std::max(longest, static_cast<double>(s.frame_count()));
    }
    CHECK(static_cast<double>(clip.frame_count()) >= 0.8 * shortest);
    CHECK(static_cast<double>(clip.frame_count()) <= 1.2 * longest);

    test::TempDir dir("synth-bvh");
    const auto path = dir / "synth.bvh";
    write_bvh(path, clip);
    const Clip back = read_bvh(path);
    REQUIRE(back.frame_count() == clip.frame_count());
    CHECK(back.frame_rate == Approx(120.0));
    // The reloaded motion: same measured turn and speed as the synthesized clip.
    const std::vector<ParameterExtractor> ex{ParameterExtractor::parse("turn"), ParameterExtractor::parse("speed")};
    const VecX p_clip = extract_parameters(clip, 0, clip.frame_count(), ex);
    const VecX p_back = extract_parameters(back, 0, back.frame_count(), ex);
    CHECK(p_back(0) == Approx(p_clip(0)).margin(1e-5));
    CHECK(p_back(1) == Approx(p_clip(1)).epsilon(1e-5));
}

TEST_CASE("batched poses equal single poses, concurrent queries are bit-identical", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const Eigen::Index n = w.aligned.samples();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, {20, 8, n - 2}, tensor::TuckerMethod::Hosvd);
    SynthesisOptions options;
    options.levels = {{12, 5, 6}};
    const MotionModel model(sm, w.aligned, w.set, w.skeleton, 120.0, options);
    const NaiveMotionModel naive(w.aligned, w.set, w.skeleton, 120.0, w.weight);
    const MatX C = between_samples(w.set.parameters);
    for (const SynthesisModel* m : {static_cast<const SynthesisModel*>(&model), static_cast<const SynthesisModel*>(&naive)}) {
        for (Eigen::Index level = 0; level < m->levels(); ++level) {
            BatchWorkspace bws;
            MatX out(m->dofs(), C.rows());
            const double t = 5.25;
            m->poses(C, t, out, bws, level);
            Workspace ws;
            VecX q(m->dofs());
            for (Eigen::Index k = 0; k < C.rows(); ++k) {
                m->pose(C.row(k).transpose(), t, q, ws, level);
                INFO(m->kind() << " level " << level << " character " << k);
                CHECK(relative(out.col(k), q) < 1e-12);
            }
        }
    }

    // Reference results on this thread, then the same queries from 4 threads at once.
    const auto run = [&](MatX& poses, MatX& motion) {
        Workspace ws;
        poses.resize(model.dofs(), C.rows() * 3);
        for (Eigen::Index k = 0; k < C.rows(); ++k)
            for (int s = 0; s < 3; ++s)
                model.pose(C.row(k).transpose(), 1.5 * s + 0.25, poses.col(3 * k + s), ws, s % 2);
        motion = naive.motion_poses(C.row(1).transpose());
    };
    MatX ref_poses, ref_motion;
    run(ref_poses, ref_motion);
    std::vector<MatX> poses(4), motions(4);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < 4; ++i) threads.emplace_back([&, i] { run(poses[i], motions[i]); });
    for (auto& th : threads) th.join();
    for (std::size_t i = 0; i < 4; ++i) {
        REQUIRE(poses[i].size() == ref_poses.size());
        REQUIRE(motions[i].size() == ref_motion.size());
        CHECK(std::memcmp(poses[i].data(), ref_poses.data(), sizeof(double) * static_cast<std::size_t>(ref_poses.size())) == 0);
        CHECK(std::memcmp(motions[i].data(), ref_motion.data(), sizeof(double) * static_cast<std::size_t>(ref_motion.size())) == 0);
    }
}

TEST_CASE("synthesis models reject bad queries and inputs", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const Eigen::Index n = w.aligned.samples();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, {10, 4, n - 2}, tensor::TuckerMethod::Hosvd);
    const MotionModel model(sm, w.aligned, w.set, w.skeleton, 120.0);
    Workspace ws;
    VecX q(model.dofs());
    const VecX c = w.set.parameters.row(0).transpose();
    CHECK_THROWS_AS(model.pose(VecX::Zero(3), 0.0, q, ws), InvalidArgument);
    CHECK_THROWS_AS(model.pose(c, -0.5, q, ws), InvalidArgument);
    CHECK_THROWS_AS(model.pose(c, static_cast<double>(model.frames()), q, ws), InvalidArgument);
    CHECK_THROWS_AS(model.pose(c, 0.0, q, ws, 1), InvalidArgument);
    VecX bad = c;
    bad(0) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(model.reliability(bad), InvalidArgument);
    SynthesisOptions options;
    options.levels = {{11, 4, 1}};
    CHECK_THROWS_AS(MotionModel(sm, w.aligned, w.set, w.skeleton, 120.0, options), InvalidArgument);
    MotionSet wrong = w.set;
    wrong.parameters.conservativeResize(n - 1, Eigen::NoChange);
    wrong.samples.pop_back();
    CHECK_THROWS_AS(MotionModel(sm, w.aligned, wrong, w.skeleton, 120.0), InvalidArgument);
    CHECK_THROWS_AS(NaiveMotionModel(w.aligned, w.set, w.skeleton, 0.0, w.weight), InvalidArgument);
}

TEST_CASE("timing kernels: the separate kernel interpolates too, the shared one keeps the speed", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    SynthesisOptions separate = exact_options();
    separate.timing_kernel = SynthesisOptions::TimingKernel::Separate;
    const NaiveMotionModel a(w.aligned, w.set, w.skeleton, 120.0, w.weight, separate);
    const NaiveMotionModel b(w.aligned, w.set, w.skeleton, 120.0, w.weight);
    for (Eigen::Index i = 0; i < w.aligned.samples(); ++i) {
        const VecX c = w.set.parameters.row(i).transpose();
        CHECK((a.timing(c).warp - w.aligned.warps.col(i)).cwiseAbs().maxCoeff() < 1e-8);
    }
    // Measured speed of motions synthesized between the samples, both kernels (the shared one is the
    // default because pose and timing then come from one blend).
    const std::vector<ParameterExtractor> ex{ParameterExtractor::parse("turn"), ParameterExtractor::parse("speed")};
    const MatX mid = nearest_midpoints(w.set.parameters);
    double err[2] = {0.0, 0.0}, worst[2] = {0.0, 0.0}, turn_worst = 0.0;
    for (Eigen::Index k = 0; k < mid.rows(); ++k) {
        const VecX c = mid.row(k).transpose();
        int m = 0;
        for (const SynthesisModel* model : {static_cast<const SynthesisModel*>(&a), static_cast<const SynthesisModel*>(&b)}) {
            const Clip clip = model->motion(c);
            const VecX v = extract_parameters(clip, 0, clip.frame_count(), ex);
            const double e = std::abs(v(1) - c(1)) / c(1);
            err[m] += e / static_cast<double>(mid.rows());
            worst[m] = std::max(worst[m], e);
            if (m == 1) turn_worst = std::max(turn_worst, std::abs(v(0) - c(0)));
            ++m;
        }
    }
    WARN("relative speed error between samples: separate timing kernel mean " << err[0] << " max " << worst[0]
         << "; shared mean " << err[1] << " max " << worst[1] << "; shared turn error max " << turn_worst << " rad");
#ifdef MOCAPDB_SANITIZED_BUILD
    CHECK(worst[1] <= 0.2);  // 8 walks at 16 aligned frames: a coarse timeline
#else
    // Measured 2026-12-02: shared mean 2.0 %, max 10.3 % (separate 2.4 %, 9.1 %) with the residual variogram
    // of issue #15; before it (raw-value variogram, exponents down to 0.2) mean 2.4 %, max 5.9 %.
    CHECK(err[1] <= 0.03);
    CHECK(worst[1] <= 0.12);
#endif
    CHECK(turn_worst <= 0.05);
}

TEST_CASE("folded coefficients equal the blend of the kriging weights", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const Eigen::Index n = w.aligned.samples();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, {20, 8, n - 2}, tensor::TuckerMethod::Hosvd);
    for (const double p : {0.0, 1.0, 1.4, 2.0}) {
        SynthesisOptions options = exact_options();
        options.exponent = p;
        const MotionModel model(sm, w.aligned, w.set, w.skeleton, 120.0, options);
        const MatX& u_sample = model.set_model().tucker.U[2];  // N by R3
        MatX C(2 * n - 1 + 3, model.parameters());
        C << between_samples(w.set.parameters), w.set.parameters,
            w.set.parameters.colwise().mean() + 3.0 * (w.set.parameters.colwise().maxCoeff() -
                                                       w.set.parameters.colwise().minCoeff()),
            w.set.parameters.colwise().minCoeff(), w.set.parameters.colwise().maxCoeff();
        // The fold changes the order of the products: its rounding differs from the weights path's by
        // ~1e-16 times the size of the kriging operator, i.e. grows with 1 / rcond of the covariance
        // matrix: 1e-12 for rcond >= 1e-8, proportionally more below (the Gaussian p = 2 kernel is the
        // ill-conditioned one here: rcond 7e-10 with the clang build's fit, difference 5e-12).
        const double tolerance = std::max(1e-12, 1e-20 / model.kernel().status().rcond);
        Workspace ws;
        VecX wts(n), folded(model.coefficient_size());
        BatchWorkspace bws;
        MatX out(model.dofs(), C.rows());
        model.poses(C, 2.5, out, bws);  // the folded batch path: bws.coefficients
        for (Eigen::Index k = 0; k < C.rows(); ++k) {
            model.weights(C.row(k).transpose(), wts, ws);
            const VecX unfolded = u_sample.transpose() * wts;
            model.coefficients(C.row(k).transpose(), folded, ws);
            INFO("p " << p << " query " << k << " rcond " << model.kernel().status().rcond << " relative difference "
                      << relative(folded, unfolded) << " (batch " << relative(bws.coefficients.col(k), unfolded) << ")");
            CHECK(relative(folded, unfolded) < tolerance);
            CHECK(relative(bws.coefficients.col(k), unfolded) < tolerance);
        }
        // At a sample, its own coefficient row (exact interpolation: only without jitter).
        model.coefficients(w.set.parameters.row(4).transpose(), folded, ws);
        INFO("p " << p << " factorization " << kriging::to_string(model.kernel().status().factorization) << " jitter "
                  << model.kernel().status().jitter);
        if (model.kernel().status().exact()) CHECK(relative(folded, u_sample.row(4).transpose()) < 1e-10);
    }
}

TEST_CASE("a precomputed kernel gives exactly the synthesis of fitting it, other inputs' kernels are ignored",
          "[synthesis][shared][kernel]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Walks& w = walks();
    const Eigen::Index n = w.aligned.samples();
    const compression::SetModel sm =
        compression::fit_set_model(w.aligned.tensor, w.weight, {20, 8, n - 2}, tensor::TuckerMethod::Hosvd);
    const MotionModel fitted(sm, w.aligned, w.set, w.skeleton, 120.0);
    CHECK_FALSE(fitted.report().kernel_precomputed);

    // What compress stores is what the model fits.
    KernelFit fit = fit_kernel(sm, w.aligned, w.set, {});
    REQUIRE(fit.key != 0);
    CHECK(fit.key == fitted.kernel_fit().key);
    CHECK(fit.variogram.to_string() == fitted.report().model.to_string());
    CHECK(fit.variogram.range == fitted.report().model.range);
    CHECK(fit.exponent_loo_mse == fitted.report().exponent_loo_mse);

    fit.exponent_loo_mse.resize(0);  // as read from a database
    SynthesisOptions options;
    options.kernel_fit = fit;
    const MotionModel stored(sm, w.aligned, w.set, w.skeleton, 120.0, options);
    CHECK(stored.report().kernel_precomputed);
    // Identical doubles: poses, timing and reliability between the samples and at a sample.
    const MatX queries = between_samples(w.set.parameters);
    for (Eigen::Index k = 0; k < queries.rows(); k += 3) {
        const VecX c = queries.row(k).transpose();
        CHECK(stored.motion_poses(c) == fitted.motion_poses(c));
        CHECK(stored.timing(c).warp == fitted.timing(c).warp);
        CHECK(stored.reliability(c) == fitted.reliability(c));
    }
    const VecX c0 = w.set.parameters.row(0).transpose();
    CHECK(stored.motion_poses(c0) == fitted.motion_poses(c0));

    // Other inputs or options: another key, the kernel is fitted again (and differs).
    MotionSet moved = w.set;
    moved.parameters(0, 1) += 1.0;
    const MotionModel other_set(sm, w.aligned, moved, w.skeleton, 120.0, options);
    CHECK_FALSE(other_set.report().kernel_precomputed);
    CHECK(other_set.kernel_fit().key != fit.key);
    SynthesisOptions given_p = options;
    given_p.exponent = 1.0;
    const MotionModel other_options(sm, w.aligned, w.set, w.skeleton, 120.0, given_p);
    CHECK_FALSE(other_options.report().kernel_precomputed);
    const compression::SetModel smaller =
        compression::fit_set_model(w.aligned.tensor, w.weight, {20, 8, n - 3}, tensor::TuckerMethod::Hosvd);
    const MotionModel other_model(smaller, w.aligned, w.set, w.skeleton, 120.0, options);
    CHECK_FALSE(other_model.report().kernel_precomputed);
    // The naive model never uses one.
    const NaiveMotionModel naive(w.aligned, w.set, w.skeleton, 120.0, w.weight, options);
    CHECK_FALSE(naive.report().kernel_precomputed);
}
