#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/skeleton.hpp"

using namespace mocapdb;
using Catch::Matchers::Contains;

namespace {
Joint make_joint(std::string name, int parent, Vec3 offset, std::vector<ChannelType> channels) {
    Joint j;
    j.name = std::move(name);
    j.parent = parent;
    j.offset = offset;
    j.channels = std::move(channels);
    return j;
}
const std::vector<ChannelType> kRootChannels = {ChannelType::Xposition, ChannelType::Yposition,
                                                ChannelType::Zposition, ChannelType::Zrotation,
                                                ChannelType::Xrotation, ChannelType::Yrotation};
const std::vector<ChannelType> kRot = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
}  // namespace

TEST_CASE("skeleton validation names the violated rule", "[skeleton]") {
    CHECK_THROWS_WITH(Skeleton(std::vector<Joint>{}), Contains("at least one joint"));
    std::vector<Joint> j = {make_joint("hip", -1, Vec3::Zero(), kRootChannels),
                            make_joint("hip", 0, Vec3(0, 10, 0), kRot)};
    CHECK_THROWS_WITH(Skeleton(j), Contains("duplicate joint name"));
    j[1].name = "spine";
    j[1].parent = 1;
    CHECK_THROWS_WITH(Skeleton(j), Contains("parents before children"));
    j[1].parent = -1;
    CHECK_THROWS_WITH(Skeleton(j), Contains("parents before children, one root"));
    j[1].parent = 0;
    j[1].channels = {ChannelType::Xrotation, ChannelType::Xrotation};
    CHECK_THROWS_WITH(Skeleton(j), Contains("appears twice"));
    j[1].channels = kRot;
    j[1].offset = Vec3(0, std::nan(""), 0);
    CHECK_THROWS_WITH(Skeleton(j), Contains("not finite"));
    j[1].offset = Vec3(0, 10, 0);
    j[1].end_site = true;
    CHECK_THROWS_WITH(Skeleton(j), Contains("end site cannot have channels"));
    j[1].end_site = false;
    j[1].name = "";
    CHECK_THROWS_WITH(Skeleton(j), Contains("empty name"));
    j[1].name = "spine";
    const Skeleton ok(j);
    CHECK(ok.channel_count() == 9);
    CHECK(ok.first_channel(1) == 6);
    CHECK(ok.channel_column(1, ChannelType::Yrotation) == 8);
    CHECK(ok.channel_column(1, ChannelType::Xposition) == -1);
    CHECK(ok.find("spine") == std::size_t{1});
    CHECK_FALSE(ok.find("nope"));
}

TEST_CASE("forward kinematics composes parent rotations and offsets", "[fk]") {
    std::vector<Joint> j = {make_joint("hip", -1, Vec3::Zero(), kRootChannels),
                            make_joint("spine", 0, Vec3(0, 10, 0), kRot),
                            make_joint("head", 1, Vec3(0, 5, 0), {})};
    j[2].end_site = true;
    const Skeleton s(j);
    // Root at (1,2,3) turned 90° about Z; spine bent 90° about Z again.
    std::vector<double> row = {1, 2, 3, kPi / 2, 0, 0, kPi / 2, 0, 0};
    GlobalPose pose;
    forward_kinematics(s, row.data(), pose);
    CHECK((pose.positions[0] - Vec3(1, 2, 3)).norm() < 1e-12);
    // Rz(90°)·(0,10,0) = (−10, 0, 0)
    CHECK((pose.positions[1] - Vec3(-9, 2, 3)).norm() < 1e-12);
    // Rz(180°)·(0,5,0) = (0,−5,0)
    CHECK((pose.positions[2] - Vec3(-9, -3, 3)).norm() < 1e-12);
}

TEST_CASE("an ASF-style axis conjugates the channel rotation", "[skeleton]") {
    std::vector<Joint> j = {make_joint("root", -1, Vec3::Zero(), {}),
                            make_joint("bone", 0, Vec3::Zero(), {ChannelType::Xrotation})};
    j[1].axis = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
    j[1].rotation_order = EulerOrder::ZYX;
    const Skeleton s(j);
    const double row[] = {0.3};
    // C·Rx(0.3)·C⁻¹ with C = Rz(90°) is a rotation by 0.3 about C·X = +Y.
    const Quat expected(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
    CHECK(angle_between(s.local_rotation(1, row), expected) < 1e-12);
}
