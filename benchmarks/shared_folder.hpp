#pragma once
// The clips of a shared CMU folder (../shared/datasets/NAME), read for a benchmark.
#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/io/clip_file.hpp"

namespace mocapdb::bench {

/// Every .amc and .bvh file of the folder in name order (the first `limit` when limit > 0), named by
/// their stems. BVH files are read at 60 Hz: the PFNN folder's Frame Time is wrong (SOURCE.txt).
inline std::vector<Clip> read_shared_folder(const std::string& name, std::size_t limit = 0) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(MOCAPDB_SHARED_DIR) / "datasets" / name;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir)) {
        const auto ext = e.path().extension().string();
        if (ext == ".amc" || ext == ".bvh") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (limit > 0 && files.size() > limit) files.resize(limit);
    std::vector<Clip> clips;
    for (const auto& f : files) {
        ClipReadOptions o;
        if (f.extension() == ".bvh") o.frame_rate = 60.0;
        Warnings warnings;
        clips.push_back(read_clip(f, o, &warnings));
        clips.back().name = f.stem().string();
    }
    return clips;
}

}  // namespace mocapdb::bench
