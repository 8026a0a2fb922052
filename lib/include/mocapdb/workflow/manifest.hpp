#pragma once
// The import manifest: a CSV file with optional per-clip fields (subject, description, labels,
// frame rate) matched to source files by name.
//
// Format: UTF-8 CSV (RFC 4180 quoting: fields may be "quoted", "" is a quote inside), first row is
// the header. Column `file` is required: a source file name ("16_15.amc") or its stem ("16_15").
// Optional columns: `subject`, `description`, `labels` (several labels separated by ';'), `fps`
// (frame rate in Hz for that file, overriding --fps). Any other column is refused (ParseError), as
// are duplicate file entries. Blank lines are skipped.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace mocapdb::workflow {

struct ManifestEntry {
    std::string subject;
    std::string description;
    std::vector<std::string> labels;
    std::optional<double> frame_rate;  ///< Hz
};

class Manifest {
public:
    Manifest() = default;
    /// Parses CSV text; `source_name` names the file in ParseError messages ("FILE:LINE:COL: ...").
    static Manifest parse(std::string_view text, const std::string& source_name);
    static Manifest read(const std::filesystem::path& path);

    /// The entry for a source file, matched by file name first, then by stem; nullptr when none.
    const ManifestEntry* find(const std::filesystem::path& source) const;
    std::size_t size() const noexcept { return entries_.size(); }

private:
    std::unordered_map<std::string, ManifestEntry> entries_;  // key: the `file` column as written
};

}  // namespace mocapdb::workflow
