#pragma once
// Temporary files beside a target, and making a finished file durable before it is published.
//
// Names: "TARGET.tmp-mocapdb-PID-XXXXXXXX" (PID of the writing process, 8 random hex digits), so
// they are unique and a later session can tell a dead process's leftovers from a live session's.
#include <filesystem>

namespace mocapdb::store {

/// A fresh, unused temporary path beside `target` (the file is not created).
std::filesystem::path make_temp_path(const std::filesystem::path& target);
/// Removes temporaries of `target` left by processes that no longer exist; returns how many.
std::size_t remove_stale_temps(const std::filesystem::path& target);
/// fsync(2) of a file's data, then of its folder (a new file's name is durable too). IoError on failure.
void make_durable(const std::filesystem::path& file);
/// fsync(2) of a file's data, then rename(2) over `target`, then fsync of the folder. IoError on failure.
void publish(const std::filesystem::path& temp, const std::filesystem::path& target);

}  // namespace mocapdb::store
