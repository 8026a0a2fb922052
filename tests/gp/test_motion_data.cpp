// Motion clips as GP data (thesis §5.1.2) on the shared CMU walks, and an end-to-end fit on them.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/experiment.hpp"
#include "mocapdb/gp/gp_metrics.hpp"
#include "mocapdb/gp/motion_data.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;

namespace {

std::vector<Clip> walks(std::vector<std::string>& names) {
    const auto dir = mocapdb::test::datasets_dir() / "cmu-asfamc";
    names = {"02_01", "02_02", "35_01"};
    std::vector<Clip> clips;
    for (const auto& n : names) clips.push_back(read_clip(dir / (n + ".amc")));
    return clips;
}

}  // namespace

TEST_CASE("walks of three CMU subjects become normalized GP children", "[gp][data][shared]") {
    MOCAPDB_REQUIRE_SHARED(mocapdb::test::datasets_dir() / "cmu-asfamc" / "35_01.amc");
    std::vector<std::string> names;
    const std::vector<Clip> clips = walks(names);
    MotionDataOptions o;
    o.frames = 30;
    const MotionData md = prepare_motion_data(clips, names, o);
    const Eigen::Index d = static_cast<Eigen::Index>(md.dofs.size());
    INFO("selected " << d << " dofs; dropped " << md.dropped.size());
    CHECK(md.data.child_count() == 3);
    CHECK(md.data.frames() == 30);
    // The common duration is the shortest walk's (02_02: 298 frames at 120 Hz).
    CHECK(md.data.times[29] == Approx(297.0 / 120.0));
    CHECK(md.frame_rate == Approx(29.0 / (297.0 / 120.0)));
    // The thesis's manual rejection: no clavicle/hand/toe dofs; the legs are kept.
    for (const auto& n : md.dof_names) {
        CHECK(n.find("clavicle") == std::string::npos);
        CHECK(n.find("toes") == std::string::npos);
        CHECK(n.find("fingers") == std::string::npos);
    }
    CHECK(std::find(md.dof_names.begin(), md.dof_names.end(), "lfemur.0") != md.dof_names.end());
    CHECK(d > 30);
    CHECK(d <= 54);
    // Normalized to [0, 1] over all children, each dof reaching both ends.
    double lo = 1e9, hi = -1e9;
    for (const MatX& y : md.data.children) {
        CHECK(y.rows() == d);
        lo = std::min(lo, y.minCoeff());
        hi = std::max(hi, y.maxCoeff());
    }
    CHECK(lo == Approx(0.0).margin(1e-12));
    CHECK(hi == Approx(1.0));
    // Every selected dof passed the SNR test.
    for (std::size_t row : md.dofs) CHECK(md.log_snr[row] >= 0.0);

    // Round trip: reassembling a child's own values gives a clip whose pose vectors (canonical frame)
    // reproduce the selected dofs.
    const Clip back = reassemble_clip(md, md.data.children[1], "02_02-back");
    CHECK(back.frame_count() == 30);
    const MatX poses = to_pose_vectors(back, Canonicalization{}, md.template_pose.col(0));
    const MatX values = denormalize(md, md.data.children[1]);
    // Joints with three rotation channels are reproduced exactly; joints with one or two channels (tibia,
    // foot, radius) only up to the projection of linearly resampled exp maps onto their channels.
    double worst = 0.0, worst3 = 0.0;
    std::string worst_name;
    for (Eigen::Index i = 0; i < d; ++i) {
        const std::string& name = md.dof_names[static_cast<std::size_t>(i)];
        const double e = (poses.row(static_cast<Eigen::Index>(md.dofs[static_cast<std::size_t>(i)])) - values.row(i)).cwiseAbs().maxCoeff();
        if (e > worst) {
            worst = e;
            worst_name = name;
        }
        const std::string joint = name.substr(0, name.find('.'));
        const auto j = md.skeleton->find(joint);
        REQUIRE(j);
        int rotations = 0;
        for (const auto c : md.skeleton->joint(*j).channels) rotations += is_rotation(c) ? 1 : 0;
        if (rotations == 3) worst3 = std::max(worst3, e);
    }
    INFO("worst pose-vector difference after reassembly " << worst << " (" << worst_name << "), 3-channel joints " << worst3);
    CHECK(worst3 < 1e-6);
    CHECK(worst < 1e-3);

    // A user joint list.
    o.include_joints = {"lfemur", "ltibia"};
    const MotionData legs = prepare_motion_data(clips, names, o);
    for (const auto& n : legs.dof_names) CHECK((n.rfind("lfemur.", 0) == 0 || n.rfind("ltibia.", 0) == 0));
    CHECK(legs.dofs.size() >= 4);
    // Different joint structures are refused.
    const auto bvh = mocapdb::test::datasets_dir() / "cmu-walkrun-pfnn" / "16_15_60fps.bvh";
    if (std::filesystem::exists(bvh)) {
        ClipReadOptions ro;
        ro.frame_rate = 60.0;
        std::vector<Clip> mixed = {clips[0], read_clip(bvh, ro)};
        CHECK_THROWS_AS(prepare_motion_data(mixed, {"a", "b"}, o), InvalidArgument);
    }
    o.include_joints = {"nosuchjoint"};
    CHECK_THROWS_AS(prepare_motion_data(clips, names, o), InvalidArgument);
}

TEST_CASE("CMU walks: MOHGP fitted on two subjects interpolates the third", "[gp][data][shared][fit]") {
    MOCAPDB_REQUIRE_SHARED(mocapdb::test::datasets_dir() / "cmu-asfamc" / "35_01.amc");
    std::vector<std::string> names;
    const std::vector<Clip> clips = walks(names);
    MotionDataOptions o;
#ifdef MOCAPDB_SANITIZED_BUILD
    o.frames = 20;
#else
    o.frames = 40;
#endif
    o.include_joints = {"lfemur", "ltibia", "rfemur", "rtibia"};
    const MotionData md = prepare_motion_data(clips, names, o);
    ExperimentOptions e;
    e.runs = 3;
    e.spec.kernel = KernelType::Matern32;
#ifdef MOCAPDB_SANITIZED_BUILD
    e.fit.max_iterations = 40;
#else
    e.fit.max_iterations = 150;
#endif
    const std::size_t k = o.frames / 4;
    const ReplicateInterpolation r = run_replicate_interpolation(md.data, 0, {k}, e);
    REQUIRE(r.rows.size() == 1);
    const InterpolationRow& row = r.rows[0];
    REQUIRE(row.mohgp.smse);
    REQUIRE(row.moa.smse);
    INFO("D=" << md.dofs.size() << " T=" << o.frames << " observed " << k << ": SMSE MOHGP " << row.mohgp.smse->mean
              << " MOA " << row.moa.smse->mean << "; MSLL MOHGP " << row.mohgp.msll.mean << " MOA " << row.moa.msll.mean
              << "; fits " << to_string(r.mohgp_fit.status) << " / " << to_string(r.moa_fit.status));
    CHECK(r.mohgp_fit.status != FitStatus::NumericalFailure);
    CHECK(r.moa_fit.status != FitStatus::NumericalFailure);
    CHECK(std::isfinite(row.mohgp.msll.mean));
    CHECK(row.mohgp.msll.mean < 0.0);  // better than the trivial model of the training data
    CHECK(row.mohgp.smse->mean < row.moa.smse->mean);
}

TEST_CASE("MCC and MLC of CMU walks have the thesis's magnitudes (its Tables 18 and 19)", "[gp][metrics][shared]") {
    const auto dir = mocapdb::test::datasets_dir() / "cmu-asfamc";
    MOCAPDB_REQUIRE_SHARED(dir / "35_01.amc");
    std::vector<std::string> names = {"16_15", "35_01"};
    std::vector<Clip> clips;
    for (const auto& n : names) clips.push_back(read_clip(dir / (n + ".amc")));
    MotionDataOptions o;
    o.frames = 90;
    o.duration = 358.0 / 120.0;  // the thesis's footnote 6: frames [0, 358], 90 samples
    const MotionData md = prepare_motion_data(clips, names, o);
    const MatX& a = md.data.children[0];
    const MatX& b = md.data.children[1];
    // Thesis: 16(15) against itself 28.002, against 35(1) 25.769 (MCC); MLC 1 and 0.509.
    CHECK(mean_cross_correlation(a, a) == Approx(28.0).margin(1.0));
    CHECK(mean_cross_correlation(a, b) == Approx(25.77).margin(1.0));
    CHECK(mean_cross_correlation(a, b) < mean_cross_correlation(a, a));
    CHECK(mean_linear_correlation(a, a).value() == Approx(1.0));
    CHECK(mean_linear_correlation(a, b).value() == Approx(0.509).margin(0.15));
}
