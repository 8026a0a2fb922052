#include <catch2/catch.hpp>
#include <random>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/motion/pose_vector_positions.hpp"

using namespace mocapdb;

namespace {

// A three-joint chain with all six Euler orders represented across joints and an ASF-style axis.
std::shared_ptr<const Skeleton> test_skeleton() {
    std::vector<Joint> joints(4);
    joints[0].name = "root";
    joints[0].channels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                          ChannelType::Zrotation, ChannelType::Yrotation, ChannelType::Xrotation};
    joints[0].rotation_order = EulerOrder::ZYX;
    joints[1].name = "a";
    joints[1].parent = 0;
    joints[1].offset = Vec3(0, 10, 0);
    joints[1].channels = {ChannelType::Yrotation, ChannelType::Xrotation, ChannelType::Zrotation};
    joints[1].rotation_order = EulerOrder::YXZ;
    joints[2].name = "b";
    joints[2].parent = 1;
    joints[2].offset = Vec3(3, 10, 1);
    joints[2].channels = {ChannelType::Xrotation, ChannelType::Zrotation};  // two dofs, ASF style
    joints[2].rotation_order = EulerOrder::ZYX;
    joints[2].axis = Quat(Eigen::AngleAxisd(0.35, Vec3(1, 1, 0).normalized()));
    joints[3].name = "b_end";
    joints[3].parent = 2;
    joints[3].offset = Vec3(0, 7, 0);
    joints[3].end_site = true;
    return std::make_shared<const Skeleton>(joints);
}

// Smooth motion whose root turns by 270° and whose joint Euler angles swing past ±180°.
Clip test_clip(int frames) {
    Clip clip;
    clip.skeleton = test_skeleton();
    clip.frame_rate = 60;
    clip.channels.resize(frames, static_cast<Eigen::Index>(clip.skeleton->channel_count()));
    for (int f = 0; f < frames; ++f) {
        const double t = f / 60.0;
        clip.channels.row(f) << 30 + 50 * t, 90 + 2 * std::sin(5 * t), -20 + 10 * t,  // root position
            0.2 * std::sin(t), 0.3 + 4.7 * t, 0.1 * std::cos(2 * t),                   // root Z Y X (yaw > π)
            2.0 * std::sin(1.5 * t), 0.4 * std::cos(t), 3.6 * std::sin(2 * t),         // a: Y X Z
            0.8 * std::sin(3 * t), -0.5 + 0.3 * t;                                     // b: X Z
    }
    return clip;
}

}  // namespace

TEST_CASE("canonicalization puts the first root at the floor origin facing +Z and inverts exactly", "[pose]") {
    const Clip clip = test_clip(120);
    const Canonicalization c = canonicalization_of(clip);
    const MatX poses = to_pose_vectors(clip, c);
    CHECK(std::abs(poses(0, 0)) < 1e-12);
    CHECK(std::abs(poses(2, 0)) < 1e-12);
    CHECK(poses(1, 0) == Approx(clip.channels(0, 1)));  // height kept
    const Quat root0 = swing_twist_exp(poses.col(0).segment<3>(3));
    CHECK(std::abs(heading_of(root0, Vec3::UnitZ())) < 1e-12);
    const Vec3 p(1.5, -2, 7);
    CHECK((c.invert(c.apply(p)) - p).norm() < 1e-12);
}

TEST_CASE("channels -> pose vectors -> channels is exact and continuous", "[pose]") {
    const Clip clip = test_clip(60);
    const Skeleton& s = *clip.skeleton;
    const PoseLayout layout(s);
    REQUIRE(layout.dof_count() == 12);  // root 6 + a 3 + b 3 (the end site has no rotation)
    const Canonicalization c = canonicalization_of(clip);
    const MatX poses = to_pose_vectors(clip, c);
    REQUIRE(poses.rows() == 12);
    // Continuity: no exp-map jump larger than π/2 between frames although angles wind past 2π.
    for (Eigen::Index f = 1; f < poses.cols(); ++f)
        for (Eigen::Index r = 3; r < poses.rows(); r += 3)
            REQUIRE((poses.col(f).segment<3>(r) - poses.col(f - 1).segment<3>(r)).norm() < kPi / 2);

    const FrameMatrix back = from_pose_vectors(s, poses, c, VecX(clip.channels.row(0).transpose()));
    double worst_angle = 0, worst_position = 0, worst_euler_step = 0;
    for (Eigen::Index f = 0; f < back.rows(); ++f) {
        for (std::size_t j = 0; j < s.size(); ++j) {
            if (!s.has_rotation(j)) continue;
            worst_angle = std::max(worst_angle, angle_between(s.local_rotation(j, clip.frame(f)),
                                                              s.local_rotation(j, back.row(f).data())));
        }
        worst_position = std::max(worst_position, (back.row(f).head<3>() - clip.channels.row(f).head<3>()).norm());
        if (f > 0)
            worst_euler_step =
                std::max(worst_euler_step, (back.row(f).tail(8) - back.row(f - 1).tail(8)).cwiseAbs().maxCoeff());
    }
    INFO("worst angle " << worst_angle << " worst position " << worst_position);
    CHECK(worst_angle < 1e-9);
    CHECK(worst_position < 1e-9);
    CHECK(worst_euler_step < 0.5);  // unwrapped: no 360° jumps
    // The windings themselves come back: the returned Euler tracks equal the source's.
    CHECK((back - clip.channels).cwiseAbs().maxCoeff() < 1e-8);
}

TEST_CASE("pose vectors and FK from local transforms equal those from channel rows", "[pose]") {
    const Clip clip = test_clip(90);
    const Skeleton& s = *clip.skeleton;
    const PoseLayout layout(s);
    const MatX expected = to_pose_vectors(clip, canonicalization_of(clip));
    std::vector<Quat> rotations(s.size());
    std::vector<Vec3> translations(s.size());
    Canonicalization c;
    VecX near = VecX::Zero(12), column(12);
    GlobalPose from_row, from_local;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        for (std::size_t j = 0; j < s.size(); ++j) {
            rotations[j] = s.local_rotation(j, clip.frame(f));
            translations[j] = s.local_translation(j, clip.frame(f));
        }
        if (f == 0) c = canonicalization_of(local_root_transform(s, rotations, translations), s.forward());
        pose_vector_from_local(s, layout, rotations, translations, c, near, column);
        REQUIRE((column - expected.col(static_cast<Eigen::Index>(f))).cwiseAbs().maxCoeff() == 0.0);
        near = column;
        forward_kinematics(s, clip.frame(f), from_row);
        forward_kinematics(s, rotations, translations, from_local);
        for (std::size_t j = 0; j < s.size(); ++j) REQUIRE(from_row.positions[j] == from_local.positions[j]);
    }
    rotations.pop_back();
    CHECK_THROWS_AS(forward_kinematics(s, rotations, translations, from_local), InvalidArgument);
    CHECK_THROWS_AS(pose_vector_from_local(s, layout, rotations, translations, c, near, column), InvalidArgument);
}

TEST_CASE("pose-vector functions refuse mismatched shapes", "[pose]") {
    const Clip clip = test_clip(5);
    const Canonicalization c = canonicalization_of(clip);
    CHECK_THROWS_AS(to_pose_vectors(clip, c, VecX::Zero(3)), InvalidArgument);
    CHECK_THROWS_AS(from_pose_vectors(*clip.skeleton, MatX::Zero(5, 2), c), InvalidArgument);
    MatX bad = to_pose_vectors(clip, c);
    bad(4, 1) = std::nan("");
    CHECK_THROWS_AS(from_pose_vectors(*clip.skeleton, bad, c), InvalidArgument);
}

TEST_CASE("joint positions straight from pose vectors equal forward kinematics of their channel rows", "[pose]") {
    const Clip clip = test_clip(120);
    const Skeleton& s = *clip.skeleton;
    const Canonicalization c = canonicalization_of(clip);
    const MatX exact = to_pose_vectors(clip, c);
    // Perturbed poses, as a compressed model gives them: joint b (two channels) gets rotations its
    // channels cannot express, which both paths project the same way.
    MatX noisy = exact;
    std::mt19937 rng(3);
    std::normal_distribution<double> g(0.0, 0.2);
    for (Eigen::Index i = 0; i < noisy.size(); ++i) noisy.data()[i] += g(rng);
    for (const MatX* poses : {&exact, static_cast<const MatX*>(&noisy)}) {
        const FrameMatrix rows = from_pose_vectors(s, *poses, c);
        const MatX direct = pose_vector_joint_positions(s, *poses, c);
        REQUIRE(direct.rows() == 3 * static_cast<Eigen::Index>(s.size()));
        REQUIRE(direct.cols() == poses->cols());
        GlobalPose pose;
        double worst = 0.0;
        for (Eigen::Index f = 0; f < poses->cols(); ++f) {
            forward_kinematics(s, rows.row(f).data(), pose);
            for (std::size_t j = 0; j < s.size(); ++j)
                worst = std::max(worst, (pose.positions[j] - direct.block<3, 1>(3 * static_cast<Eigen::Index>(j), f)).norm());
        }
        INFO("worst difference " << worst << " cm");
        CHECK(worst < 1e-10);
    }
    CHECK_THROWS_AS(pose_vector_joint_positions(s, MatX::Zero(5, 2), c), InvalidArgument);
    MatX bad = exact;
    bad(4, 1) = std::nan("");
    CHECK_THROWS_AS(pose_vector_joint_positions(s, bad, c), InvalidArgument);
}
