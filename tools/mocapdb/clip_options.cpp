#include "clip_options.hpp"

#include <cstdlib>
#include <ostream>

#include "mocapdb/io/frame_rate.hpp"

namespace mocapdb::cli {

ClipReadOptions ClipOptions::to_read_options() const {
    ClipReadOptions o;
    o.asf = asf;
    if (fps > 0.0) o.frame_rate = fps;
    o.strict = strict;
    o.bvh_positions = bvh_positions_from_option(bvh_positions);
    return o;
}

CLI::Validator frame_rate_check() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            char* end = nullptr;
            const double rate = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0') return "expected a frame rate in Hz, got '" + text + "'";
            return frame_rate_problem(rate);
        },
        "HZ");
}

void add_bvh_positions_option(CLI::App& command, std::string& value) {
    command
        .add_option("--bvh-positions", value,
                    "BVH position channels: 'replace' = the joint's local translation, replacing OFFSET (Blender, "
                    "MotionBuilder; default), 'add' = added to OFFSET")
        ->check(CLI::IsMember({"replace", "add"}));
}

PositionChannels bvh_positions_from_option(const std::string& value) {
    return value == "add" ? PositionChannels::add_to_offset : PositionChannels::replace_offset;
}

void add_clip_options(CLI::App& command, ClipOptions& options) {
    command.add_option("--asf", options.asf, "ASF skeleton of an AMC clip (default: NN.asf beside NN_MM.amc)")
        ->check(CLI::ExistingFile);
    command.add_option("--fps", options.fps, "frame rate override in Hz (AMC default 120; BVH: its Frame Time)")
        ->check(frame_rate_check());
    command.add_flag("--strict", options.strict, "refuse file defects instead of working around them");
    add_bvh_positions_option(command, options.bvh_positions);
}

Clip load_clip(const std::string& path, const ClipOptions& options, std::ostream& warnings) {
    Warnings found;
    Clip clip = read_clip(path, options.to_read_options(), &found);
    for (const Warning& w : found) warnings << "mocapdb: warning: " << w.to_string() << "\n";
    return clip;
}

}  // namespace mocapdb::cli
