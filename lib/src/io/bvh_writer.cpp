#include <charconv>
#include <ostream>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb {
namespace {

// Appends `value` with `precision` significant digits, shortest form, locale-independent.
void append_number(std::string& out, double value, int precision) {
    if (value == 0.0) value = 0.0;  // no "-0"
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, precision);
    out.append(buffer, result.ptr);
}

class BvhWriter {
public:
    BvhWriter(const Clip& clip, const BvhWriteOptions& options) : clip_(clip), options_(options) {}

    void write(std::ostream& os) {
        const Skeleton& s = *clip_.skeleton;
        children_.assign(s.size(), {});
        for (std::size_t j = 1; j < s.size(); ++j) children_[static_cast<std::size_t>(s.joint(j).parent)].push_back(j);
        out_ = "HIERARCHY\n";
        write_joint(0, 0);
        out_ += "MOTION\nFrames: " + std::to_string(clip_.frame_count()) + "\nFrame Time: ";
        append_number(out_, 1.0 / clip_.frame_rate, 17);
        out_ += "\n";
        os << out_;
        write_rows(os);
    }

private:
    void indent(int depth) { out_.append(static_cast<std::size_t>(depth), '\t'); }

    void write_offset(const Vec3& offset) {
        out_ += "OFFSET";
        for (int a = 0; a < 3; ++a) {
            out_ += ' ';
            append_number(out_, offset[a] / options_.cm_per_unit, options_.precision);
        }
        out_ += '\n';
    }

    void write_joint(std::size_t j, int depth) {
        const Joint& joint = clip_.skeleton->joint(j);
        indent(depth);
        if (joint.end_site) {
            out_ += "End Site\n";
        } else {
            out_ += (j == 0 ? "ROOT " : "JOINT ") + joint.name + "\n";
        }
        indent(depth);
        out_ += "{\n";
        indent(depth + 1);
        write_offset(joint.offset);
        if (!joint.end_site) {
            indent(depth + 1);
            out_ += "CHANNELS " + std::to_string(joint.channels.size());
            for (ChannelType c : joint.channels) out_ += " " + to_string(c);
            out_ += '\n';
        }
        for (std::size_t c : children_[j]) write_joint(c, depth + 1);
        indent(depth);
        out_ += "}\n";
    }

    void write_rows(std::ostream& os) {
        const Skeleton& s = *clip_.skeleton;
        std::vector<double> scale(s.channel_count());
        for (std::size_t j = 0; j < s.size(); ++j)
            for (std::size_t k = 0; k < s.joint(j).channels.size(); ++k)
                scale[s.first_channel(j) + k] =
                    is_rotation(s.joint(j).channels[k]) ? 180.0 / kPi : 1.0 / options_.cm_per_unit;
        std::string line;
        for (std::size_t f = 0; f < clip_.frame_count(); ++f) {
            line.clear();
            const double* row = clip_.frame(f);
            for (std::size_t c = 0; c < scale.size(); ++c) {
                if (c) line += ' ';
                append_number(line, row[c] * scale[c], options_.precision);
            }
            line += '\n';
            os << line;
        }
    }

    const Clip& clip_;
    const BvhWriteOptions& options_;
    std::vector<std::vector<std::size_t>> children_;
    std::string out_;
};

bool joint_is_bvh_compatible(const Joint& joint) {
    if (joint.end_site) return true;
    if (angle_between(joint.axis, Quat::Identity()) > 1e-12) return false;
    // Joints without rotation channels (CMU's hip joints) get three zero channels: not every BVH
    // importer accepts "CHANNELS 0".
    bool rotates = false;
    for (ChannelType c : joint.channels) rotates = rotates || is_rotation(c);
    if (!rotates) return false;
    // The listed rotation channels must follow the composition order.
    const auto order = axes_of(joint.rotation_order);
    std::size_t next = 0;
    for (ChannelType c : joint.channels) {
        if (!is_rotation(c)) continue;
        while (next < 3 && order[next] != channel_axis(c)) ++next;
        if (next == 3) return false;
        ++next;
    }
    return true;
}

// BVH position channels replace OFFSET (see PositionChannels): a skeleton whose channels add to a
// non-zero offset component must be rewritten.
bool positions_are_bvh_compatible(const Skeleton& s, std::size_t j) {
    if (s.position_channels() == PositionChannels::replace_offset) return true;
    for (int a = 0; a < 3; ++a)
        if (s.channel_column(j, static_cast<ChannelType>(a)) >= 0 && s.joint(j).offset[a] != 0.0) return false;
    return true;
}

}  // namespace

bool is_bvh_compatible(const Skeleton& skeleton) {
    for (std::size_t j = 0; j < skeleton.size(); ++j)
        if (!joint_is_bvh_compatible(skeleton.joint(j)) || !positions_are_bvh_compatible(skeleton, j)) return false;
    return true;
}

Clip to_bvh_channels(const Clip& clip, EulerOrder order) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    std::vector<Joint> joints = s.joints();
    std::vector<bool> convert(s.size(), false);
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (joint_is_bvh_compatible(s.joint(j))) continue;
        convert[j] = true;
        Joint& joint = joints[j];
        std::vector<ChannelType> channels;
        for (ChannelType c : joint.channels)
            if (!is_rotation(c)) channels.push_back(c);
        for (Axis a : axes_of(order)) channels.push_back(static_cast<ChannelType>(3 + static_cast<int>(a)));
        joint.channels = channels;
        joint.rotation_order = order;
        joint.axis = Quat::Identity();
    }
    Clip out;
    out.name = clip.name;
    out.frame_rate = clip.frame_rate;
    auto skeleton = std::make_shared<const Skeleton>(joints, s.source_units(), s.forward(),
                                                     PositionChannels::replace_offset, s.motion_root());
    const Skeleton& t = *skeleton;
    out.skeleton = skeleton;
    out.channels = FrameMatrix::Zero(clip.channels.rows(), static_cast<Eigen::Index>(t.channel_count()));
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const double* row = clip.frame(f);
        double* dst = out.channels.row(static_cast<Eigen::Index>(f)).data();
        for (std::size_t j = 0; j < s.size(); ++j) {
            const Joint& old_joint = s.joint(j);
            for (std::size_t k = 0; k < old_joint.channels.size(); ++k) {
                const ChannelType c = old_joint.channels[k];
                if (convert[j] && is_rotation(c)) continue;
                double value = row[s.first_channel(j) + k];
                if (!is_rotation(c) && s.position_channels() == PositionChannels::add_to_offset)
                    value += old_joint.offset[static_cast<int>(channel_axis(c))];
                dst[t.channel_column(j, c)] = value;
            }
            if (!convert[j]) continue;
            Vec3 near = Vec3::Zero();
            const auto ax = axes_of(order);
            int cols[3];
            for (int k = 0; k < 3; ++k) {
                cols[k] = t.channel_column(j, static_cast<ChannelType>(3 + static_cast<int>(ax[k])));
                if (f > 0) near[k] = out.channels(static_cast<Eigen::Index>(f - 1), cols[k]);
            }
            const Vec3 angles = matrix_to_euler_near(s.local_rotation(j, row).toRotationMatrix(), order, near);
            for (int k = 0; k < 3; ++k) dst[cols[k]] = angles[k];
        }
    }
    return out;
}

void write_bvh(std::ostream& out, const Clip& clip, const BvhWriteOptions& options) {
    validate(clip);
    if (options.precision < 1 || options.precision > 17)
        throw InvalidArgument("BVH write options: precision must be 1..17 significant digits");
    if (!(options.cm_per_unit > 0.0)) throw InvalidArgument("BVH write options: cm_per_unit must be positive");
    if (!is_bvh_compatible(*clip.skeleton)) {
        BvhWriter(to_bvh_channels(clip), options).write(out);
        return;
    }
    BvhWriter(clip, options).write(out);
    if (!out) throw IoError("writing BVH '" + clip.name + "' failed");
}

void write_bvh(const std::filesystem::path& path, const Clip& clip, const BvhWriteOptions& options) {
    write_file_atomically(path, [&](std::ostream& os) { write_bvh(os, clip, options); });
}

}  // namespace mocapdb
