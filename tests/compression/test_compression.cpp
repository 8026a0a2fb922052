#include <catch2/catch.hpp>

#include <random>

#include "mocapdb/compression/byte_accounting.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/compression/joint_error.hpp"
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
    const MatX positions = compression::pose_joint_positions(*clip.skeleton, to_pose_vectors(clip, canonical));
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
    const compression::JointErrorMeter meter(skeleton_of("cmu-asfamc/16_15.amc"), a.tensor);
    const compression::JointErrorStats same = meter.measure(a.tensor);
    CHECK(same.max_cm == 0.0);
    CHECK(same.dof_rmse == 0.0);
    CHECK(same.positions == 20 * 3 * static_cast<Eigen::Index>(meter.skeleton().size()));

    Tensor3 shifted = a.tensor;
    for (Eigen::Index t = 0; t < 20; ++t)
        for (Eigen::Index n = 0; n < 3; ++n) shifted(0, t, n) += 1.5;  // root x + 1.5 cm moves every joint 1.5 cm
    const compression::JointErrorStats s = meter.measure(shifted);
    CHECK(s.max_cm == Approx(1.5).epsilon(1e-9));
    CHECK(s.mean_cm == Approx(1.5).epsilon(1e-9));
    CHECK(s.rmse_cm == Approx(1.5).epsilon(1e-9));
    CHECK(s.p99_cm == Approx(1.5).epsilon(1e-9));
    // exceeds() decides as measure() does, around the measured maximum (#16).
    CHECK_FALSE(meter.exceeds(a.tensor, 0.0));
    CHECK_FALSE(meter.exceeds(shifted, s.max_cm));
    CHECK(meter.exceeds(shifted, s.max_cm * (1.0 - 1e-12)));
    CHECK(meter.exceeds(shifted, 1.0));

    Tensor3 wrong(a.tensor.dimension(0), 19, 3);
    wrong.setZero();
    CHECK_THROWS_AS(meter.measure(wrong), InvalidArgument);
    CHECK_THROWS_AS(meter.exceeds(wrong, 1.0), InvalidArgument);
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
    const compression::JointErrorMeter meter(clip.skeleton, reference);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> sign(0, 1);
    for (const double e : {0.1, 1.0, 5.0}) {
        Tensor3 noisy = reference;
        for (Eigen::Index i = 0; i < noisy.size(); ++i) {
            const Eigen::Index d = i % poses.rows();
            noisy.data()[i] += (sign(rng) ? e : -e) / w[d];  // |ΔX| = e on every value: the worst case
        }
        const compression::JointErrorStats s = meter.measure(noisy);
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

    const compression::JointErrorMeter meter(skeleton, a.tensor);
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

namespace {

// Windows of `length` frames cut every `hop` frames from subject 16's walks 16_11..16_16 (at most
// `max_windows`), canonicalized, as a dof x time x window tensor.
Tensor3 walk_windows(std::size_t length, std::size_t hop, std::size_t max_windows) {
    std::vector<MatX> cut;
    for (int t = 11; t < 17; ++t) {
        const Clip clip = read_clip(test::datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc"));
        for (std::size_t f = 0; f + length <= clip.frame_count() && cut.size() < max_windows; f += hop) {
            const Clip part = slice(clip, f, f + length);
            cut.push_back(to_pose_vectors(part, canonicalization_of(part)));
        }
    }
    Tensor3 windows(cut[0].rows(), static_cast<Eigen::Index>(length), static_cast<Eigen::Index>(cut.size()));
    for (std::size_t k = 0; k < cut.size(); ++k)
        std::copy(cut[k].data(), cut[k].data() + cut[k].size(), windows.data() + k * cut[k].size());
    return windows;
}

}  // namespace

TEST_CASE("rank search: projected sample basis gives the dense path's ranks and errors (#16)", "[compression][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto skeleton = skeleton_of("cmu-asfamc/16_15.amc");
    const VecX w = compression::position_error_weights(*skeleton);
    // Real tensors on both sides of N = D T: six walks aligned to 30 frames (N < D T), and 3-frame
    // windows cut every 4 frames from the same walks (N > D T).
    const Tensor3 windows = walk_windows(3, 4, 400);
    REQUIRE(windows.dimension(2) > windows.dimension(0) * windows.dimension(1));
    const AlignedSet aligned = walks(6, 30);
    for (const Tensor3* poses : std::initializer_list<const Tensor3*>{&aligned.tensor, &windows}) {
        const tensor::Dims3 dims = tensor::dims_of(*poses);
        const compression::JointErrorMeter meter(skeleton, *poses);
        compression::PreparedSet dense = compression::prepare_set(*poses, w);
        compression::PreparedSet projected = dense;
        tensor::HosvdOptions o;
        o.sample_basis = tensor::SampleBasisMethod::Dense;
        dense.bases = tensor::hosvd_bases(dense.x, o);
        o.sample_basis = tensor::SampleBasisMethod::Projected;
        projected.bases = tensor::hosvd_bases(projected.x, o);
        for (const double target : {2.0, 0.5}) {
            const auto rd = compression::search_ranks_for_max_error(dense, meter, target);
            const auto rp = compression::search_ranks_for_max_error(projected, meter, target);
            const tensor::Ranks& a = rd.model.tucker.ranks;
            const tensor::Ranks& b = rp.model.tucker.ranks;
            INFO("tensor " << dims[0] << "x" << dims[1] << "x" << dims[2] << ", target " << target << " cm: dense ranks "
                           << a[0] << "x" << a[1] << "x" << a[2] << " max " << rd.stats.max_cm << " cm, projected "
                           << b[0] << "x" << b[1] << "x" << b[2] << " max " << rp.stats.max_cm << " cm");
            CHECK(a == b);
            CHECK(rd.evaluations == rp.evaluations);
            CHECK(rp.target_met);
            CHECK(std::abs(rd.stats.max_cm - rp.stats.max_cm) <= 1e-6);
            const double fd = 1.0 - rd.model.tucker.fit, fp = 1.0 - rp.model.tucker.fit;
            CHECK(std::abs(fd * fd - fp * fp) <= 1e-12);
            const double bd = rd.model.tucker.error_bound, bp = rp.model.tucker.error_bound;
            const double norm = rd.model.tucker.data_norm;
            CHECK(std::abs(bd * bd - bp * bp) <= 1e-12 * norm * norm);
        }
        // The other decompositions at explicit ranks, as compress runs them after the search.
        const tensor::Ranks r{std::min<Eigen::Index>(20, dims[0]), std::min<Eigen::Index>(3, dims[1]),
                              std::min<Eigen::Index>(12, dims[2])};
        const compression::SetModel h = compression::fit_set_model(*poses, w, r, tensor::TuckerMethod::Hosvd);
        const compression::SetModel oracle = compression::hosvd_model(dense, r);
        CHECK(max_abs_difference(h.reconstruct(), oracle.reconstruct()) <= 1e-8);
        for (auto method : {tensor::TuckerMethod::StHosvd, tensor::TuckerMethod::Hooi}) {
            const compression::SetModel m = compression::fit_set_model(*poses, w, r, method);
            CHECK(m.tucker.U[2].rows() == dims[2]);
            CHECK(m.tucker.U[2].cols() == r[2]);
            CHECK(m.tucker.fit >= oracle.tucker.fit - 1e-6);
        }
    }
}

TEST_CASE("rank search: screened probes give a model checked on every pose (#16)", "[compression][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto skeleton = skeleton_of("cmu-asfamc/16_15.amc");
    const VecX w = compression::position_error_weights(*skeleton);
    // 10-frame windows cut every 5 frames from six walks: a few hundred samples, so a screen of 16
    // of them (plus the outliers and the truncation's samples) is a small part of the set.
    const Tensor3 windows = walk_windows(10, 5, 600);
    REQUIRE(windows.dimension(2) > 4 * 16);
    const compression::JointErrorMeter meter(skeleton, windows);
    const compression::PreparedSet prepared = compression::prepare_set(windows, w);
    for (const double target : {2.0, 0.5, 0.1}) {
        const auto full = compression::search_ranks_for_max_error(prepared, meter, target, {}, 0);
        const auto screened = compression::search_ranks_for_max_error(prepared, meter, target, {}, 16);
        const tensor::Ranks& a = full.model.tucker.ranks;
        const tensor::Ranks& b = screened.model.tucker.ranks;
        INFO("target " << target << " cm: unscreened " << a[0] << "x" << a[1] << "x" << a[2] << " max "
                       << full.stats.max_cm << " cm, " << full.evaluations << " models, " << full.full_checks
                       << " full checks; screened " << b[0] << "x" << b[1] << "x" << b[2] << " max "
                       << screened.stats.max_cm << " cm, " << screened.evaluations << " models, "
                       << screened.full_checks << " full checks");
        CHECK(screened.target_met);
        CHECK(screened.stats.max_cm <= target);
        // The errors are those of the returned model, measured on every pose.
        CHECK(meter.measure(screened.model.reconstruct()).max_cm == screened.stats.max_cm);
        CHECK(screened.full_checks >= 1);
        CHECK(screened.full_checks < full.full_checks);
        // On these walks the screens decide as the full checks do: the same ranks.
        CHECK(a == b);
        CHECK(screened.stats.max_cm == full.stats.max_cm);
    }
    CHECK_THROWS_AS(compression::search_ranks_for_max_error(prepared, meter, 1.0, {}, -1), InvalidArgument);
}

TEST_CASE("rank search: probes decided on the truncation reconstruction give the full search's model (#16)",
          "[compression][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto skeleton = skeleton_of("cmu-asfamc/16_15.amc");
    const VecX w = compression::position_error_weights(*skeleton);
    // 8-frame windows at every frame of six walks: N > D T, and the walks have no low numerical rank,
    // so the sample basis comes from the exact Gram of the projected samples and spans them (the
    // truncation path applies).
    const Tensor3 windows = walk_windows(8, 1, 3000);
    REQUIRE(windows.dimension(2) > windows.dimension(0) * windows.dimension(1));
    const compression::JointErrorMeter meter(skeleton, windows);
    const compression::PreparedSet prepared = compression::prepare_set(windows, w);
    REQUIRE(prepared.bases.spans_projected_samples);
    int decided_by_truncation = 0;
    for (const double target : {0.02, 0.002, 0.0005}) {
        const auto full = compression::search_ranks_for_max_error(prepared, meter, target, {}, 0);
        const auto screened = compression::search_ranks_for_max_error(prepared, meter, target, {}, 32);
        const tensor::Ranks& a = full.model.tucker.ranks;
        const tensor::Ranks& b = screened.model.tucker.ranks;
        INFO("target " << target << " cm: unscreened " << a[0] << "x" << a[1] << "x" << a[2] << " max "
                       << full.stats.max_cm << " cm; screened " << b[0] << "x" << b[1] << "x" << b[2] << " max "
                       << screened.stats.max_cm << " cm, " << screened.evaluations << " models, "
                       << screened.truncation_checks << " on the truncation reconstruction");
        CHECK(full.truncation_checks == 0);  // unscreened: every probe measured on its own model
        decided_by_truncation += screened.truncation_checks;
        CHECK(screened.target_met);
        CHECK(screened.stats.max_cm <= target);
        // The reported errors are the returned model's own, bit for bit.
        CHECK(meter.measure(screened.model.reconstruct()).max_cm == screened.stats.max_cm);
        CHECK(a == b);
        CHECK(screened.stats.max_cm == full.stats.max_cm);
        // The search that takes the prepared set (compress's) returns the same model and errors.
        compression::PreparedSet copy = prepared;
        const auto taken = compression::search_ranks_for_max_error(std::move(copy), meter, target, {}, 32);
        CHECK(copy.x.size() == 0);
        CHECK(taken.model.tucker.ranks == b);
        for (std::size_t n = 0; n < 3; ++n) CHECK(taken.model.tucker.U[n] == screened.model.tucker.U[n]);
        const Tensor3& c0 = taken.model.tucker.core;
        const Tensor3& c1 = screened.model.tucker.core;
        REQUIRE(c0.size() == c1.size());
        CHECK(Eigen::Map<const VecX>(c0.data(), c0.size()) == Eigen::Map<const VecX>(c1.data(), c1.size()));
        CHECK(taken.stats.max_cm == screened.stats.max_cm);
        CHECK(taken.stats.p99_cm == screened.stats.p99_cm);
    }
    CHECK(decided_by_truncation > 0);
}

TEST_CASE("joint error meter: a check on listed samples, and every sample beyond the target (#16)", "[compression][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const AlignedSet a = walks(4, 20);
    const auto skeleton = skeleton_of("cmu-asfamc/16_15.amc");
    const compression::JointErrorMeter meter(skeleton, a.tensor);
    // Samples 1 and 3 moved rigidly by 2 cm: their every joint is 2 cm off, the others exact.
    Tensor3 shifted = a.tensor;
    for (const Eigen::Index n : {1, 3})
        for (Eigen::Index f = 0; f < a.tensor.dimension(1); ++f) shifted(0, f, n) += 2.0;
    const auto approx = [&](const std::vector<Eigen::Index>& ids, MatX& out) {
        const Eigen::Index d = shifted.dimension(0), t = shifted.dimension(1);
        out.resize(d, t * static_cast<Eigen::Index>(ids.size()));
        for (std::size_t i = 0; i < ids.size(); ++i)
            out.middleCols(static_cast<Eigen::Index>(i) * t, t) =
                Eigen::Map<const MatX>(shifted.data() + ids[i] * d * t, d, t);
    };
    CHECK_FALSE(meter.exceeds_on(approx, {0, 2}, 1.0));
    CHECK(meter.exceeds_on(approx, {0, 3}, 1.0));
    CHECK_FALSE(meter.exceeds_on(approx, {1, 3}, 2.5));
    std::vector<Eigen::Index> suspects;
    CHECK(meter.exceeds_on(approx, {1}, 1.0, &suspects));
    CHECK(suspects == std::vector<Eigen::Index>{1});
    CHECK_THROWS_AS(meter.exceeds_on(approx, {4}, 1.0), InvalidArgument);

    std::vector<Eigen::Index> beyond{7};
    CHECK_FALSE(meter.measure_within(approx, 1.0, nullptr, &beyond).has_value());
    CHECK(beyond == std::vector<Eigen::Index>{1, 3});
    const auto within = meter.measure_within(approx, 2.5, nullptr, &beyond);
    REQUIRE(within.has_value());
    CHECK(beyond.empty());
    CHECK(std::abs(within->max_cm - 2.0) < 1e-9);
    CHECK(within->max_cm == meter.measure(shifted).max_cm);
}

TEST_CASE("the set held once: prepared in place, measured against poses read back from X (#16)", "[compression][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto skeleton = skeleton_of("cmu-asfamc/16_15.amc");
    const VecX w = compression::position_error_weights(*skeleton);
    const Tensor3 windows = walk_windows(10, 5, 600);
    const compression::PreparedSet copied = compression::prepare_set(windows, w);
    Tensor3 held = windows;
    const compression::PreparedSet in_place = compression::prepare_set_in_place(held, w);
    // The same X and bases, bit for bit; the tensor holds X, the prepared set only points at it.
    REQUIRE(in_place.in_place == &held);
    CHECK(in_place.x.size() == 0);
    const Eigen::Map<const VecX> a(copied.x.data(), copied.x.size()), b(held.data(), held.size());
    CHECK(a == b);
    CHECK(&in_place.weighted() == &held);
    for (std::size_t n = 0; n < 3; ++n) CHECK(in_place.bases.U[n] == copied.bases.U[n]);
    CHECK(in_place.mean == copied.mean);

    // A meter on X, mean and weight measures as the meter on the poses, to rounding of the poses.
    const compression::JointErrorMeter on_poses(skeleton, windows);
    const compression::JointErrorMeter on_x(skeleton, held, in_place.mean, w);
    const compression::SetModel m = compression::hosvd_model(copied, {8, 6, 20});
    const Tensor3 approx = m.reconstruct();
    const compression::JointErrorStats s0 = on_poses.measure(approx), s1 = on_x.measure(approx);
    INFO("max " << s0.max_cm << " / " << s1.max_cm << " cm, dof rmse " << s0.dof_rmse << " / " << s1.dof_rmse);
    CHECK(s0.max_cm > 0.1);
    CHECK(std::abs(s0.max_cm - s1.max_cm) <= 1e-9 * s0.max_cm);
    CHECK(std::abs(s0.rmse_cm - s1.rmse_cm) <= 1e-9 * s0.rmse_cm);
    CHECK(std::abs(s0.dof_rmse - s1.dof_rmse) <= 1e-9 * s0.dof_rmse);
    CHECK(s0.worst.sample == s1.worst.sample);
    // The poses themselves, read back, are at 0 cm.
    CHECK(on_x.measure(windows).max_cm <= 1e-9);
    CHECK_THROWS_AS(compression::JointErrorMeter(skeleton, held, in_place.mean, VecX::Zero(w.size())), InvalidArgument);
    CHECK_THROWS_AS(compression::JointErrorMeter(skeleton, held, in_place.mean.head(3), w), InvalidArgument);

    // The decomposition from X equals the one from the poses, bit for bit.
    for (const auto method : {tensor::TuckerMethod::Hosvd, tensor::TuckerMethod::Hooi}) {
        const compression::SetModel from_poses = compression::fit_set_model(windows, w, {8, 6, 20}, method);
        const compression::SetModel from_x = compression::fit_weighted_set_model(held, in_place.mean, w, {8, 6, 20}, method);
        for (std::size_t n = 0; n < 3; ++n) CHECK(from_x.tucker.U[n] == from_poses.tucker.U[n]);
        CHECK(from_x.mean == from_poses.mean);
    }
}
