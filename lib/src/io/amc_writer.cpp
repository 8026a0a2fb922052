// Skeleton -> ASF and Clip -> AMC (mapping and number policy in mocapdb/io/amc_writer.hpp).
#include "mocapdb/io/amc_writer.hpp"

#include <array>
#include <charconv>
#include <ostream>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb {
namespace {

constexpr double kOffsetTolerance = 1e-9;  // cm

// Skeleton numbers: 15 significant digits (a relative error below 1e-15, far inside the 1e-9 of
// Skeleton::same_structure) print the source file's own numbers back, e.g. 0.45 not 0.44999999999999996.
void append_exact(std::string& out, double value) {
    if (value == 0.0) value = 0.0;
    char buffer[64];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 15);
    out.append(buffer, r.ptr);
}

void append_digits(std::string& out, double value, int precision) {
    if (value == 0.0) value = 0.0;
    char buffer[64];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, precision);
    out.append(buffer, r.ptr);
}

/// The Joint::rotation_order the ASF reader gives a joint with these channels: the rotation axes
/// listed last-to-first, then the unlisted axes in X, Y, Z order.
EulerOrder asf_composition(const std::vector<ChannelType>& channels) {
    std::array<Axis, 3> out{};
    bool used[3] = {};
    std::size_t n = 0;
    for (auto it = channels.rbegin(); it != channels.rend(); ++it) {
        if (!is_rotation(*it)) continue;
        const Axis a = channel_axis(*it);
        out[n++] = a;
        used[static_cast<int>(a)] = true;
    }
    for (int a = 0; a < 3; ++a)
        if (!used[a]) out[n++] = static_cast<Axis>(a);
    return *euler_order_from_axes(out[0], out[1], out[2]);
}

const char* dof_name(ChannelType c) {
    static constexpr const char* names[] = {"tx", "ty", "tz", "rx", "ry", "rz"};
    return names[static_cast<int>(c)];
}
const char* root_dof_name(ChannelType c) {
    static constexpr const char* names[] = {"TX", "TY", "TZ", "RX", "RY", "RZ"};
    return names[static_cast<int>(c)];
}

struct BoneLayout {
    std::vector<std::vector<std::size_t>> bone_children;  // per joint: children that are bones
    std::vector<Vec3> vector;                             // per bone joint: the bone vector, cm
};

std::string check_and_layout(const Skeleton& s, BoneLayout* out) {
    const std::size_t n = s.size();
    BoneLayout layout;
    layout.bone_children.assign(n, {});
    layout.vector.assign(n, Vec3::Zero());
    std::vector<std::vector<std::size_t>> end_children(n);
    const Joint& root = s.joint(0);
    if (root.name != "root") return "joint 0 is '" + root.name + "', expected 'root'";
    if (root.end_site) return "the root is an end site";
    if (root.rotation_order != asf_composition(root.channels))
        return "the root's rotation order " + to_string(root.rotation_order) +
               " is not the ASF composition of its channels";
    for (std::size_t j = 1; j < n; ++j) {
        const Joint& joint = s.joint(j);
        const auto parent = static_cast<std::size_t>(joint.parent);
        const std::string who = "joint '" + joint.name + "'";
        if (joint.end_site) {
            if (parent == 0) return who + ": an end site on the root";
            end_children[parent].push_back(j);
            if (joint.name != s.joint(parent).name + "_end")
                return who + ": an end site must be named '" + s.joint(parent).name + "_end'";
            continue;
        }
        if (joint.name == "root" || joint.name.empty() || joint.name.find_first_of(" \t\r\n#") != std::string::npos)
            return who + ": not usable as an ASF bone name";
        layout.bone_children[parent].push_back(j);
        if (joint.rotation_order != asf_composition(joint.channels))
            return who + ": rotation order " + to_string(joint.rotation_order) +
                   " is not the ASF composition of its channels";
        bool translates = false;
        for (ChannelType c : joint.channels) translates = translates || !is_rotation(c);
        if (translates && angle_between(joint.axis, Quat::Identity()) > 1e-12)
            return who + ": translation channels on a bone with a non-identity axis";
        if (parent == 0 && joint.offset.norm() > kOffsetTolerance)
            return who + ": a bone on the root must start at the root (zero offset)";
    }
    for (std::size_t j = 1; j < n; ++j) {
        const Joint& joint = s.joint(j);
        if (joint.end_site) continue;
        const std::string who = "bone '" + joint.name + "'";
        const auto& bones = layout.bone_children[j];
        const auto& ends = end_children[j];
        if (bones.empty()) {
            if (ends.size() != 1) return who + ": a leaf bone needs exactly one end site '" + joint.name + "_end'";
            layout.vector[j] = s.joint(ends.front()).offset;
            continue;
        }
        if (!ends.empty()) return who + ": has both child bones and an end site";
        layout.vector[j] = s.joint(bones.front()).offset;
        for (std::size_t c : bones)
            if ((s.joint(c).offset - layout.vector[j]).norm() > kOffsetTolerance)
                return who + ": its children start at different points ('" + s.joint(bones.front()).name + "' and '" +
                       s.joint(c).name + "')";
    }
    if (out) *out = std::move(layout);
    return {};
}

/// ASF axis angles (about X, Y, Z, written order XYZ: C = Rz(c)·Ry(b)·Rx(a)), in the source unit.
Vec3 axis_angles(const Quat& axis, double angle_scale) {
    const Vec3 zyx = matrix_to_euler(axis.normalized().toRotationMatrix(), EulerOrder::ZYX);
    return Vec3(zyx[2], zyx[1], zyx[0]) * angle_scale;
}

void append_vec(std::string& out, const Vec3& v) {
    for (int a = 0; a < 3; ++a) {
        out += ' ';
        append_exact(out, v[a]);
    }
}

}  // namespace

std::string asf_incompatibility(const Skeleton& skeleton) { return check_and_layout(skeleton, nullptr); }

void write_asf(std::ostream& out, const Skeleton& s, const AsfWriteOptions& options) {
    BoneLayout layout;
    if (const std::string why = check_and_layout(s, &layout); !why.empty())
        throw InvalidArgument("cannot write the skeleton as ASF: " + why);
    const double cm = s.source_units().cm_per_unit;
    const double angle_scale = s.source_units().degrees ? 180.0 / kPi : 1.0;
    std::string t = ":version 1.10\n:name " + options.name + "\n:units\n  mass 1.0\n  length ";
    append_exact(t, 2.54 / cm);
    t += std::string("\n  angle ") + (s.source_units().degrees ? "deg" : "rad") + "\n";
    t += ":documentation\n  written by mocapdb\n:root\n  order";
    const Joint& root = s.joint(0);
    for (ChannelType c : root.channels) t += std::string(" ") + root_dof_name(c);
    t += "\n  axis XYZ\n  position";
    append_vec(t, root.offset / cm);
    t += "\n  orientation";
    append_vec(t, axis_angles(root.axis, angle_scale));
    t += "\n:bonedata\n";
    int id = 1;
    for (std::size_t j = 1; j < s.size(); ++j) {
        const Joint& joint = s.joint(j);
        if (joint.end_site) continue;
        const Vec3& v = layout.vector[j];
        const double length = v.norm();
        t += "  begin\n    id " + std::to_string(id++) + "\n    name " + joint.name + "\n    direction";
        append_vec(t, length > 0.0 ? Vec3(v / length) : Vec3(Vec3::Zero()));
        t += "\n    length ";
        append_exact(t, length / cm);
        t += "\n    axis";
        append_vec(t, axis_angles(joint.axis, angle_scale));
        t += " XYZ\n";
        if (!joint.channels.empty()) {
            t += "    dof";
            for (ChannelType c : joint.channels) t += std::string(" ") + dof_name(c);
            t += "\n";
        }
        t += "  end\n";
    }
    t += ":hierarchy\n  begin\n";
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (layout.bone_children[j].empty()) continue;
        t += "    " + s.joint(j).name;
        for (std::size_t c : layout.bone_children[j]) t += " " + s.joint(c).name;
        t += "\n";
    }
    t += "  end\n";
    out << t;
    if (!out) throw IoError("writing ASF failed");
}

void write_asf(const std::filesystem::path& path, const Skeleton& skeleton, const AsfWriteOptions& options) {
    if (const std::string why = asf_incompatibility(skeleton); !why.empty())
        throw InvalidArgument(path.string() + ": cannot write the skeleton as ASF: " + why);
    write_file_atomically(path, [&](std::ostream& os) { write_asf(os, skeleton, options); });
}

void write_amc(std::ostream& out, const Clip& clip, const AmcWriteOptions& options) {
    validate(clip);
    if (options.precision < 1 || options.precision > 17)
        throw InvalidArgument("AMC write options: precision must be 1..17 significant digits");
    const Skeleton& s = *clip.skeleton;
    if (const std::string why = asf_incompatibility(s); !why.empty())
        throw InvalidArgument("cannot write '" + clip.name + "' as AMC: " + why + " (export it as BVH instead)");
    const bool degrees = s.source_units().degrees;
    std::vector<double> scale(s.channel_count());
    for (std::size_t j = 0; j < s.size(); ++j)
        for (std::size_t k = 0; k < s.joint(j).channels.size(); ++k)
            scale[s.first_channel(j) + k] = is_rotation(s.joint(j).channels[k]) ? (degrees ? 180.0 / kPi : 1.0)
                                                                                : 1.0 / s.source_units().cm_per_unit;
    std::string header = "#!OML:ASF " + (options.asf_name.empty() ? std::string("skeleton.asf") : options.asf_name) +
                         "\n:FULLY-SPECIFIED\n" + (degrees ? ":DEGREES\n" : ":RADIANS\n");
    out << header;
    std::string block;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        block = std::to_string(f + 1) + "\n";
        const double* row = clip.frame(f);
        for (std::size_t j = 0; j < s.size(); ++j) {
            const Joint& joint = s.joint(j);
            if (joint.end_site || joint.channels.empty()) continue;
            block += joint.name;
            const std::size_t first = s.first_channel(j);
            for (std::size_t k = 0; k < joint.channels.size(); ++k) {
                block += ' ';
                append_digits(block, row[first + k] * scale[first + k], options.precision);
            }
            block += '\n';
        }
        out << block;
    }
    if (!out) throw IoError("writing AMC '" + clip.name + "' failed");
}

void write_amc(const std::filesystem::path& path, const Clip& clip, const AmcWriteOptions& options) {
    validate(clip);
    if (const std::string why = asf_incompatibility(*clip.skeleton); !why.empty())
        throw InvalidArgument(path.string() + ": cannot write '" + clip.name + "' as AMC: " + why +
                              " (export it as BVH instead)");
    write_file_atomically(path, [&](std::ostream& os) { write_amc(os, clip, options); });
}

}  // namespace mocapdb
