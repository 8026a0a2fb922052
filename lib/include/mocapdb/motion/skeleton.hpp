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
    int parent = -1;               ///< index of the parent joint; -1 for the root only
    Vec3 offset = Vec3::Zero();    ///< rest translation from the parent, in the parent's frame, cm
    /// The values this joint contributes to a frame row, in row order. Position channels add to the
    /// offset (cm); rotation channels are angles (radians).
    std::vector<ChannelType> channels;
    /// How the rotation channels compose (see EulerOrder). Axes without a channel have angle 0.
    EulerOrder rotation_order = EulerOrder::ZXY;
    /// ASF bone axis C: the local rotation is C · R(channels) · C⁻¹. Identity for BVH.
    Quat axis = Quat::Identity();
    /// A BVH "End Site": a leaf with an offset and nothing else.
    bool end_site = false;
};

/// Units the skeleton's source file used, so writers can reproduce the source numbers.
struct SourceUnits {
    double cm_per_unit = 1.0;  ///< source length unit in centimetres
    bool degrees = true;       ///< source angles in degrees (else radians)
};

/// Immutable after construction. Invariants (checked, InvalidArgument otherwise): at least one
/// joint; joint 0 is the only root; parents come before children; names are unique and non-empty;
/// a joint has at most one channel of each type; end sites have no channels and no children;
/// offsets are finite.
class Skeleton {
public:
    Skeleton() = default;
    explicit Skeleton(std::vector<Joint> joints, SourceUnits units = {}, Vec3 forward = Vec3::UnitZ());

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

    /// Local rotation of a joint for one frame row (`row` holds channel_count() values).
    Quat local_rotation(std::size_t index, const double* row) const;
    /// Local translation (offset plus position channels) for one frame row.
    Vec3 local_translation(std::size_t index, const double* row) const;

    /// Same joints, parents, offsets, channels, order and axes (names compared exactly, numbers to `tol`).
    bool same_structure(const Skeleton& other, double tol = 1e-9) const;

private:
    std::vector<Joint> joints_;
    SourceUnits units_;
    Vec3 forward_ = Vec3::UnitZ();
    std::size_t channel_count_ = 0;
    std::vector<std::size_t> first_channel_;
    std::vector<std::array<int, 6>> columns_;  // per joint, column of each ChannelType or -1
};

}  // namespace mocapdb
