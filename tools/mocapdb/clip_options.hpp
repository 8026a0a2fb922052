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

    ClipReadOptions to_read_options() const;
};

/// Adds --asf, --fps and --strict to `command`.
void add_clip_options(CLI::App& command, ClipOptions& options);

/// Reads the clip and prints the reader's warnings to `warnings` (stderr), one per line.
Clip load_clip(const std::string& path, const ClipOptions& options, std::ostream& warnings);

}  // namespace mocapdb::cli
