#pragma once
// The BVH layout commercial pipelines export, made from any clip (header-only, for tests): a static
// ROOT "Reference" above the body, whose root becomes "Hips" (OFFSET `hips_offset`) and carries the
// travel; 6 channels (Xposition Yposition Zposition + the joint's rotations) on every joint, the
// position channels holding each joint's local translation (constant = OFFSET except on Hips), read
// the way BVH readers take them (PositionChannels::replace_offset). With static_root false there is
// no Reference: the moving root is the file's ROOT, with OFFSET `hips_offset`. End sites are kept.
#include <catch2/catch.hpp>

#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "mocapdb/io/bvh.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb::test {

inline Clip six_channel_layout(const Clip& source, const Vec3& hips_offset, bool static_root = true) {
    constexpr ChannelType kPositions[] = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition};
    const Skeleton& s = *source.skeleton;
    const int shift = static_root ? 1 : 0;
    std::vector<Joint> joints;
    if (static_root) {
        Joint reference;
        reference.name = "Reference";
        reference.channels = {kPositions[0], kPositions[1], kPositions[2], ChannelType::Zrotation, ChannelType::Xrotation,
                              ChannelType::Yrotation};
        reference.rotation_order = EulerOrder::ZXY;
        joints.push_back(reference);
    }
    for (std::size_t j = 0; j < s.size(); ++j) {
        Joint joint = s.joint(j);
        REQUIRE(joint.axis.w() == 1.0);  // BVH joints (no bone axis)
        joint.parent = joint.parent < 0 ? (static_root ? 0 : -1) : joint.parent + shift;
        if (j == 0) {
            joint.name = "Hips";
            joint.offset = hips_offset;
        }
        if (!joint.end_site) {
            std::vector<ChannelType> channels(std::begin(kPositions), std::end(kPositions));
            for (ChannelType c : joint.channels)
                if (is_rotation(c)) channels.push_back(c);
            joint.channels = channels;
        }
        joints.push_back(joint);
    }
    auto skeleton = std::make_shared<const Skeleton>(joints, s.source_units(), s.forward(), PositionChannels::replace_offset);
    Clip out;
    out.name = source.name;
    out.frame_rate = source.frame_rate;
    out.skeleton = skeleton;
    out.channels = FrameMatrix::Zero(source.channels.rows(), static_cast<Eigen::Index>(skeleton->channel_count()));
    for (std::size_t f = 0; f < source.frame_count(); ++f) {
        double* row = out.channels.row(static_cast<Eigen::Index>(f)).data();
        for (std::size_t j = 0; j < s.size(); ++j) {
            const std::size_t to = j + static_cast<std::size_t>(shift);
            const Vec3 t = s.local_translation(j, source.frame(f));  // Hips: the body's path; others: OFFSET
            for (int a = 0; a < 3; ++a) {
                const int col = skeleton->channel_column(to, kPositions[a]);
                if (col >= 0) row[col] = t[a];
            }
            for (ChannelType c : s.joint(j).channels)
                if (is_rotation(c)) row[skeleton->channel_column(to, c)] = source.frame(f)[s.channel_column(j, c)];
        }
    }
    return out;
}

/// `clip` written as BVH text (17 digits: lossless) and read back as a user's import reads it, with
/// `positions` as the position-channel convention (the motion root is the reader's).
inline Clip through_bvh_text(const Clip& clip, PositionChannels positions) {
    std::ostringstream text;
    write_bvh(text, clip, BvhWriteOptions{17, 1.0});
    BvhReadOptions o;
    o.frame_rate = clip.frame_rate;
    o.position_channels = positions;
    Clip read = parse_bvh(text.str(), clip.name + ".bvh", o);
    read.name = clip.name;
    return read;
}

}  // namespace mocapdb::test
