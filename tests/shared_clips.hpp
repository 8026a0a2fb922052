#pragma once
// Reading named clips of a shared CMU folder in tests (needs ../shared; see shared_data.hpp).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

namespace mocapdb::test {

/// The clips `stems` of ../shared/datasets/FOLDER (STEM.amc beside its NN.asf, or STEM.bvh read at
/// 60 Hz, the PFNN folder's true rate), named by their stems; each cut to its first `max_frames`
/// frames when max_frames > 0.
inline std::vector<Clip> read_shared_clips(const std::string& folder, const std::vector<std::string>& stems,
                                           std::size_t max_frames = 0) {
    std::vector<Clip> out;
    for (const auto& stem : stems) {
        const auto dir = datasets_dir() / folder;
        ClipReadOptions o;
        std::filesystem::path path = dir / (stem + ".amc");
        if (!std::filesystem::exists(path)) {
            path = dir / (stem + ".bvh");
            o.frame_rate = 60.0;
        }
        Clip c = read_clip(path, o);
        c.name = stem;
        if (max_frames > 0 && c.frame_count() > max_frames) c = slice(c, 0, max_frames);
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace mocapdb::test
