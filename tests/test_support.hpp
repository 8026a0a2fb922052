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

}  // namespace mocapdb::test
