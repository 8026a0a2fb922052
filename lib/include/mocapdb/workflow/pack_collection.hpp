#pragma once
// Packing a whole database into its error-bounded tier (/packed, schemas/format-v4.md §9): every
// clip, grouped by skeleton topology and frame rate (packing::group_clips) and cut into groups of at
// most max_group_frames source frames (so memory is bounded by a group, not by the collection), each
// group packed with packing::pack_group and stored through one DatabaseWriter session (atomic,
// writer lock).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/packing/byte_parts.hpp"
#include "mocapdb/packing/group_split.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {

/// The range of bounds a byte budget is searched over (cm): E is never coarser or finer.
inline constexpr double kCoarsestBudgetErrorCm = 100.0;
inline constexpr double kFinestBudgetErrorCm = 0.001;

/// Thrown when a byte budget cannot be met even at kCoarsestBudgetErrorCm (the message says the
/// smallest size reached).
class BudgetUnreachable : public Error {
public:
    using Error::Error;
};

struct PackDatabaseOptions {
    double max_error_cm = 1.0;  ///< E: max FK joint-position error (cm), > 0 and finite
    /// A byte budget instead of E (0: off): the tier is packed at the smallest E (three significant
    /// digits, found to about 2 %, within [kFinestBudgetErrorCm, kCoarsestBudgetErrorCm]) whose
    /// bytes (PackedTierRecord::bytes, everything the decoder needs) are <= max_bytes. Each E tried
    /// packs the whole collection in memory (measured as stored); only the E chosen is written.
    /// max_error_cm is then ignored.
    std::uint64_t max_bytes = 0;
    /// Runtime (default): a pose decodes from the stored bytes in about a microsecond; Archive: the
    /// smallest bytes, a pose costs its window's decoding (packing::PackFormat).
    packing::PackFormat format = packing::PackFormat::Runtime;
    int threads = 2;  ///< encoder threads (>= 1)
    /// Replace an existing packed tier; without it a database that has one is refused (StoreError).
    bool replace = false;
    double wait_seconds = kWriterWaitSeconds;  ///< for another writing session on the file
    /// A topology and rate with more frames is split into ceil(frames / max) groups of about equal
    /// frames (whole clips; a single longer clip is a group of its own; packing::split_by_frames). >= 1.
    std::size_t max_group_frames = packing::kMaxGroupFrames;
    /// In the same session, remove the lossless channels of every packed clip
    /// (DatabaseWriter::drop_lossless): the file keeps them only within E.
    bool drop_lossless = false;
};

struct PackDatabaseOutcome {
    /// With a byte budget: the budget and every E tried (in order), with its bytes and whether
    /// they fit (bytes 0 and fits false: E so fine that the stored skeleton alone misses it).
    struct Budget {
        struct Try {
            double max_error_cm = 0.0;
            std::uint64_t bytes = 0;
            bool fits = false;
        };
        std::uint64_t max_bytes = 0;
        std::vector<Try> tried;
    };
    std::optional<Budget> budget;  ///< set when packed to a byte budget
    /// The tier as stored: E, bytes, the collection's and each group's figures (measured by decoding
    /// the stored bytes and comparing FK positions with the source clips at every source frame).
    PackedTierRecord tier;
    std::vector<std::uint64_t> group_float32_bytes;  ///< per group: frames × channels × 4
    std::vector<double> group_seconds;               ///< per group: encode + measurement, s
    /// Per group: the format its bytes are in (Runtime unless asked for Archive, or a group the
    /// runtime format cannot hold: packing::PackOptions::format) and its W.
    std::vector<packing::PackFormat> group_formats;
    std::vector<int> group_windows;
    /// Bytes per kind of stored data (packing::PackStats::parts), summing exactly to tier.bytes,
    /// and per group (each summing to its group's bytes).
    packing::ByteParts parts;
    std::vector<packing::ByteParts> group_parts;
    std::uint64_t float32_bytes = 0;   ///< the clips' channels as float32
    double motion_seconds = 0.0;       ///< duration of the clips
    std::size_t dropped_lossless = 0;  ///< clips whose lossless channels were removed (drop_lossless)
    bool replaced = false;             ///< an earlier packed tier was replaced
    double replaced_max_error_cm = 0.0;
    std::uint64_t file_bytes = 0;  ///< the database file after the commit
    double seconds = 0.0;          ///< wall time

    double ratio_float32() const;                         ///< float32 bytes / tier bytes (0 without bytes)
    double group_ratio_float32(std::size_t group) const;  ///< the same per group
    double bytes_per_second() const;                      ///< tier bytes per second of motion (0 without motion)
};

/// Packs every clip of the database at `db` and stores the result as its packed tier (committed).
/// InvalidArgument for E <= 0 or not finite (without a budget), threads < 1; BudgetUnreachable when
/// options.max_bytes cannot be met; IoError when `db` does not exist;
/// StoreError when it is not a database or already has a packed tier and !options.replace (or that
/// tier is the only copy of some clips: their lossless channels were dropped);
/// packing::PackingFailed when a window cannot meet the bound. An empty database gets an empty
/// tier. `progress` counts source frames of the collection (done/total), item = the clip.
/// Memory: one group's clips at a time (see max_group_frames).
PackDatabaseOutcome pack_database(const std::filesystem::path& db, const PackDatabaseOptions& options,
                                  const ProgressCallback& progress = {});

/// Removes the lossless channels of every clip in the database's packed tier, in one committed
/// session (DatabaseWriter::drop_lossless). Returns how many clips were dropped. IoError when `db`
/// does not exist, StoreError when it has no packed tier.
std::size_t drop_lossless_tier(const std::filesystem::path& db, double wait_seconds = kWriterWaitSeconds);

}  // namespace mocapdb::workflow
