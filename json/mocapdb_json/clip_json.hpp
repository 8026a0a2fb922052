#pragma once
// The documents of clip files: `mocapdb info CLIP --json` (skeleton, frames, rate, channels) and
// `mocapdb generate ... --json` (the procedural set's files and parameters). Formatting only; no I/O.
// Keys: docs/json.md.
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/motion/clip.hpp"
#include "mocapdb/procedural/parametric_set.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

/// `file`: the path as given; figure_height_cm is null for a clip without frames.
void write_clip_info(JsonWriter& j, const std::string& file, const Clip& clip);
/// `paths`: the files write_parametric_set wrote (one per clip, then params.csv).
void write_generated_set(JsonWriter& j, const std::string& folder, const procedural::ParametricSet& set,
                         const std::vector<std::filesystem::path>& paths);

}  // namespace mocapdb::json
