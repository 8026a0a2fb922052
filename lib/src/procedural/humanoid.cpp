#include "mocapdb/procedural/humanoid.hpp"

#include <utility>

namespace mocapdb::procedural {
namespace {

const std::vector<ChannelType> kRootChannels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                                                ChannelType::Yrotation, ChannelType::Xrotation, ChannelType::Zrotation};
const std::vector<ChannelType> kZXY = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
const std::vector<ChannelType> kZYX = {ChannelType::Zrotation, ChannelType::Yrotation, ChannelType::Xrotation};

class Builder {
public:
    int add(const std::string& name, int parent, const Vec3& offset, bool leg = false) {
        Joint j;
        j.name = name;
        j.parent = parent;
        j.offset = offset;
        j.channels = leg ? kZYX : kZXY;
        j.rotation_order = leg ? EulerOrder::ZYX : EulerOrder::ZXY;
        joints.push_back(std::move(j));
        return static_cast<int>(joints.size()) - 1;
    }
    void end(int parent, const Vec3& offset) {
        Joint j;
        j.name = joints[static_cast<std::size_t>(parent)].name + "_end";
        j.parent = parent;
        j.offset = offset;
        j.end_site = true;
        joints.push_back(std::move(j));
    }
    std::vector<Joint> joints;
};

std::shared_ptr<const Skeleton> build() {
    Builder b;
    Joint root;
    root.name = "Hips";
    root.channels = kRootChannels;
    root.rotation_order = EulerOrder::YXZ;  // heading outermost: no gimbal lock however the body turns
    b.joints.push_back(root);
    // Spine, neck and head (the joints are listed depth-first, as a BVH file lists them).
    const int spine = b.add("Spine", 0, Vec3(0, 9, 0));
    const int spine1 = b.add("Spine1", spine, Vec3(0, 12, 0));
    const int spine2 = b.add("Spine2", spine1, Vec3(0, 12, 0));
    const int neck = b.add("Neck", spine2, Vec3(0, 15, -1));
    const int head = b.add("Head", neck, Vec3(0, 9, 1));
    b.end(head, Vec3(0, 18, 0));
    for (const double sign : {1.0, -1.0}) {
        const std::string side = sign > 0 ? "Left" : "Right";
        const int clavicle = b.add(side + "Shoulder", spine2, Vec3(sign * 2.5, 10, 0));
        const int arm = b.add(side + "Arm", clavicle, Vec3(sign * 14.5, 2, 0));
        const int forearm = b.add(side + "ForeArm", arm, Vec3(sign * 28, 0, 0));
        const int hand = b.add(side + "Hand", forearm, Vec3(sign * 25, 0, 0));
        b.end(hand, Vec3(sign * 18, 0, 0));
    }
    for (const double sign : {1.0, -1.0}) {
        const std::string side = sign > 0 ? "Left" : "Right";
        const int upleg = b.add(side + "UpLeg", 0, Vec3(sign * 9, -4, 0), true);
        const int leg = b.add(side + "Leg", upleg, Vec3(0, -42, 0), true);
        const int foot = b.add(side + "Foot", leg, Vec3(0, -41, 0), true);
        const int toe = b.add(side + "ToeBase", foot, Vec3(0, -7, 13), true);
        b.end(toe, Vec3(0, 0, 6));
    }
    return std::make_shared<const Skeleton>(b.joints, SourceUnits{1.0, true}, Vec3::UnitZ(),
                                            PositionChannels::replace_offset);  // as the BVH files it writes are read
}

}  // namespace

std::shared_ptr<const Skeleton> humanoid_skeleton() {
    static const std::shared_ptr<const Skeleton> skeleton = build();
    return skeleton;
}

std::vector<std::string> humanoid_feet() { return {HumanoidNames::left_toe, HumanoidNames::right_toe}; }

Vec3 humanoid_heel_point() { return Vec3(0, -8, -5); }

}  // namespace mocapdb::procedural
