#pragma once
// Output files of the subcommands: never overwritten without --force, refused before any work.
#include <filesystem>
#include <initializer_list>

namespace mocapdb::cli {

/// IoError "PATH: exists (pass --force to overwrite it)" when `path` is non-empty, exists and `force`
/// is off. Call it before the work, so a refused run costs nothing.
void refuse_existing(const std::filesystem::path& path, bool force);
/// The same for every non-empty path of a command.
void refuse_existing(std::initializer_list<std::filesystem::path> paths, bool force);

}  // namespace mocapdb::cli
