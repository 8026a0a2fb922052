#pragma once
// Command-line options shared by the subcommands that read a clip file.
#include <CLI/CLI.hpp>
#include <iosfwd>
#include <string>

#include "mocapdb/io/clip_file.hpp"

namespace mocapdb::cli {

struct ClipOptions {
    std::string asf;
    double fps = 0.0;  // 0: not given
    bool strict = false;
    std::string bvh_positions = "replace";

    ClipReadOptions to_read_options() const;
};

/// Checks an --fps value: a number in (0, kMaxFrameRate] Hz (motion/clip.hpp), else a one-line error
/// naming the value (never CLI11's PositiveNumber range of 309 digits).
CLI::Validator frame_rate_check();

/// Adds --asf, --fps, --strict and --bvh-positions to `command`.
void add_clip_options(CLI::App& command, ClipOptions& options);

/// Adds --bvh-positions replace|add (stored in `value`) to `command`.
void add_bvh_positions_option(CLI::App& command, std::string& value);
/// "replace" or "add" (as checked by the option) to the reader's convention.
PositionChannels bvh_positions_from_option(const std::string& value);

/// Reads the clip and prints the reader's warnings to `warnings` (stderr), one per line.
Clip load_clip(const std::string& path, const ClipOptions& options, std::ostream& warnings);

}  // namespace mocapdb::cli
