#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

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

std::filesystem::path folder_for_this_build(const std::filesystem::path& folder, const std::string& extension,
                                            const std::filesystem::path& scratch) {
#ifdef MOCAPDB_SANITIZED_BUILD
    constexpr std::size_t stride = 6;
#else
    constexpr std::size_t stride = 1;
#endif
    if (stride == 1) return folder;
    std::vector<std::filesystem::path> clips, others;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        (entry.path().extension() == extension ? clips : others).push_back(entry.path());
    std::sort(clips.begin(), clips.end());
    const auto sample = scratch / ("every-" + std::to_string(stride) + "th-" + folder.filename().string());
    std::filesystem::create_directories(sample);
    for (std::size_t i = 0; i < clips.size(); i += stride)
        std::filesystem::create_symlink(clips[i], sample / clips[i].filename());
    for (const auto& p : others) std::filesystem::create_symlink(p, sample / p.filename());
    return sample;
}

std::size_t count_files(const std::filesystem::path& folder, const std::string& extension) {
    std::size_t n = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) n += entry.path().extension() == extension;
    return n;
}

std::string folder_listing(const std::filesystem::path& folder) {
    std::vector<std::string> lines;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        const std::string size = entry.is_directory() ? "dir" : std::to_string(entry.file_size());
        lines.push_back(std::filesystem::relative(entry.path(), folder).string() + " " + size);
    }
    std::sort(lines.begin(), lines.end());
    std::string out;
    for (const std::string& line : lines) out += line + "\n";
    return out;
}

}  // namespace mocapdb::test
