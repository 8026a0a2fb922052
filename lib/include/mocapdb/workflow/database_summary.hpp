#pragma once
// What a database holds, summarized (`mocapdb info DB`): its clips and their totals (frames,
// seconds of motion, stored lossless bytes), each clip's packed-tier entry, the skeletons, the sets and
// the packed tier. Nothing is printed; the text and JSON renderings are the caller's.
// Errors: IoError / StoreError opening the database. Threads: opens it read-only for the call.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {

struct SkeletonSummary {
    std::string id;
    std::string source_file;
    std::size_t joints = 0;
    std::size_t channels = 0;
};

/// A clip's entry in the packed tier.
struct PackedClipEntry {
    std::string group;
    PackedClipRecord clip;
};

struct DatabaseSummary {
    int format_version = 0;
    std::uint64_t file_bytes = 0;
    std::vector<ClipRecord> clips;
    std::vector<std::optional<PackedClipEntry>> packed_clips;  ///< per clip, its packed entry (none when not packed)
    std::vector<SkeletonSummary> skeletons;
    std::vector<SetRecord> sets;
    std::optional<PackedTierRecord> packed;
    std::size_t total_frames = 0;
    double total_seconds = 0.0;
    std::uint64_t total_stored_bytes = 0;  ///< the clips' lossless channels as stored
};

DatabaseSummary summarize_database(const std::filesystem::path& db);

}  // namespace mocapdb::workflow
