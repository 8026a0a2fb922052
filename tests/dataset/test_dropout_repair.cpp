// Solver dropouts (issue #15, acceptance 5): exactly the five dropout clips of the walks16 / runs16
// evaluation sets are found, nothing in the others, and the repaired frames join their neighbours.
#include <catch2/catch.hpp>

#include <map>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/rotation.hpp"
#include "shared_clips.hpp"

using namespace mocapdb;
using Catch::Matchers::Contains;

namespace {

constexpr double kDeg = kPi / 180.0;

// walks16 (16_11..16_34, 16_47) and runs16 (16_36..16_56 without 16_47), as tools/mocapdb/cmd_eval.cpp.
std::vector<std::string> walks_and_runs() {
    std::vector<std::string> out;
    for (int t = 11; t <= 34; ++t) out.push_back("16_" + std::to_string(t));
    for (int t = 36; t <= 56; ++t) out.push_back("16_" + std::to_string(t));
    return out;
}

// "joint begin-end" per run (end exclusive), in detection order.
std::vector<std::string> runs_text(const std::vector<DropoutRun>& runs) {
    std::vector<std::string> out;
    for (const DropoutRun& r : runs) out.push_back(r.joint_name + " " + std::to_string(r.begin) + "-" + std::to_string(r.end));
    return out;
}

std::vector<std::string> arm(const std::string& side, std::initializer_list<const char*> joints, std::size_t end) {
    std::vector<std::string> out;
    for (const char* j : joints) out.push_back(side + j + " 0-" + std::to_string(end));
    return out;
}

// Largest angle between consecutive frames' local rotations of joint j over frames [first, last].
double largest_step(const Clip& clip, std::size_t j, std::size_t first, std::size_t last) {
    double m = 0.0;
    for (std::size_t f = first; f < last; ++f)
        m = std::max(m, angle_between(clip.skeleton->local_rotation(j, clip.frame(f)),
                                      clip.skeleton->local_rotation(j, clip.frame(f + 1))));
    return m;
}

// Largest frame-to-frame displacement (cm) of any joint over frames [first, last].
double largest_joint_step(const MatX& positions, std::size_t first, std::size_t last) {
    double m = 0.0;
    for (std::size_t f = first; f < last; ++f)
        for (Eigen::Index r = 0; r + 2 < positions.rows(); r += 3)
            m = std::max(m, (positions.block<3, 1>(r, static_cast<Eigen::Index>(f + 1)) -
                             positions.block<3, 1>(r, static_cast<Eigen::Index>(f))).norm());
    return m;
}

}  // namespace

TEST_CASE("dropouts: the five clips of walks16/runs16", "[dropout][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    std::map<std::string, std::vector<std::string>> expected;
    // 16_15: the arm for 2 frames, the hand for 7 (the "left arm frames 1-7" counts from 1).
    expected["16_15"] = arm("l", {"humerus", "radius", "wrist"}, 2);
    for (const auto& s : arm("l", {"hand", "fingers", "thumb"}, 7)) expected["16_15"].push_back(s);
    expected["16_23"] = arm("r", {"humerus", "radius", "wrist", "hand", "fingers", "thumb"}, 3);
    expected["16_28"] = arm("r", {"humerus", "radius", "wrist", "hand", "fingers", "thumb"}, 6);
    expected["16_33"] = arm("l", {"hand", "fingers", "thumb"}, 2);
    expected["16_54"] = {"rtoes 0-2"};
    const auto ids = walks_and_runs();
    const auto clips = test::read_shared_clips("cmu-asfamc", ids);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        INFO(ids[i]);
        const auto runs = detect_dropouts(clips[i]);
        CHECK(runs_text(runs) == expected[ids[i]]);  // (empty for every other clip: 16_47's knee zeros are a limit)
        if (runs.empty()) continue;

        Clip fixed = clips[i];
        repair_dropouts(fixed, runs);
        CHECK(detect_dropouts(fixed).empty());
        // Only the runs' rotation channels change.
        Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> changed =
            fixed.channels.array() != clips[i].channels.array();
        for (const DropoutRun& r : runs)
            for (std::size_t f = r.begin; f < r.end; ++f)
                for (const ChannelType t : fixed.skeleton->joint(r.joint).channels)
                    changed(static_cast<Eigen::Index>(f), fixed.skeleton->channel_column(r.joint, t)) = false;
        CHECK(!changed.any());

        // Continuous with the neighbours: every run starts at frame 0, so it holds the first clean
        // frame; the joint's rotation then steps from the run into the clean frames no more than the
        // clean frames step among themselves (it jumped by the dropout's whole angle before).
        for (const DropoutRun& r : runs) {
            INFO(r.joint_name);
            const double clean = largest_step(fixed, r.joint, r.end, r.end + 10);
            CHECK(largest_step(fixed, r.joint, 0, r.end + 10) <= clean + 1e-12);
            CHECK(largest_step(clips[i], r.joint, 0, r.end + 10) >= r.jump - 1e-12);
            CHECK(r.jump >= 4.0 * kDeg);
        }
        // Joint positions too: no joint jumps more between the first 20 frames than it does later.
        const MatX after = joint_positions(fixed);
        const double later = largest_joint_step(after, 20, 60);
        CHECK(largest_joint_step(after, 0, 20) <= 1.5 * later);
    }
}

TEST_CASE("dropouts: a mid-clip arm is slerped, rest poses and wraps are handled", "[dropout][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Clip clean = test::read_shared_clips("cmu-asfamc", {"16_11"}).front();
    REQUIRE(detect_dropouts(clean).empty());
    const Skeleton& s = *clean.skeleton;
    const std::size_t humerus = *s.find("lhumerus"), radius = *s.find("lradius");

    // The left humerus and radius zeroed at frames 50..59: found, and the repair lies within a few
    // degrees of the true arm (a smooth walk over 1/12 s) and on the slerp path between frames 49, 60.
    Clip damaged = clean;
    for (const std::size_t j : {humerus, radius})
        for (const ChannelType t : s.joint(j).channels) damaged.channels.block(50, s.channel_column(j, t), 10, 1).setZero();
    const auto runs = detect_dropouts(damaged);
    REQUIRE(runs_text(runs) == std::vector<std::string>{"lhumerus 50-60", "lradius 50-60"});
    repair_dropouts(damaged, runs);
    const Quat q0 = s.local_rotation(humerus, damaged.frame(49)), q1 = s.local_rotation(humerus, damaged.frame(60));
    for (std::size_t f = 50; f < 60; ++f) {
        const Quat q = s.local_rotation(humerus, damaged.frame(f));
        CHECK(angle_between(q, s.local_rotation(humerus, clean.frame(f))) < 3.0 * kDeg);
        const double t = static_cast<double>(f - 49) / 11.0;
        CHECK(angle_between(q, q0.slerp(t, q1)) < 1e-9);
    }

    // Across the ±180° wrap (2° apart): Euler lerp would swing the arm through 0 (358°); the repair
    // stays within those 2°.
    Clip wrap = clean;
    const int z = s.channel_column(humerus, ChannelType::Zrotation);
    wrap.channels.block(99, s.channel_column(humerus, ChannelType::Xrotation), 9, 3).setZero();
    wrap.channels(99, z) = 179.0 * kDeg;
    wrap.channels(107, z) = -179.0 * kDeg;
    const auto wrap_runs = detect_dropouts(wrap);
    REQUIRE(runs_text(wrap_runs) == std::vector<std::string>{"lhumerus 100-107"});
    repair_dropouts(wrap, wrap_runs);
    for (std::size_t f = 100; f < 107; ++f)
        CHECK(angle_between(s.local_rotation(humerus, wrap.frame(f)), s.local_rotation(humerus, wrap.frame(99))) <
              2.0 * kDeg + 1e-9);
    CHECK(largest_step(wrap, humerus, 99, 107) < 0.5 * kDeg);

    // A whole body at rest (every rotation channel 0, root included) is a pose, not a dropout.
    Clip rest = clean;
    for (std::size_t j = 0; j < s.size(); ++j)
        for (const ChannelType t : s.joint(j).channels)
            if (is_rotation(t)) rest.channels.block(0, s.channel_column(j, t), 3, 1).setZero();
    CHECK(detect_dropouts(rest).empty());
}

TEST_CASE("dropouts: records replay the repair and name bad joints", "[dropout][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Clip clip = test::read_shared_clips("cmu-asfamc", {"16_15"}).front();
    const auto runs = detect_dropouts(clip);
    const auto records = repair_records("16_15", runs);
    CHECK(describe_repairs("16_15", records) == "lhumerus, lradius, lwrist 0-1; lhand, lfingers, lthumb 0-6");
    CHECK(describe_repairs("16_11", records).empty());
    Clip direct = clip;
    repair_dropouts(direct, runs);
    CHECK(with_repairs(clip, "16_15", records).channels == direct.channels);
    CHECK(with_repairs(clip, "16_11", records).channels == clip.channels);  // records of another clip
    auto bad = records;
    bad[0].joint = "lwing";
    CHECK_THROWS_WITH(with_repairs(clip, "16_15", bad), Contains("16_15") && Contains("lwing"));
    bad = records;
    bad[0].end = clip.frame_count() + 1;
    CHECK_THROWS_WITH(with_repairs(clip, "16_15", bad), Contains("frames ["));
}
