// Acceptance checks of the motion data layer on every shared CMU clip (BVH and ASF/AMC).
#include <catch2/catch.hpp>
#include <set>
#include <sstream>

#include "mocapdb/io/bvh.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using mocapdb::test::LoadedClip;

namespace {

std::size_t expected_count(std::size_t all) {
#ifdef MOCAPDB_SANITIZED_BUILD
    return (all + 5) / 6;
#else
    return all;
#endif
}

// Largest relative deviation of FK bone lengths from the skeleton offsets, over all frames and joints.
double worst_bone_length_error(const Clip& clip) {
    const Skeleton& s = *clip.skeleton;
    const MatX p = joint_positions(clip);
    double worst = 0.0;
    for (std::size_t j = 1; j < s.size(); ++j) {
        bool translates = false;
        for (ChannelType c : s.joint(j).channels) translates = translates || !is_rotation(c);
        if (translates) continue;
        const auto parent = static_cast<Eigen::Index>(s.joint(j).parent);
        const double expected = s.joint(j).offset.norm();
        const auto r = 3 * static_cast<Eigen::Index>(j);
        for (Eigen::Index f = 0; f < p.cols(); ++f) {
            const double length = (p.block<3, 1>(r, f) - p.block<3, 1>(3 * parent, f)).norm();
            const double err = std::abs(length - expected) / std::max(expected, 1.0);
            worst = std::max(worst, err);
        }
    }
    return worst;
}

struct RoundTrip {
    double rotation = 0;     // worst angle between original and returned joint rotation, rad
    double position = 0;     // worst root position difference, cm
    double euler_step = 0;   // largest change of a returned rotation channel between frames, rad
    double exp_step = 0;     // largest exp-map change between frames where the rotation moved ≤ π/4
    std::size_t source_jumps = 0;  // steps where the source rotation itself moved > π/4 in one frame
    double max_norm = 0;     // largest joint (non-root) exp-map norm: how close tracks come to the 2π shell
};

RoundTrip pose_round_trip(const Clip& clip) {
    const Skeleton& s = *clip.skeleton;
    const Canonicalization c = canonicalization_of(clip);
    const MatX poses = to_pose_vectors(clip, c);
    const FrameMatrix back = from_pose_vectors(s, poses, c, VecX(clip.channels.row(0).transpose()));
    const PoseLayout layout(s);
    RoundTrip r;
    for (Eigen::Index f = 0; f < back.rows(); ++f) {
        for (std::size_t j = 0; j < s.size(); ++j) {
            if (!s.has_rotation(j)) continue;
            r.rotation = std::max(r.rotation, angle_between(s.local_rotation(j, clip.frame(f)),
                                                            s.local_rotation(j, back.row(f).data())));
        }
        r.position = std::max(r.position, (s.local_translation(0, clip.frame(f)) -
                                           s.local_translation(0, back.row(f).data())).norm());
        if (f == 0) continue;
        for (std::size_t j = 0; j < s.size(); ++j)
            for (std::size_t k = 0; k < s.joint(j).channels.size(); ++k)
                if (is_rotation(s.joint(j).channels[k])) {
                    const auto col = static_cast<Eigen::Index>(s.first_channel(j) + k);
                    r.euler_step = std::max(r.euler_step, std::abs(back(f, col) - back(f - 1, col)));
                }
        for (std::size_t j : layout.rotation_joints()) {
            const Eigen::Index row = layout.exp_map_row(j);
            const double step = (poses.col(f).segment<3>(row) - poses.col(f - 1).segment<3>(row)).norm();
            // CMU data has glitches where a joint flips by a large angle within one frame; no
            // representation can hide those, so they are counted, and bounded relative to the flip.
            const double moved = angle_between(s.local_rotation(j, clip.frame(f - 1)), s.local_rotation(j, clip.frame(f)));
            if (moved <= kPi / 4) {
                r.exp_step = std::max(r.exp_step, step);
            } else {
                ++r.source_jumps;
            }
            if (j != 0) r.max_norm = std::max(r.max_norm, poses.col(f).segment<3>(row).norm());
        }
    }
    return r;
}

void check_pose_round_trips(const std::vector<LoadedClip>& clips) {
    RoundTrip worst;
    for (const LoadedClip& c : clips) {
        const RoundTrip r = pose_round_trip(c.clip);
        INFO(c.path << ": rotation " << r.rotation << " rad, root " << r.position << " cm, Euler step "
                    << r.euler_step << " rad, exp-map step " << r.exp_step << " rad, source jumps "
                    << r.source_jumps << ", largest joint exp-map norm " << r.max_norm << " rad");
        CHECK(r.rotation <= 1e-9);
        CHECK(r.position <= 1e-9);
        CHECK(r.euler_step < kPi);  // unwrapped: no 360° jumps
        CHECK(r.exp_step <= kPi / 2);
        CHECK(r.max_norm <= 1.5 * kPi);  // tracks never drift toward the singular 2π shell
        worst.rotation = std::max(worst.rotation, r.rotation);
        worst.position = std::max(worst.position, r.position);
        worst.euler_step = std::max(worst.euler_step, r.euler_step);
        worst.exp_step = std::max(worst.exp_step, r.exp_step);
        worst.source_jumps += r.source_jumps;
        worst.max_norm = std::max(worst.max_norm, r.max_norm);
    }
    WARN(clips.size() << " clips: worst rotation " << worst.rotation << " rad, root " << worst.position
                      << " cm, Euler step " << worst.euler_step << " rad, exp-map step " << worst.exp_step
                      << " rad; " << worst.source_jumps << " source flips of > 45 deg in one frame, largest joint"
                      << " exp-map norm " << worst.max_norm << " rad");
}

}  // namespace

TEST_CASE("every shared BVH clip loads, the 8 short files warn, and so does the 60 Hz override of every file",
          "[shared][bvh]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-walkrun-pfnn");
    const auto& clips = test::shared_bvh_clips();
    REQUIRE(clips.size() == expected_count(33));
    const std::set<std::string> short_files = {"08_04", "16_13", "16_19", "16_37", "16_44", "35_01", "39_01", "46_01"};
    for (const LoadedClip& c : clips) {
        INFO(c.path);
        const std::string trial = c.clip.name.substr(0, c.clip.name.find("_60fps"));
        // Read at 60 Hz (the true rate); every file's Frame Time says 1/15 s, so each says so once.
        CHECK(c.warnings == (short_files.count(trial) ? 2u : 1u));
        CHECK(c.clip.skeleton->channel_count() == 132);
        CHECK(c.clip.frame_count() > 50);
    }
}

// (AMC clips: the same property is checked in test_asf_amc.cpp.)
TEST_CASE("FK bone lengths of every shared BVH clip are constant and equal the offsets", "[shared][fk]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-walkrun-pfnn");
    double worst = 0;
    for (const LoadedClip& c : test::shared_bvh_clips()) {
        const double e = worst_bone_length_error(c.clip);
        INFO(c.path << ": worst relative bone-length error " << e);
        CHECK(e <= 1e-6);
        worst = std::max(worst, e);
    }
    WARN("worst relative bone-length error over the shared BVH clips: " << worst);
}

TEST_CASE("channels -> pose vector -> channels round trip on every shared clip", "[shared][pose]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir());
    check_pose_round_trips(test::shared_bvh_clips());
    check_pose_round_trips(test::shared_amc_clips());
}

TEST_CASE("BVH write then read reproduces every shared BVH clip", "[shared][bvh]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-walkrun-pfnn");
    for (const LoadedClip& c : test::shared_bvh_clips()) {
        std::ostringstream out;
        write_bvh(out, c.clip);
        const Clip back = parse_bvh(out.str(), c.path);
        INFO(c.path);
        CHECK(back.skeleton->same_structure(*c.clip.skeleton, 1e-6));
        CHECK(back.frame_rate == Approx(60.0).epsilon(1e-12));
        // 9 significant digits of values up to a few hundred: well below 1e-6 in file units.
        CHECK((back.channels - c.clip.channels).cwiseAbs().maxCoeff() < 1e-6);
    }
}

TEST_CASE("AMC -> BVH export -> read back gives the same joint positions", "[shared][amc][bvh]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    double worst = 0;
    for (const LoadedClip& c : test::shared_amc_clips()) {
        std::ostringstream out;
        write_bvh(out, c.clip);
        const Clip back = parse_bvh(out.str(), c.path + ".bvh");
        REQUIRE(back.frame_count() == c.clip.frame_count());
        // Joint sets are the same (BVH keeps every ASF joint and end site, in order).
        REQUIRE(back.skeleton->size() == c.clip.skeleton->size());
        const double e = (joint_positions(back) - joint_positions(c.clip)).cwiseAbs().maxCoeff();
        INFO(c.path << ": worst joint position difference " << e << " cm");
        CHECK(e <= 1e-3);
        worst = std::max(worst, e);
    }
    WARN("AMC->BVH->read worst joint position difference: " << worst << " cm");
}
