#pragma once
// Importing clip files (BVH, CMU ASF/AMC) into a database session, one file at a time: a folder is
// never held in memory whole, only the clip being stored (and the ASF skeletons met so far).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/diagnostics.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/manifest.hpp"

namespace mocapdb::workflow {

struct ImportOptions {
    /// Skeleton for every AMC file; when empty each NN_MM.amc uses NN.asf beside it (CMU naming).
    std::filesystem::path asf;
    /// Frame rate for every file (Hz); default: BVH Frame Time, AMC 120 Hz. A manifest `fps` wins.
    std::optional<double> frame_rate;
    /// Refuse reader defects instead of working around them with a warning.
    bool strict = false;
    /// What BVH position channels mean (BvhReadOptions::position_channels).
    PositionChannels bvh_positions = PositionChannels::replace_offset;
    /// A file that cannot be read or parsed is reported (ImportedFile::error) and skipped instead of
    /// stopping the import.
    bool keep_going = false;
    /// Optional per-file fields; may be null.
    const Manifest* manifest = nullptr;
};

/// What happened to one file.
struct ImportedFile {
    std::filesystem::path file;
    AddClipResult result;
    std::size_t frames = 0;
    double seconds = 0.0;     ///< duration of the clip
    std::uint64_t bytes = 0;  ///< size of the source file
    Warnings warnings;        ///< the reader's warnings
    std::string error;        ///< with keep_going: why the file was not imported (empty: it was read)
};

struct ImportSummary {
    std::size_t files = 0;         ///< files read
    std::size_t added = 0;         ///< clips stored
    std::size_t skipped = 0;       ///< duplicates (sha256 already stored)
    std::size_t failed = 0;        ///< with keep_going: files that could not be read or parsed
    std::size_t frames = 0;        ///< frames of the added clips
    double seconds = 0.0;          ///< motion duration of the added clips
    std::uint64_t bytes_read = 0;  ///< source bytes read (all files)
};

/// The clip files under `inputs`: files are taken as they are (any extension: read_clip refuses the
/// unsupported ones), folders are searched recursively for *.bvh and *.amc (case-insensitive).
/// Sorted by path within each folder, inputs in the order given, duplicates removed.
/// IoError for an input that does not exist.
std::vector<std::filesystem::path> collect_clip_files(const std::vector<std::filesystem::path>& inputs);

/// Reads each file and adds it to `db` (duplicates by SHA-256 are skipped before parsing).
/// `progress` is called with bytes done of the total; `on_file` after each file. A file that cannot
/// be read (IoError) or is empty (nothing but white space) is always counted in `failed`, passed to
/// `on_file` with its error, and the import goes on. Otherwise the first error (ParseError,
/// InvalidArgument naming the file) stops the import, and the caller then simply does not commit;
/// with options.keep_going a file that cannot be parsed is counted in `failed` and passed to
/// `on_file` too (errors while storing a parsed clip still stop it).
ImportSummary import_files(DatabaseWriter& db, const std::vector<std::filesystem::path>& files,
                           const ImportOptions& options, const ProgressCallback& progress = {},
                           const std::function<void(const ImportedFile&)>& on_file = {});

}  // namespace mocapdb::workflow
