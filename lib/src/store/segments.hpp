#pragma once
// The segments of a format-4 database (schemas/format-v4.md). The database file the user names
// ("DB.h5") is a small index: root attributes, the top groups, and one external link per top-level
// object (skeleton, clip, set, packed tier) into a segment, an HDF5 file in the folder "DB.h5.d"
// beside it. A writing session puts what it creates into one new segment and publishes a new index
// by rename; published segments are never modified, so a commit costs what it writes, not the file.
// Segments no published index links to (replaced objects, killed sessions) are removed when no
// reader holds the folder's readers' lock (ReaderLock).
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

#include "h5/file.hpp"

namespace mocapdb::store {

/// "DB.h5" -> "DB.h5.d" (beside it).
std::filesystem::path segment_dir(const std::filesystem::path& index);
/// A fresh segment's name as its links store it, relative to the index's folder: "DB.h5.d/NAME.h5"
/// with the UTC time, this process's id and random digits (the file is not created).
std::string new_segment_name(const std::filesystem::path& index);
/// The file of a segment link name, beside `index`.
std::filesystem::path segment_file(const std::filesystem::path& index, const std::string& link_name);
/// The top-level object paths ("/clips/02_01", "/packed", ...) of an index, in order.
std::vector<std::string> top_level_objects(const h5::File& index);
/// The segment link names an index refers to.
std::set<std::string> referenced_segments(const h5::File& index);
/// Stored bytes of the datasets at or below `path` (their chunks, after filters).
std::uint64_t stored_bytes_under(const h5::File& file, const std::string& path);
/// Removes the files of `index`'s segment folder that `referenced` does not name (and stale partial
/// files), unless a reader holds the readers' lock: then nothing is removed now (a later commit
/// does it). Returns how many files were removed. Never throws for a file it cannot remove.
std::size_t remove_unreferenced_segments(const std::filesystem::path& index, const std::set<std::string>& referenced);
/// Rewrites a finished, unpublished index or segment file with only its live objects (HDF5 does
/// not reuse the space of unlinked objects): copies them into a new file beside it and renames that
/// over it. Links to segments are copied as links.
void rewrite_live_objects(const std::filesystem::path& file);
/// Copies the database `from` (its index and the segments it links to, byte for byte) to `to`, a
/// path that must not exist, with links into "to.d/". IoError when a file cannot be copied.
void copy_database(const std::filesystem::path& from, const std::filesystem::path& to);
/// Bytes the database occupies on disk: the index plus every file of its segment folder.
std::uint64_t disk_bytes(const std::filesystem::path& index);
/// The index plus the segment files `referenced` names.
std::uint64_t referenced_bytes(const std::filesystem::path& index, const std::set<std::string>& referenced);

/// A shared flock(2) on "DB.h5.d/readers.lock", held by every open Database of a format-4 file so
/// that no segment it may still read is removed under it. Taking it never waits (writers only try
/// the exclusive lock, without waiting). Without a segment folder, or when the lock file cannot be
/// opened (read-only media), no lock is held: nothing can be removed there either.
class ReaderLock {
public:
    explicit ReaderLock(const std::filesystem::path& index);
    ~ReaderLock();
    ReaderLock(const ReaderLock&) = delete;
    ReaderLock& operator=(const ReaderLock&) = delete;

private:
    int fd_ = -1;
};

}  // namespace mocapdb::store
