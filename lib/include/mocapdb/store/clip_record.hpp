#pragma once
// What the database records about a stored clip besides its motion: where it came from and the
// optional manifest fields.
#include <cstdint>
#include <string>
#include <vector>

namespace mocapdb {

/// Provenance of a clip, given to DatabaseWriter::add_clip and returned in listings.
struct ClipSource {
    std::string file_name;      ///< source file name without folders ("16_15.amc"); the clip id is its stem
    std::string sha256;         ///< lowercase hex SHA-256 of the source file's bytes (64 characters)
    std::string format;         ///< "bvh" or "amc"
    std::string skeleton_file;  ///< the ASF file name of an AMC clip; empty for BVH
    // Optional manifest columns (empty when not given).
    std::string subject;
    std::string description;
    std::vector<std::string> labels;
};

/// One stored clip as listed by Database::clips().
struct ClipRecord {
    std::string id;  ///< clip id (group name under /clips)
    ClipSource source;
    std::string skeleton;  ///< skeleton id (group name under /skeletons)
    std::size_t frames = 0;
    std::size_t channels = 0;
    double frame_rate = 0.0;         ///< Hz
    std::uint64_t stored_bytes = 0;  ///< bytes the lossless channel data takes in the file (compressed)
    /// False when the lossless channels were dropped (mocapdb pack --drop-lossless): the clip is
    /// then in the packed tier only, and Database::load_clip decodes it from there.
    bool lossless = true;

    double duration() const noexcept {
        return frames > 0 && frame_rate > 0.0 ? static_cast<double>(frames - 1) / frame_rate : 0.0;
    }
};

}  // namespace mocapdb
