#pragma once
// Whole-file reads and atomic whole-file writes shared by the text formats.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>

namespace mocapdb {

/// The file's bytes; IoError naming the file when it cannot be read.
std::string read_text_file(const std::filesystem::path& path);

/// Calls `write` on a stream to a temporary file beside `path`, flushes it to disk and renames it
/// over `path`, so a crash at any moment leaves either the old file or the complete new one.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

}  // namespace mocapdb
