// Building blocks of the evaluation (issue #7): the nearest-neighbour blend baseline, the Pearson
// correlation, set subsets, foot skating and the method factory on a few of subject 16's walks.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/constraint_accuracy.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/foot_skating.hpp"
#include "mocapdb/eval/loo_prediction.hpp"
#include "mocapdb/eval/nearest_neighbour.hpp"
#include "mocapdb/eval/synthesis_method.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using namespace mocapdb::eval;

TEST_CASE("nearest-neighbour blend: partition of unity, exact at samples, support on the k nearest", "[eval]") {
    Eigen::MatrixXd x(5, 2);
    x << 0, 0, 1, 0, 0, 1, 1, 1, 5, 5;
    const NearestNeighbourBlend nn(x, {3, 2.0});
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
        const Eigen::VectorXd w = nn.weights(x.row(i).transpose());
        CHECK(w(i) == Approx(1.0));
        CHECK(w.sum() == Approx(1.0));
    }
    Eigen::VectorXd c(2);
    c << 0.2, 0.1;
    const Eigen::VectorXd w = nn.weights(c);
    CHECK(w.sum() == Approx(1.0));
    CHECK((w.array() >= 0.0).all());
    CHECK(w(4) == 0.0);   // the far sample is not among the 3 nearest
    CHECK(w(3) == 0.0);   // (1, 1) is the 4th nearest
    CHECK(w(0) > w(1));   // closer gets more
    // Inverse squared distances, normalized.
    const double d0 = c.norm(), d1 = (c - x.row(1).transpose()).norm(), d2 = (c - x.row(2).transpose()).norm();
    const double s = 1 / (d0 * d0) + 1 / (d1 * d1) + 1 / (d2 * d2);
    CHECK(w(0) == Approx(1 / (d0 * d0) / s));
    CHECK_THROWS_AS(NearestNeighbourBlend(x, {0, 2.0}), InvalidArgument);
}

TEST_CASE("pearson correlation", "[eval]") {
    Eigen::VectorXd a(4), b(4);
    a << 1, 2, 3, 4;
    b << 2, 4, 6, 8;
    CHECK(pearson(a, b) == Approx(1.0));
    CHECK(pearson(a, -b) == Approx(-1.0));
    CHECK(pearson(a, Eigen::VectorXd::Constant(4, 3.0)) == 0.0);
    b << 1, -1, -1, 1;
    CHECK(std::abs(pearson(a, b)) < 1e-12);
}

TEST_CASE("eval set of walks: subset, leave-one-out sanity and foot skating of the originals", "[eval][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    EvalSetSpec spec;
    spec.name = "walks";
    spec.clips = {"16_11", "16_13", "16_15", "16_17", "16_19", "16_21"};
    spec.extractors = {"turn", "speed"};
    spec.frames = 10;
    const EvalSet set = build_eval_set(spec, test::datasets_dir() / "cmu-asfamc");
    REQUIRE(set.size() == 6);
    REQUIRE(set.set.parameters.cols() == 2);
    CHECK(set.skeleton_source == "16.asf");

    const EvalSet sub = subset(set, {4, 1, 2});
    REQUIRE(sub.size() == 3);
    CHECK(sub.labels[0] == set.labels[4]);
    CHECK(sub.set.parameters.row(0) == set.set.parameters.row(4));
    CHECK(aligned_sample(sub.aligned, 0) == aligned_sample(set.aligned, 4));
    CHECK(sub.aligned.warps.col(2) == set.aligned.warps.col(2));
    CHECK_THROWS_AS(subset(set, {1, 1}), InvalidArgument);

    // Every method reproduces a sample it was built on (exact interpolation), and predicts a left-out
    // one with a finite, non-zero error.
    const MatX truth = aligned_sample(set.aligned, 2);
    for (MethodKind kind : {MethodKind::PerPoseKriging, MethodKind::PerElementKriging, MethodKind::NaiveKriging,
                            MethodKind::Rbf, MethodKind::NearestNeighbour}) {
        MethodSpec m;
        m.kind = kind;
        m.name = to_string(kind);
        INFO(m.name);
        const auto synth = build_synthesizer(m, set);
        SynthesizedMotion motion;
        synth->synthesize(set.set.parameters.row(2).transpose(), motion);
        const MatX e = frame_joint_errors(*set.skeleton, truth, motion.aligned);
        CHECK(e.col(1).maxCoeff() < 0.05);
        CHECK(motion.warp(motion.warp.size() - 1) == Approx(static_cast<double>(set.samples[2].frame_count() - 1)).epsilon(1e-6));
    }
    MethodSpec nn;
    nn.kind = MethodKind::NearestNeighbour;
    nn.name = "nn";
    LooOptions options;
    options.samples = {0, 3};
    const LooResult loo = leave_one_out(set, {nn}, options);
    REQUIRE(loo.methods.size() == 1);
    CHECK(loo.methods[0].sample_mean_cm.size() == 2);
    CHECK(loo.methods[0].mean_cm > 0.1);
    CHECK(loo.methods[0].max_cm >= loo.methods[0].mean_cm);
    CHECK(loo.methods[0].frame_mean_cm.size() == 10);

    // Captured walks keep their planted feet: contacts exist and slide slowly.
    const FootSkating s = foot_skating(set.samples[0]);
    CHECK(s.contact_fraction > 0.2);
    CHECK(s.contact_seconds > 0.5);
    CHECK(s.cm_per_s < 20.0);
}
