#pragma once
// Checking a database file against the format specification (schemas/format-v1.md), driven by the
// machine-readable mirror schemas/format-v1.json (compiled into the library).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

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
    bool ok() const noexcept { return violations.empty(); }
};

struct ValidateOptions {
    std::size_t max_violations = 50;
    /// Schema mirror text (JSON) to check against; empty: the built-in format-v1.json.
    std::string schema_json;
};

/// Checks structure (every object against the schema: kinds, dtypes, ranks, dims names, shapes,
/// attributes, filters), content (every dataset read in full, so checksums are verified; clip
/// columns match their skeleton; sets reference stored clips within their frames; aligned tensors
/// match their set and skeleton) and reports violations instead of throwing. A file that cannot be
/// opened or is not a mocapdb file of this version gives one violation at "/". IoError only when
/// the file does not exist.
ValidationReport validate_database(const std::filesystem::path& file, const ValidateOptions& options = {});

/// The built-in schema mirror (schemas/format-v1.json).
const std::string& builtin_schema_json();

}  // namespace mocapdb
