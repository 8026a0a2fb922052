#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <random>

#include "shared_data.hpp"

namespace mocapdb::test {

TempDir::TempDir(const std::string& tag) {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("mocapdb-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000));
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

CommandResult run_command(const std::string& command_line) {
    static int counter = 0;
    const std::filesystem::path err_file =
        std::filesystem::temp_directory_path() /
        ("mocapdb-test-stderr-" + std::to_string(::getpid()) + "-" + std::to_string(++counter));
    CommandResult r;
    FILE* pipe = ::popen((command_line + " 2>" + quoted(err_file.string())).c_str(), "r");
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
    std::error_code ignored;
    std::filesystem::remove(err_file, ignored);
    r.output = r.out + r.err;
    return r;
}

std::string quoted(const std::string& word) {
    std::string out = "'";
    for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

CommandResult run_cli(const std::string& arguments) { return run_command(quoted(cli_path()) + " " + arguments); }

}  // namespace mocapdb::test
