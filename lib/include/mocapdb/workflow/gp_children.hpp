#pragma once
// The children of `mocapdb gp`: the samples of a stored motion set (their frames with the
// set's dropout repairs, named "CLIP:BEGIN-END") or clip files (named by their file stem), as clips
// ready for gp::prepare_motion_data. Nothing is printed.
// Errors: IoError / FormatError from the database, IoError / ParseError from the clip files.
// Threads: opens the database read-only for the call.
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb::workflow {

struct GpChildren {
    std::vector<Clip> clips;
    std::vector<std::string> names;
};

/// The samples of set `set` of the database at `db`, in the set's order.
GpChildren set_children(const std::filesystem::path& db, const std::string& set);

/// Clip files (BVH, or AMC with the ASF beside it); `frame_rate` > 0 overrides the files' rate.
GpChildren clip_file_children(const std::vector<std::string>& paths, double frame_rate);

}  // namespace mocapdb::workflow
