// BVH reader. Policy for real-world defects: a non-strict read works around what it can and says so
// in a warning (fewer rows than "Frames:" declares, a partial last row); strict mode refuses them.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/frame_rate.hpp"
#include "mocapdb/io/text_file.hpp"
#include "text_scanner.hpp"

namespace mocapdb {
namespace {

using detail::quoted;
using detail::TextScanner;

constexpr std::size_t kMaxJoints = 10000;
constexpr int kMaxDepth = 1000;

class BvhParser {
public:
    BvhParser(std::string_view text, const std::string& name, const BvhReadOptions& options, Warnings* warnings)
        : in_(text, name), options_(options), warnings_(warnings) {}

    Clip parse() {
        if (!(options_.cm_per_unit > 0.0 && std::isfinite(options_.cm_per_unit)))
            throw InvalidArgument("BVH read options: cm_per_unit must be positive and finite");
        if (options_.frame_rate) check_frame_rate(*options_.frame_rate, "BVH read options");
        in_.expect("HIERARCHY");
        in_.expect("ROOT");
        parse_joint(-1, 0);
        if (in_.peek_token() == "ROOT")
            in_.fail("a second ROOT is not supported (one skeleton per file); found another ROOT");
        in_.expect("MOTION");
        Clip clip;
        clip.name = std::filesystem::path(in_.source_name()).stem().string();
        clip.skeleton = std::make_shared<const Skeleton>(build_skeleton());
        parse_motion(clip);
        // A static ROOT above the body (exported rigs' "Reference"): its only child carries the motion.
        const std::size_t motion_root = find_motion_root(*clip.skeleton, clip.channels);
        if (motion_root != 0)
            clip.skeleton = std::make_shared<const Skeleton>(clip.skeleton->with_motion_root(motion_root));
        return clip;
    }

private:
    std::string joint_name() {
        std::string_view name = in_.rest_of_line();
        if (name.empty()) in_.fail("expected a joint name after ROOT/JOINT");
        return std::string(name);
    }

    void parse_joint(int parent, int depth) {
        if (depth > kMaxDepth) in_.fail("hierarchy nested deeper than " + std::to_string(kMaxDepth) + " levels");
        if (joints_.size() >= kMaxJoints) in_.fail("more than " + std::to_string(kMaxJoints) + " joints");
        Joint joint;
        joint.parent = parent;
        joint.name = joint_name();
        const std::size_t name_line = in_.line() - 1;
        const int index = static_cast<int>(joints_.size());
        joints_.push_back(joint);
        names_line_.push_back(name_line);
        in_.expect("{");
        in_.expect("OFFSET");
        Vec3 offset;
        for (int a = 0; a < 3; ++a) offset[a] = in_.number("OFFSET component") * options_.cm_per_unit;
        joints_[index].offset = offset;
        if (in_.peek_token() == "CHANNELS") {
            in_.token();
            parse_channels(joints_[index]);
        }
        for (;;) {
            const std::string_view t = in_.token();
            if (t == "}") break;
            if (t == "JOINT") {
                parse_joint(index, depth + 1);
            } else if (t == "End") {
                in_.expect("Site");
                parse_end_site(index);
            } else {
                in_.fail_at_token("expected JOINT, End Site or '}' in joint '" + joints_[index].name + "', found " +
                                  (t.empty() ? std::string("end of file") : quoted(t)));
            }
        }
    }

    void parse_channels(Joint& joint) {
        const long long n = in_.integer("channel count");
        if (n > 6)
            in_.fail_at_token("joint '" + joint.name + "' declares " + std::to_string(n) +
                              " channels, at most 6 allowed");
        std::vector<Axis> rotation_axes;
        for (long long i = 0; i < n; ++i) {
            const std::string_view t = in_.token();
            const auto type = channel_type_from_string(t);
            if (!type)
                in_.fail_at_token(
                    "expected a channel name (Xposition, Yposition, Zposition, Xrotation, Yrotation, "
                    "Zrotation) for joint '" +
                    joint.name + "', found " + (t.empty() ? std::string("end of file") : quoted(t)));
            for (ChannelType c : joint.channels)
                if (c == *type)
                    in_.fail_at_token("joint '" + joint.name + "' lists channel " + std::string(t) + " twice");
            joint.channels.push_back(*type);
            if (is_rotation(*type)) rotation_axes.push_back(channel_axis(*type));
        }
        // Rotation channels compose in the order listed; absent axes (angle 0) go last.
        for (Axis a : {Axis::X, Axis::Y, Axis::Z}) {
            bool present = false;
            for (Axis b : rotation_axes) present = present || a == b;
            if (!present) rotation_axes.push_back(a);
        }
        joint.rotation_order = *euler_order_from_axes(rotation_axes[0], rotation_axes[1], rotation_axes[2]);
    }

    void parse_end_site(int parent) {
        Joint site;
        site.parent = parent;
        site.end_site = true;
        site.name = unique_end_name(joints_[parent].name);
        in_.expect("{");
        in_.expect("OFFSET");
        for (int a = 0; a < 3; ++a) site.offset[a] = in_.number("End Site OFFSET component") * options_.cm_per_unit;
        in_.expect("}");
        if (joints_.size() >= kMaxJoints) in_.fail("more than " + std::to_string(kMaxJoints) + " joints");
        joints_.push_back(site);
        names_line_.push_back(in_.line());
    }

    std::string unique_end_name(const std::string& parent) const {
        std::string name = parent + "_end";
        for (int k = 2; taken(name); ++k) name = parent + "_end" + std::to_string(k);
        return name;
    }

    bool taken(const std::string& name) const {
        for (const Joint& j : joints_)
            if (j.name == name) return true;
        return false;
    }

    Skeleton build_skeleton() {
        // Skeleton validates; re-throw its complaint located at the offending joint's line.
        for (std::size_t i = 0; i < joints_.size(); ++i)
            for (std::size_t k = 0; k < i; ++k)
                if (joints_[i].name == joints_[k].name)
                    throw ParseError(in_.source_name(), names_line_[i], 0,
                                     "duplicate joint name '" + joints_[i].name + "' (first on line " +
                                         std::to_string(names_line_[k]) + ")");
        try {
            return Skeleton(joints_, SourceUnits{options_.cm_per_unit, true}, Vec3::UnitZ(),
                            options_.position_channels);
        } catch (const InvalidArgument& e) {
            throw ParseError(in_.source_name(), 0, 0, e.what());
        }
    }

    void warn(std::size_t line, const std::string& message) {
        if (warnings_) warnings_->push_back(Warning{in_.source_name(), line, message});
    }

    void parse_motion(Clip& clip) {
        in_.expect("Frames:");
        const long long declared = in_.integer("frame count");
        in_.expect("Frame");
        in_.expect("Time:");
        const double frame_time = in_.number("frame time (seconds)");
        if (options_.frame_rate) {
            clip.frame_rate = *options_.frame_rate;
            // An override that disagrees with the header by more than 1 % is most likely a mistake
            // (everything then plays too fast or too slow), unless the header is known to be wrong: say so.
            const double header_rate = frame_time > 0.0 ? 1.0 / frame_time : 0.0;
            if (header_rate > 0.0 && std::abs(clip.frame_rate - header_rate) > 0.01 * header_rate) {
                char text[200];
                std::snprintf(text, sizeof text,
                              "the frame rate given, %g Hz, differs from the file's Frame Time %g s (%g Hz) by "
                              "%.0f %%; the given rate is used",
                              clip.frame_rate, frame_time, header_rate,
                              100.0 * std::abs(clip.frame_rate - header_rate) / header_rate);
                warn(in_.line(), text);
            }
        } else {
            if (!(frame_time > 0.0))
                in_.fail_at_token("Frame Time must be positive, found " + std::to_string(frame_time) +
                                  " (the caller can override the frame rate)");
            clip.frame_rate = 1.0 / frame_time;
        }
        in_.next_line();

        const Skeleton& s = *clip.skeleton;
        const std::size_t width = s.channel_count();
        // Per column: scale from file units to internal units.
        std::vector<double> scale(width);
        for (std::size_t j = 0; j < s.size(); ++j)
            for (std::size_t k = 0; k < s.joint(j).channels.size(); ++k)
                scale[s.first_channel(j) + k] =
                    is_rotation(s.joint(j).channels[k]) ? kPi / 180.0 : options_.cm_per_unit;

        const std::size_t reserve = static_cast<std::size_t>(std::min<long long>(declared, 1000000));
        std::vector<double> values;
        values.reserve(reserve * width);
        std::size_t rows = 0;
        while (!in_.at_end()) {
            if (rows == static_cast<std::size_t>(declared)) {
                const std::size_t line = in_.line();
                if (options_.strict)
                    in_.fail("more data rows than the " + std::to_string(declared) + " declared by 'Frames:'");
                warn(line, "data rows beyond the " + std::to_string(declared) + " declared by 'Frames:' were ignored");
                break;
            }
            const std::size_t line = in_.line();
            std::size_t count = 0;
            while (!in_.at_line_end()) {
                const double v = in_.number_on_line("channel value");
                if (count < width) values.push_back(v * scale[count]);
                ++count;
            }
            if (count != width) {
                values.resize(rows * width);
                const bool last = in_.at_end();
                const std::string what = "frame " + std::to_string(rows + 1) + " has " + std::to_string(count) +
                                         " values, expected " + std::to_string(width) + " (one per channel)";
                if (!last || options_.strict || count > width) throw ParseError(in_.source_name(), line, 0, what);
                warn(line, what + "; the truncated last frame was dropped");
                break;
            }
            ++rows;
            in_.next_line();
        }
        if (rows < static_cast<std::size_t>(declared)) {
            const std::string what = "'Frames:' declares " + std::to_string(declared) + " frames but " +
                                     std::to_string(rows) + " data rows are present";
            if (options_.strict || rows == 0) in_.fail(what);
            warn(0, what + "; using the " + std::to_string(rows) + " present");
        }
        clip.channels = Eigen::Map<const FrameMatrix>(values.data(), static_cast<Eigen::Index>(rows),
                                                      static_cast<Eigen::Index>(width));
    }

    TextScanner in_;
    const BvhReadOptions& options_;
    Warnings* warnings_;
    std::vector<Joint> joints_;
    std::vector<std::size_t> names_line_;
};

}  // namespace

Clip parse_bvh(std::string_view text, const std::string& source_name, const BvhReadOptions& options,
               Warnings* out_warnings) {
    return BvhParser(text, source_name, options, out_warnings).parse();
}

Clip read_bvh(const std::filesystem::path& path, const BvhReadOptions& options, Warnings* out_warnings) {
    return parse_bvh(read_text_file(path), path.string(), options, out_warnings);
}

}  // namespace mocapdb
