#pragma once
// Helpers for the store tests: a temporary folder per test, running the CLI, small fixtures.
#include <filesystem>
#include <string>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/store/clip_record.hpp"

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
    std::string output;  ///< stdout and stderr together
};

/// Runs a shell command line, capturing both streams.
CommandResult run_command(const std::string& command_line);
/// Runs the mocapdb CLI with `arguments` (already shell-quoted where needed).
CommandResult run_cli(const std::string& arguments);
/// Single-quotes a path or word for the shell.
std::string quoted(const std::string& word);

/// A small synthetic clip: root with 6 channels and `joints` chain joints with 3 rotation channels
/// each (plus an end site), smooth values; deterministic for a given seed.
Clip synthetic_clip(std::size_t frames, std::size_t joints, unsigned seed, double frame_rate = 30.0);
/// A source description with a sha256 made from `seed_text`.
ClipSource synthetic_source(const std::string& file_name, const std::string& seed_text);
/// An aligned set that fits `set` (N samples) for a skeleton with pose vectors of `dofs` values and
/// `frames` aligned frames; values encode their position: tensor(d, t, s) = d + 10·t + 100·s.
AlignedSet synthetic_aligned(std::size_t dofs, std::size_t frames, const MotionSet& set);

/// The bytes of a file.
std::string file_bytes(const std::filesystem::path& path);

}  // namespace mocapdb::test
