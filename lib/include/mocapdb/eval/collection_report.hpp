#pragma once
// The whole-collection benchmark of a database: for each bound E, every clip packed
// in memory as `mocapdb pack` would store it (grouped by skeleton topology and frame rate,
// packing::pack_measured per group; nothing is written), with bytes, ratio to float32 channels,
// bytes per second of motion, bits per joint per frame, max / p99 / RMSE cm measured on the decoded
// bytes, encode time, random-access decode time per pose and streaming decode speed; and the lossless
// tier beside gzip -9 of the clips' source text.
//
// The database is only read (not thread-safe: one Database per thread). Memory: one group's clips
// and their FK positions at a time, plus every E's packed bytes. Errors: InvalidArgument for bad
// options (no E, E <= 0 or not finite, threads < 1); the database's StoreError; pack errors.
//
// Details: docs/headers/eval.md (mocapdb/eval/collection_report.hpp).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/packing/byte_parts.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::eval {

struct CollectionReportOptions {
    std::vector<double> max_error_cm{1.0, 0.5, 0.1, 0.03, 0.01};  ///< the bounds E, cm
    int threads = 2;                                              ///< encoder threads
    std::size_t random_poses = 20000;                             ///< poses timed per E (0: no timing)
    std::uint32_t seed = 7;                                       ///< of the random poses
    /// Folders searched, subfolders included, for the clips' source files (by recorded file name,
    /// the first with the recorded SHA-256) for gzip -9; empty: not measured.
    std::vector<std::filesystem::path> source_dirs;
};

/// Packed figures of a set of clips (one group, or the collection) at one E.
struct PackedFigures {
    std::size_t clips = 0;
    std::size_t frames = 0;
    std::uint64_t bytes = 0;
    std::uint64_t float32_bytes = 0;
    double motion_seconds = 0.0;
    double joint_frames = 0.0;  ///< sum over clips of frames x joints (end sites included)
    double max_cm = 0.0, p99_cm = 0.0, rmse_cm = 0.0;
    double encode_seconds = 0.0;
    double stream_seconds = 0.0;  ///< decode_clip wall time
    std::size_t raw_windows = 0;  ///< windows stored as source rows (no step met E)
    packing::ByteParts parts;     ///< bytes per kind of stored data (PackStats::parts), summing to bytes
    int attempts = 0;             ///< max over groups of pack attempts

    double ratio_float32() const;
    double bytes_per_second() const;
    double bits_per_joint_frame() const;
    double stream_mb_per_second() const;  ///< float32 channel MB (1e6 B) per second
};

struct GroupFigures {
    std::string skeleton;  ///< skeleton id of its first clip
    std::string first_clip;
    double frame_rate = 0.0;
    PackedFigures figures;
};

struct TargetFigures {
    double max_error_cm = 0.0;  ///< E
    PackedFigures total;
    std::vector<GroupFigures> groups;
    double pose_microseconds = 0.0;  ///< random access, per pose (GroupDecoder::decode_pose, channel row)
    /// What the groups' decoders hold in memory beyond the stored bytes (GroupDecoder::resident_bytes):
    /// what decode_pose needs besides the bytes.
    std::uint64_t resident_bytes = 0;
    std::size_t poses_timed = 0;
    /// The same poses as local transforms through a PoseIndex (packing/pose_index.hpp: each group
    /// range-decoded once and held in memory; built one group at a time), per pose; and the bytes the
    /// groups' indexes hold (their sum: what a reader keeping every group indexed holds).
    double indexed_pose_microseconds = 0.0;
    std::uint64_t index_bytes = 0;
};

struct LosslessFigures {
    std::uint64_t bytes = 0;          ///< file bytes spent on the clips (Database::clips_file_bytes)
    std::uint64_t channel_bytes = 0;  ///< of which the stored channel data (ClipRecord::stored_bytes)
    std::uint64_t float32_bytes = 0;
    bool gzip_available = false;
    std::uint64_t gzip_bytes = 0;         ///< gzip -9 of every clip's source file (when available)
    std::uint64_t source_text_bytes = 0;  ///< the source files' sizes (when available)
    std::string gzip_reason;              ///< why not available ("" when available)
    std::size_t sources_found = 0;        ///< source files found with the recorded SHA-256
    std::size_t sources_missing = 0;      ///< not found in any source folder
    std::size_t sources_changed = 0;      ///< found, but with another SHA-256

    double ratio_float32() const;  ///< float32 / bytes
    double gzip_ratio_float32() const;
    double gzip_over_lossless() const;  ///< gzip bytes / bytes: how much smaller the lossless tier is (0 without bytes)
};

struct CollectionReport {
    std::size_t clips = 0;
    std::size_t frames = 0;
    std::size_t groups = 0;
    double motion_seconds = 0.0;
    std::uint64_t float32_bytes = 0;
    std::vector<std::string> clip_names;  ///< source file stems (the names the ACL tables use), by id
    std::vector<TargetFigures> targets;   ///< in the order of options.max_error_cm
    LosslessFigures lossless;
    int threads = 0;
    std::size_t random_poses = 0;

    double lossless_bytes_per_second() const;  ///< lossless bytes per second of motion (0 without motion)
};

/// Measures the report of `db`. `progress` counts frames: every clip once per E, plus once for the
/// gzip pass when source folders are given (item = the clip id). An empty database gives a report
/// with zero clips and, per E, zero bytes.
CollectionReport collection_report(const Database& db, const CollectionReportOptions& options,
                                   const ProgressCallback& progress = {});

}  // namespace mocapdb::eval
