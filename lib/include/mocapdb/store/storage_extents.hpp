#pragma once
// Where a dataset's bytes lie in a database file: for diagnostics and for the corruption tests,
// which flip bytes inside a stored chunk and expect a checksum error.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace mocapdb {

struct ByteExtent {
    std::uint64_t offset = 0;    ///< from the start of the file
    std::uint64_t size = 0;      ///< stored (filtered) bytes
    std::filesystem::path file;  ///< the file holding them: the database file or one of its segments
};

/// The stored chunks (or the contiguous block) of dataset `dataset_path` of database `file`, in chunk
/// order, each with the file that holds it (in format 4 a segment reached through an external link).
/// StoreError when the file or dataset cannot be opened.
std::vector<ByteExtent> dataset_extents(const std::filesystem::path& file, const std::string& dataset_path);

}  // namespace mocapdb
