#pragma once
// `mocapdb import` as a library step: the clip files found under the inputs stored in a
// database, appending (or replacing the file with a new database when `force`), committed when
// anything was added (otherwise the file is left as it was, or not created, and no segment folder or
// lock file of a new database is left behind). Nothing is printed: the readers' warnings, the errors
// of the files skipped (empty or unreadable files always, unparsable ones with
// ImportOptions::keep_going) and the reasons files were not added (duplicates) are in the outcome,
// in file order.
//
// Errors: InvalidArgument when no clip file is found; IoError for an input that does not exist;
// StoreError when the target is not a mocapdb database (the message says --force replaces it); without
// keep_going the first file that cannot be read (ParseError, IoError, InvalidArgument naming it), and
// then nothing is stored. Threads: the database's writer lock serializes writers.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/workflow/import_files.hpp"

namespace mocapdb::workflow {

/// A line for the user about one file: a reader warning (Warning::to_string(), names the file) or,
/// with keep_going, why the file was not imported (ImportedFile::error).
struct ImportMessage {
    enum class Kind { Warning, Error };
    Kind kind = Kind::Warning;
    std::string text;
};

struct ImportOutcome {
    ImportSummary summary;
    bool existed = false;                 ///< the database file existed before
    std::size_t clips_in_db = 0;          ///< clips the database holds afterwards
    std::uint64_t file_bytes = 0;         ///< its size afterwards
    double seconds = 0.0;                 ///< wall time of reading and storing
    std::vector<ImportMessage> messages;  ///< warnings and errors, in file order
    std::vector<std::string> not_added;   ///< "FILE: why" for each file read but not stored (already stored)
};

/// `progress` is called with bytes read of the total (import_files); may be empty.
ImportOutcome import_clips(const std::filesystem::path& db, const std::vector<std::filesystem::path>& inputs,
                           const ImportOptions& options, bool force, const ProgressCallback& progress = {});

}  // namespace mocapdb::workflow
