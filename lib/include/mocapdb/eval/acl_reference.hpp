#pragma once
// ACL (the Animation Compression Library) as the codec to beat: its per-clip results on the shared
// CMU clips (../shared/reference/acl/*.csv, one row per clip and precision setting, errors measured
// with our FK metric) aggregated over a collection, and ACL's bytes at a given error.
//
// Pure functions; no state, thread-safe. Errors: IoError when a table cannot be read, ParseError
// ("FILE:LINE:COLUMN: ...") naming the column and what was expected for a malformed table.
//
// Details: docs/headers/eval.md (mocapdb/eval/acl_reference.hpp).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mocapdb::eval {

/// One row of a per-clip ACL table (the columns compare.py reads).
struct AclClipRow {
    std::string dataset;
    std::string clip;           ///< the source file's stem ("16_15", "02_01_60fps")
    double precision_cm = 0.0;  ///< ACL's per-track precision setting
    std::size_t joints = 0;
    std::size_t end_sites = 0;
    std::size_t frames = 0;
    std::uint64_t acl_bytes = 0;  ///< the whole compressed buffer
    double max_cm = 0.0;          ///< FK position errors, our metric
    double rmse_cm = 0.0;
    std::size_t line = 0;  ///< 1-based line in its file
};

/// The usable rows of one or more tables (status "ok", precision not "raw").
struct AclTable {
    std::vector<std::filesystem::path> files;
    std::vector<AclClipRow> rows;
    std::size_t skipped_rows = 0;  ///< rows left out: raw containers and failed settings
};

/// Reads a per-clip table. Quoted cells (RFC 4180) are allowed; the header must name at least
/// clip, precision_cm, status, joints, end_sites, frames, acl_bytes, max_cm, rmse_cm.
AclTable read_acl_table(const std::filesystem::path& file);
/// Appends the rows of `more` to `table` (several folders' tables for one database).
void append(AclTable& table, AclTable more);

/// ACL at one precision setting over the selected clips.
struct AclSetting {
    double precision_cm = 0.0;
    std::uint64_t bytes = 0;
    double max_cm = 0.0;
    double rmse_cm = 0.0;
    std::size_t clips = 0;
};

/// ACL over a collection: one entry per precision (increasing), and the requested clips that have
/// no row at all (the comparison is not over the same clips then).
struct AclCollection {
    std::vector<AclSetting> settings;
    std::vector<std::string> missing;
    std::size_t requested = 0;

    /// Every requested clip has a row at every setting.
    bool complete() const;
};

/// Aggregates the rows whose `clip` is one of `clips` (every row when `clips` is empty).
AclCollection aggregate_acl(const AclTable& table, const std::vector<std::string>& clips);

/// Log-linear interpolation of bytes at `error` over (error, bytes) points, as compare.py's
/// at_error: the points are sorted, the first bracketing pair is used; nullopt outside the range
/// of the points' errors (or for fewer than one point, or a non-positive error).
std::optional<double> bytes_at_error(std::vector<std::pair<double, double>> points, double error);

/// ACL's bytes at our measured max error and RMSE, and how many times smaller `bytes` is.
/// Below ACL's range (our error smaller than that of ACL's most precise setting, e.g. E = 0.01 cm
/// against ACL's default precision, whose max error is 0.012-0.026 cm) the figure is ACL's bytes at
/// that most precise setting, flagged as a lower bound (`*_lower_bound`): reaching a smaller error
/// costs ACL at least those bytes, as its bytes grow with every finer setting; given only when the
/// most precise setting is also the largest. Above ACL's range: nullopt, never an extrapolation.
struct AclComparison {
    std::optional<double> bytes_at_max;  ///< nullopt: outside ACL's measured range
    std::optional<double> bytes_at_rmse;
    std::optional<double> smaller_at_max;  ///< ACL bytes / our bytes
    std::optional<double> smaller_at_rmse;
    bool max_lower_bound = false;   ///< bytes_at_max (so smaller_at_max) is a lower bound
    bool rmse_lower_bound = false;  ///< bytes_at_rmse (so smaller_at_rmse) is a lower bound
};

AclComparison compare_with_acl(const AclCollection& acl, double bytes, double max_cm, double rmse_cm);

}  // namespace mocapdb::eval
