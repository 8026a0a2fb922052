#pragma once
// Helpers shared by every test executable: a temporary folder per test and running the CLI.
#include <filesystem>
#include <string>

namespace mocapdb::test {

/// A fresh folder under the system temp folder, removed with its content on destruction.
class TempDir {
public:
    explicit TempDir(const std::string& tag);
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const noexcept { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

struct CommandResult {
    int exit_code = -1;
    std::string out;     ///< stdout
    std::string err;     ///< stderr
    std::string output;  ///< stdout then stderr
};

/// Runs a shell command line, capturing both streams (apart, and together).
CommandResult run_command(const std::string& command_line);
/// Runs the mocapdb CLI with `arguments` (already shell-quoted where needed).
CommandResult run_cli(const std::string& arguments);
/// Single-quotes a path or word for the shell.
std::string quoted(const std::string& word);

/// The clip folder a whole-folder test imports: `folder` itself in a release build; in a sanitizer build
/// (MOCAPDB_SANITIZED_BUILD, 10-20x slower) a folder created under `scratch` holding symbolic links to
/// every 6th clip with extension `extension` (".amc", sorted by name) and to every other file (e.g. the
/// ASF skeletons). The release pass checks every clip; the sanitizer pass checks the same code paths.
std::filesystem::path folder_for_this_build(const std::filesystem::path& folder, const std::string& extension,
                                            const std::filesystem::path& scratch);
/// Number of files with `extension` in `folder` (links included).
std::size_t count_files(const std::filesystem::path& folder, const std::string& extension);
/// Every file and folder under `folder` (recursive), one "RELATIVE_PATH SIZE" line each (size of a
/// regular file, "dir" for a folder), sorted: what a failed command must leave as it found it.
std::string folder_listing(const std::filesystem::path& folder);

}  // namespace mocapdb::test
