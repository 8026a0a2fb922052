#include "clip_options.hpp"

#include <ostream>

namespace mocapdb::cli {

ClipReadOptions ClipOptions::to_read_options() const {
    ClipReadOptions o;
    o.asf = asf;
    if (fps > 0.0) o.frame_rate = fps;
    o.strict = strict;
    return o;
}

void add_clip_options(CLI::App& command, ClipOptions& options) {
    command.add_option("--asf", options.asf, "ASF skeleton of an AMC clip (default: NN.asf beside NN_MM.amc)")
        ->check(CLI::ExistingFile);
    command.add_option("--fps", options.fps, "frame rate override in Hz (AMC default 120; BVH: its Frame Time)")
        ->check(CLI::PositiveNumber);
    command.add_flag("--strict", options.strict, "refuse file defects instead of working around them");
}

Clip load_clip(const std::string& path, const ClipOptions& options, std::ostream& warnings) {
    Warnings found;
    Clip clip = read_clip(path, options.to_read_options(), &found);
    for (const Warning& w : found) warnings << "mocapdb: warning: " << w.to_string() << "\n";
    return clip;
}

}  // namespace mocapdb::cli
