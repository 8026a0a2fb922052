#include "skeleton_codec.hpp"

#include <cmath>

#include "layout.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {
namespace {

std::string count_text(std::uint64_t n) { return std::to_string(n); }

}  // namespace

void write_skeleton(h5::File& file, const std::string& id, const Skeleton& s, const std::string& source_file) {
    const std::string g = skeleton_path(id);
    file.create_group(g, "skeleton");
    file.write_string_attribute(g, "source_file", source_file);
    file.write_double_attribute(g, "cm_per_unit", s.source_units().cm_per_unit);
    file.write_string_attribute(g, "source_angles", s.source_units().degrees ? "deg" : "rad");
    file.write_doubles_attribute(g, "forward", {s.forward().x(), s.forward().y(), s.forward().z()});
    file.write_string_attribute(g, "position_channels", to_string(s.position_channels()));
    file.write_int_attribute(g, "motion_root", static_cast<std::int64_t>(s.motion_root()));

    const std::size_t n = s.size();
    std::vector<std::string> names, orders;
    std::vector<std::int32_t> parents;
    std::vector<double> offsets, axes;
    std::vector<std::uint8_t> end_sites;
    std::vector<std::int32_t> channel_joint;
    std::vector<std::string> channel_type;
    for (std::size_t j = 0; j < n; ++j) {
        const Joint& joint = s.joint(j);
        names.push_back(joint.name);
        parents.push_back(joint.parent);
        for (int a = 0; a < 3; ++a) offsets.push_back(joint.offset[a]);
        const Quat q = joint.axis.normalized();
        axes.insert(axes.end(), {q.w(), q.x(), q.y(), q.z()});
        orders.push_back(to_string(joint.rotation_order));
        end_sites.push_back(joint.end_site ? 1 : 0);
        for (ChannelType c : joint.channels) {
            channel_joint.push_back(static_cast<std::int32_t>(j));
            channel_type.push_back(to_string(c));
        }
    }
    file.write_strings(g + "/joint_name", names, "joint", "");
    file.write_array(g + "/joint_parent", parents.data(), {n}, {"joint"}, "");
    file.write_array(g + "/joint_offset", offsets.data(), {n, 3}, {"joint", "xyz"}, "cm");
    file.write_array(g + "/joint_axis", axes.data(), {n, 4}, {"joint", "wxyz"}, "");
    file.write_strings(g + "/joint_rotation_order", orders, "joint", "");
    file.write_array(g + "/joint_end_site", end_sites.data(), {n}, {"joint"}, "");
    file.write_array(g + "/channel_joint", channel_joint.data(), {channel_joint.size()}, {"channel"}, "");
    file.write_strings(g + "/channel_type", channel_type, "channel", "");
}

Skeleton read_skeleton(const h5::File& file, const std::string& id) {
    const std::string g = skeleton_path(id);
    const std::string& fname = file.name();
    if (file.type_of(g) != h5::ObjectType::Group) throw StoreError(fname, g, "no such skeleton");
    const auto names = file.read_strings(g + "/joint_name");
    const std::uint64_t n = names.size();
    auto expect_rows = [&](const std::string& path, const h5::Shape& shape, std::uint64_t rows, std::uint64_t cols) {
        const bool ok = shape.size() == (cols == 0 ? 1u : 2u) && shape[0] == rows && (cols == 0 || shape[1] == cols);
        if (!ok) {
            h5::Shape expected{rows};
            if (cols != 0) expected.push_back(cols);
            throw StoreError(fname, path,
                             "expected shape " + h5::shape_text(expected) + " (one row per joint of " + g +
                                 "/joint_name), found " + h5::shape_text(shape));
        }
    };
    const auto parents = file.read_array<std::int32_t>(g + "/joint_parent", 1);
    expect_rows(g + "/joint_parent", parents.shape, n, 0);
    const auto offsets = file.read_array<double>(g + "/joint_offset", 2);
    expect_rows(g + "/joint_offset", offsets.shape, n, 3);
    for (std::size_t k = 0; k < offsets.data.size(); ++k)
        if (!std::isfinite(offsets.data[k]))
            throw StoreError(fname, g + "/joint_offset",
                             "joint " + std::to_string(k / 3) + ": expected a finite offset, found " +
                                 std::to_string(offsets.data[k]));
    const auto axes = file.read_array<double>(g + "/joint_axis", 2);
    expect_rows(g + "/joint_axis", axes.shape, n, 4);
    const auto orders = file.read_strings(g + "/joint_rotation_order");
    if (orders.size() != n)
        throw StoreError(fname, g + "/joint_rotation_order",
                         "expected shape (" + count_text(n) + ",), found (" + count_text(orders.size()) + ",)");
    const auto end_sites = file.read_array<std::uint8_t>(g + "/joint_end_site", 1);
    expect_rows(g + "/joint_end_site", end_sites.shape, n, 0);
    const auto channel_joint = file.read_array<std::int32_t>(g + "/channel_joint", 1);
    const auto channel_type = file.read_strings(g + "/channel_type");
    if (channel_type.size() != channel_joint.data.size())
        throw StoreError(fname, g + "/channel_type",
                         "expected shape (" + count_text(channel_joint.data.size()) + ",) like " + g +
                             "/channel_joint, found (" + count_text(channel_type.size()) + ",)");

    std::vector<Joint> joints(n);
    for (std::size_t j = 0; j < n; ++j) {
        Joint& joint = joints[j];
        joint.name = names[j];
        joint.parent = parents.data[j];
        joint.offset = Vec3(offsets.data[3 * j], offsets.data[3 * j + 1], offsets.data[3 * j + 2]);
        joint.axis = Quat(axes.data[4 * j], axes.data[4 * j + 1], axes.data[4 * j + 2], axes.data[4 * j + 3]);
        const double norm = joint.axis.norm();
        if (!(std::abs(norm - 1.0) < 1e-6))
            throw StoreError(
                fname, g + "/joint_axis",
                "joint " + std::to_string(j) + ": expected a unit quaternion, found norm " + std::to_string(norm));
        const auto order = euler_order_from_string(orders[j]);
        if (!order)
            throw StoreError(
                fname, g + "/joint_rotation_order",
                "joint " + std::to_string(j) + ": expected XYZ, XZY, YXZ, YZX, ZXY or ZYX, found '" + orders[j] + "'");
        joint.rotation_order = *order;
        if (end_sites.data[j] > 1)
            throw StoreError(
                fname, g + "/joint_end_site",
                "joint " + std::to_string(j) + ": expected 0 or 1, found " + std::to_string(end_sites.data[j]));
        joint.end_site = end_sites.data[j] == 1;
    }
    std::int32_t previous = 0;
    for (std::size_t c = 0; c < channel_joint.data.size(); ++c) {
        const std::int32_t j = channel_joint.data[c];
        if (j < previous || j < 0 || static_cast<std::uint64_t>(j) >= n)
            throw StoreError(fname, g + "/channel_joint",
                             "channel " + std::to_string(c) + ": expected a joint index in [" +
                                 std::to_string(previous) + ", " + count_text(n) + ") (non-decreasing), found " +
                                 std::to_string(j));
        previous = j;
        const auto type = channel_type_from_string(channel_type[c]);
        if (!type)
            throw StoreError(fname, g + "/channel_type",
                             "channel " + std::to_string(c) +
                                 ": expected Xposition, Yposition, Zposition, Xrotation, "
                                 "Yrotation or Zrotation, found '" +
                                 channel_type[c] + "'");
        joints[static_cast<std::size_t>(j)].channels.push_back(*type);
    }

    SourceUnits units;
    units.cm_per_unit = file.read_double_attribute(g, "cm_per_unit");
    if (!(units.cm_per_unit > 0.0) || !std::isfinite(units.cm_per_unit))
        throw StoreError(
            fname, g,
            "attribute 'cm_per_unit': expected a positive number, found " + std::to_string(units.cm_per_unit));
    const std::string angles = file.read_string_attribute(g, "source_angles");
    if (angles != "deg" && angles != "rad")
        throw StoreError(fname, g, "attribute 'source_angles': expected \"deg\" or \"rad\", found \"" + angles + "\"");
    units.degrees = angles == "deg";
    const auto forward = file.read_doubles_attribute(g, "forward");
    if (forward.size() != 3)
        throw StoreError(fname, g, "attribute 'forward': expected 3 values, found " + std::to_string(forward.size()));
    // Formats 1 and 2 have no such attribute: their position channels add to the offset.
    PositionChannels positions = PositionChannels::add_to_offset;
    if (file.has_attribute(g, "position_channels")) {
        const std::string text = file.read_string_attribute(g, "position_channels");
        const auto mode = position_channels_from_string(text);
        if (!mode)
            throw StoreError(
                fname, g,
                "attribute 'position_channels': expected \"replace_offset\" or \"add_to_offset\", found \"" + text +
                    "\"");
        positions = *mode;
    }
    std::int64_t motion_root = 0;  // formats 1 and 2: joint 0
    if (file.has_attribute(g, "motion_root")) {
        motion_root = file.read_int_attribute(g, "motion_root");
        if (motion_root < 0 || static_cast<std::uint64_t>(motion_root) >= n)
            throw StoreError(fname, g,
                             "attribute 'motion_root': expected a joint index in [0, " + count_text(n) + "), found " +
                                 std::to_string(motion_root));
    }
    try {
        return Skeleton(std::move(joints), units, Vec3(forward[0], forward[1], forward[2]), positions,
                        static_cast<std::size_t>(motion_root));
    } catch (const InvalidArgument& e) {
        throw StoreError(fname, g, std::string("invalid skeleton: ") + e.what());
    }
}

}  // namespace mocapdb::store
