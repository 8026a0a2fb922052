#pragma once
// A validated joint hierarchy: names, parents, rest offsets, and the channels each joint animates.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/rotation.hpp"

namespace mocapdb {

enum class ChannelType { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

/// "Xposition", ..., "Zrotation" (the BVH names).
std::string to_string(ChannelType type);
std::optional<ChannelType> channel_type_from_string(std::string_view text);
bool is_rotation(ChannelType type);
/// The axis a channel translates along or rotates about.
Axis channel_axis(ChannelType type);

struct Joint {
    std::string name;
    int parent = -1;             ///< index of the parent joint; -1 for the root only
    Vec3 offset = Vec3::Zero();  ///< rest translation from the parent, in the parent's frame, cm
    /// The values this joint contributes to a frame row, in row order. Position channels are cm (they
    /// replace or add to the offset, see PositionChannels); rotation channels are angles (radians).
    std::vector<ChannelType> channels;
    /// How the rotation channels compose (see EulerOrder). Axes without a channel have angle 0.
    EulerOrder rotation_order = EulerOrder::ZXY;
    /// ASF bone axis C: the local rotation is C · R(channels) · C⁻¹. Identity for BVH.
    Quat axis = Quat::Identity();
    /// A BVH "End Site": a leaf with an offset and nothing else.
    bool end_site = false;
};

/// What a joint's position channels mean. BVH as Blender and MotionBuilder read it: the channel
/// values are the local translation on their axes and replace OFFSET there (`replace_offset`).
/// The older reading adds them to OFFSET (`add_to_offset`); databases of format 1 and 2 and ASF/AMC
/// skeletons use it. Both agree whenever the offsets of joints with position channels are zero.
enum class PositionChannels { replace_offset, add_to_offset };

/// "replace_offset" / "add_to_offset" (the names the file format stores).
std::string to_string(PositionChannels mode);
std::optional<PositionChannels> position_channels_from_string(std::string_view text);

/// Units the skeleton's source file used, so writers can reproduce the source numbers.
struct SourceUnits {
    double cm_per_unit = 1.0;  ///< source length unit in centimetres
    bool degrees = true;       ///< source angles in degrees (else radians)
};

/// Immutable after construction. Invariants (checked, InvalidArgument otherwise): at least one
/// joint; joint 0 is the only root; parents come before children; names are unique and non-empty;
/// a joint has at most one channel of each type; end sites have no channels and no children;
/// offsets are finite.
///
/// The motion root is the joint whose world transform the pose vector carries: joint 0, or a joint
/// below it when every joint above it has exactly one (non-end-site) child and stays at rest (a static
/// "Reference" ROOT whose only child Hips carries the body; see find_motion_root). Joints above it
/// are taken at rest where a pose vector is turned back into channels. InvalidArgument when
/// `motion_root` is out of range or a joint above it has another child.
class Skeleton {
public:
    Skeleton() = default;
    explicit Skeleton(std::vector<Joint> joints, SourceUnits units = {}, Vec3 forward = Vec3::UnitZ(),
                      PositionChannels positions = PositionChannels::add_to_offset, std::size_t motion_root = 0);

    const std::vector<Joint>& joints() const noexcept { return joints_; }
    std::size_t size() const noexcept { return joints_.size(); }
    const Joint& joint(std::size_t index) const { return joints_.at(index); }
    std::optional<std::size_t> find(std::string_view name) const;

    /// Total values in one frame row.
    std::size_t channel_count() const noexcept { return channel_count_; }
    /// Column of the first channel of joint `index` in a frame row.
    std::size_t first_channel(std::size_t index) const { return first_channel_.at(index); }
    /// Column of the joint's channel of `type`, or -1 when the joint has none.
    int channel_column(std::size_t index, ChannelType type) const;
    /// True when the joint has at least one rotation channel.
    bool has_rotation(std::size_t index) const;

    const SourceUnits& source_units() const noexcept { return units_; }
    /// The direction the character faces in the rest pose (unit, horizontal). CMU data: +Z.
    const Vec3& forward() const noexcept { return forward_; }
    PositionChannels position_channels() const noexcept { return positions_; }
    /// See the class comment; 0 unless a static single-child chain sits above the body.
    std::size_t motion_root() const noexcept { return motion_root_; }
    /// The same skeleton with another motion root (validated as in the constructor).
    Skeleton with_motion_root(std::size_t motion_root) const;
    /// Joints from 0 down to motion_root(), root first (size 1 when the motion root is joint 0).
    const std::vector<std::size_t>& motion_root_chain() const noexcept { return chain_; }

    /// Local rotation of a joint for one frame row (`row` holds channel_count() values).
    Quat local_rotation(std::size_t index, const double* row) const;
    /// Local translation for one frame row: the offset with the position channels replacing or added
    /// to its components (see PositionChannels).
    Vec3 local_translation(std::size_t index, const double* row) const;
    /// The value a position channel holds when the joint sits at its offset: offset[axis] when the
    /// channels replace the offset, 0 when they add to it.
    double rest_position_value(std::size_t index, Axis axis) const;
    /// True when every offset component of the joint is replaced by a position channel (its OFFSET
    /// has no effect on the motion).
    bool offset_replaced(std::size_t index) const;

    /// Same motion structure: joints, parents, channels, orders, end sites, axes and motion root
    /// equal, offsets equal to `tol` except components replaced by position channels
    /// (those have no effect on any pose). Two performers of one rig compare equal when only such
    /// offsets differ.
    bool same_structure(const Skeleton& other, double tol = 1e-9) const;
    /// same_structure() and every offset component equal to `tol` (the source text's OFFSET lines).
    bool same_definition(const Skeleton& other, double tol = 1e-9) const;

private:
    std::vector<Joint> joints_;
    SourceUnits units_;
    Vec3 forward_ = Vec3::UnitZ();
    PositionChannels positions_ = PositionChannels::add_to_offset;
    std::size_t motion_root_ = 0;
    std::vector<std::size_t> chain_{0};
    std::size_t channel_count_ = 0;
    std::vector<std::size_t> first_channel_;
    std::vector<std::array<int, 6>> columns_;  // per joint, column of each ChannelType or -1
};

/// The motion root a clip calls for: starting at joint 0, step down to the only (non-end-site) child
/// while the joint stays at rest in every frame (position channels at rest_position_value within
/// 1e-6 cm, rotation channels 0 within 1e-9 rad). 0 when joint 0 moves or branches.
std::size_t find_motion_root(const Skeleton& skeleton, const FrameMatrix& channels);

}  // namespace mocapdb
