#include <catch2/catch.hpp>

#include <random>

#include "mocapdb/compression/byte_accounting.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/eval/joint_error.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "shared_data.hpp"

using namespace mocapdb;

namespace {

// Subject 16's first `count` straight and veering walks, linearly aligned to `frames` frames.
AlignedSet walks(int count, Eigen::Index frames) {
    std::vector<Clip> clips;
    for (int t = 11; t < 11 + count; ++t)
        clips.push_back(read_clip(test::datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")));
    AlignOptions options;
    options.method = "linear";
    options.frames = frames;
    return align_samples(clips, options);
}

std::shared_ptr<const Skeleton> skeleton_of(const std::string& file) {
    return read_clip(test::datasets_dir() / file).skeleton;
}

double max_abs_difference(const Tensor3& a, const Tensor3& b) {
    double m = 0.0;
    for (Eigen::Index i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a.data()[i] - b.data()[i]));
    return m;
}

}  // namespace

TEST_CASE("joint positions of pose vectors equal forward kinematics of the clip", "[eval][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Clip clip = read_clip(test::datasets_dir() / "cmu-asfamc" / "16_15.amc");
    const Canonicalization canonical = canonicalization_of(clip);
    const MatX positions = eval::pose_joint_positions(*clip.skeleton, to_pose_vectors(clip, canonical));
    const MatX world = joint_positions(clip);
    double worst = 0.0;
    for (Eigen::Index f = 0; f < world.cols(); ++f)
        for (Eigen::Index j = 0; j < world.rows() / 3; ++j)
            worst = std::max(worst, (canonical.apply(Vec3(world.block<3, 1>(3 * j, f))) -
                                     positions.block<3, 1>(3 * j, f)).norm());
    INFO("worst difference " << worst << " cm");
    CHECK(worst < 1e-9);
}

TEST_CASE("joint error meter: zero for the reference, exact for a rigid shift", "[eval][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const AlignedSet a = walks(3, 20);
    const eval::JointErrorMeter meter(skeleton_of("cmu-asfamc/16_15.amc"), a.tensor);
    const eval::JointErrorStats same = meter.measure(a.tensor);
    CHECK(same.max_cm == 0.0);
    CHECK(same.dof_rmse == 0.0);
    CHECK(same.positions == 20 * 3 * static_cast<Eigen::Index>(meter.skeleton().size()));

    Tensor3 shifted = a.tensor;
    for (Eigen::Index t = 0; t < 20; ++t)
        for (Eigen::Index n = 0; n < 3; ++n) shifted(0, t, n) += 1.5;  // root x + 1.5 cm moves every joint 1.5 cm
    const eval::JointErrorStats s = meter.measure(shifted);
    CHECK(s.max_cm == Approx(1.5).epsilon(1e-9));
    CHECK(s.mean_cm == Approx(1.5).epsilon(1e-9));
    CHECK(s.rmse_cm == Approx(1.5).epsilon(1e-9));
    CHECK(s.p99_cm == Approx(1.5).epsilon(1e-9));

    Tensor3 wrong(a.tensor.dimension(0), 19, 3);
    wrong.setZero();
    CHECK_THROWS_AS(meter.measure(wrong), InvalidArgument);
}

TEST_CASE("position-error weights bound every joint's error", "[compression][shared]") {
    // A BVH skeleton: every joint has three rotation channels, so no channel projection intervenes
    // and the bound of dof_weights.hpp must hold exactly.
    const auto dir = test::datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(dir);
    const Clip clip = read_clip(dir / "02_01_60fps.bvh");
    const Clip part = slice(clip, 0, 60);
    const MatX poses = to_pose_vectors(part, canonicalization_of(part));
    const VecX w = compression::position_error_weights(*clip.skeleton);
    REQUIRE(w.size() == poses.rows());
    CHECK((w.array() > 0).all());

    Tensor3 reference(poses.rows(), poses.cols(), 1);
    std::copy(poses.data(), poses.data() + poses.size(), reference.data());
    const eval::JointErrorMeter meter(clip.skeleton, reference);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> sign(0, 1);
    for (const double e : {0.1, 1.0, 5.0}) {
        Tensor3 noisy = reference;
        for (Eigen::Index i = 0; i < noisy.size(); ++i) {
            const Eigen::Index d = i % poses.rows();
            noisy.data()[i] += (sign(rng) ? e : -e) / w[d];  // |ΔX| = e on every value: the worst case
        }
        const eval::JointErrorStats s = meter.measure(noisy);
        INFO("E = " << e << " cm: measured max " << s.max_cm << " cm at " << s.worst.joint);
        CHECK(s.max_cm <= e);
        CHECK(s.max_cm > 0.05 * e);  // and the weights are not absurdly conservative
    }
}

TEST_CASE("set model: full ranks reproduce the poses, truncation meets the searched max error", "[compression][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const AlignedSet a = walks(6, 30);
    const auto skeleton = skeleton_of("cmu-asfamc/16_15.amc");
    const VecX w = compression::position_error_weights(*skeleton);
    const tensor::Dims3 dims = tensor::dims_of(a.tensor);

    for (auto method : {tensor::TuckerMethod::Hosvd, tensor::TuckerMethod::StHosvd, tensor::TuckerMethod::Hooi}) {
        const compression::SetModel full = compression::fit_set_model(a.tensor, w, dims, method);
        double norm = 0.0;
        for (Eigen::Index i = 0; i < a.tensor.size(); ++i) norm = std::max(norm, std::abs(a.tensor.data()[i]));
        CHECK(max_abs_difference(full.reconstruct(), a.tensor) <= 1e-10 * norm);
    }

    const eval::JointErrorMeter meter(skeleton, a.tensor);
    const compression::PreparedSet prepared = compression::prepare_set(a.tensor, w);
    for (const double target : {2.0, 0.5}) {
        const auto r = compression::search_ranks_for_max_error(prepared, meter, target);
        INFO("target " << target << " cm: ranks " << r.model.tucker.ranks[0] << "x" << r.model.tucker.ranks[1] << "x"
                       << r.model.tucker.ranks[2] << ", max " << r.stats.max_cm << " cm after " << r.evaluations
                       << " evaluations");
        CHECK(r.target_met);
        CHECK(r.stats.max_cm <= target);
        CHECK(meter.measure(r.model.reconstruct()).max_cm == r.stats.max_cm);
        // Not the trivial answer: the model is smaller than the full-rank one.
        CHECK(r.model.tucker.parameter_count() < tensor::tucker_parameter_count(dims, dims));
    }
    CHECK_THROWS_AS(compression::search_ranks_for_max_error(prepared, meter, 0.0), InvalidArgument);
}
