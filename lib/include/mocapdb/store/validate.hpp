#pragma once
// Checking a database file against the format specification of its version (schemas/format-vN.md),
// driven by the machine-readable mirror schemas/format-vN.json (compiled into the library for every
// version it reads).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"

namespace mocapdb {

struct Violation {
    std::string path;     ///< HDF5 path of the offending object ("/" for the file)
    std::string message;  ///< what was expected and what was found
};

struct ValidationReport {
    std::vector<Violation> violations;  ///< at most ValidateOptions::max_violations, in file order
    bool truncated = false;             ///< more violations were found than reported
    std::size_t objects = 0;            ///< groups and datasets checked
    std::size_t datasets_read = 0;      ///< datasets read in full (checksums verified)
    int format_version = 0;             ///< the file's format_version; 0 when the root could not be read
    bool ok() const noexcept { return violations.empty(); }
};

struct ValidateOptions {
    std::size_t max_violations = 50;
    /// Schema mirror text (JSON) to check against; empty: the built-in mirror of the file's
    /// format_version (format-vN.json for a version-N file).
    std::string schema_json;
    /// Called per clip checked: done counts clips of the structure pass then of the content pass,
    /// total = 2 x the clips (item = the clip id). Sets, skeletons and the packed tier are checked
    /// between and after, unreported. May be empty.
    ProgressCallback progress;
};

/// Checks structure (every object against the schema: kinds, dtypes, ranks, dims names, shapes,
/// attributes, filters), content (every dataset read in full, so checksums are verified; clip
/// columns match their skeleton; sets reference stored clips within their frames; aligned tensors
/// match their set and skeleton; models match their aligned tensor) and reports violations instead
/// of throwing. A file that cannot be opened or is not a mocapdb file of a version this library reads
/// gives one violation at "/". IoError only when the file does not exist; ParseError for a malformed
/// options.schema_json.
ValidationReport validate_database(const std::filesystem::path& file, const ValidateOptions& options = {});

/// The built-in schema mirror of the current version (schemas/format-v3.json).
const std::string& builtin_schema_json();
/// The built-in schema mirror schemas/format-v{format_version}.json; InvalidArgument for a version
/// this library does not read.
const std::string& builtin_schema_json(int format_version);

}  // namespace mocapdb
