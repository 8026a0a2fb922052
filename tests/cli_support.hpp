#pragma once
// Test helpers for running the mocapdb CLI: a temporary folder per test and a command runner that
// captures output and exit code.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "shared_data.hpp"

namespace mocapdb::test {

/// A fresh folder under the system temp folder, removed with its content on destruction.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& tag) {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() /
                ("mocapdb-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000));
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::filesystem::path& path() const noexcept { return path_; }
    std::string operator/(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

struct CliResult {
    int exit_code = -1;
    std::string out;  ///< stdout
    std::string err;  ///< stderr
};

/// Single-quotes a word for the shell.
inline std::string shell_quote(const std::string& word) {
    std::string out = "'";
    for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

/// Runs `mocapdb ARGUMENTS` (arguments already shell-quoted where needed); stdout and stderr apart.
inline CliResult mocapdb_cli(const std::string& arguments) {
    static int counter = 0;
    const std::filesystem::path err_file = std::filesystem::temp_directory_path() /
                                           ("mocapdb-cli-stderr-" + std::to_string(::getpid()) + "-" + std::to_string(++counter));
    CliResult r;
    const std::string line = shell_quote(cli_path()) + " " + arguments + " 2>" + shell_quote(err_file.string());
    FILE* pipe = ::popen(line.c_str(), "r");
    if (pipe == nullptr) return r;
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.out.append(buffer, n);
    const int status = ::pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (FILE* f = std::fopen(err_file.c_str(), "rb")) {
        while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) r.err.append(buffer, n);
        std::fclose(f);
    }
    std::filesystem::remove(err_file);
    return r;
}

}  // namespace mocapdb::test
