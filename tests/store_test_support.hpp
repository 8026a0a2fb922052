#pragma once
// Helpers for the store tests: a temporary folder per test, running the CLI, small fixtures.
#include <filesystem>
#include <string>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/store/clip_record.hpp"
#include "mocapdb/store/validate.hpp"
#include "test_support.hpp"

namespace mocapdb::test {

/// A small synthetic clip: root with 6 channels and `joints` chain joints with 3 rotation channels
/// each (plus an end site), smooth values; deterministic for a given seed.
Clip synthetic_clip(std::size_t frames, std::size_t joints, unsigned seed, double frame_rate = 30.0);
/// A source description with a sha256 made from `seed_text`.
ClipSource synthetic_source(const std::string& file_name, const std::string& seed_text);
/// An aligned set that fits `set` (N samples) for a skeleton with pose vectors of `dofs` values and
/// `frames` aligned frames; values encode their position: tensor(d, t, s) = d + 10·t + 100·s.
AlignedSet synthetic_aligned(std::size_t dofs, std::size_t frames, const MotionSet& set);

/// Every violation as "PATH: MESSAGE" lines (for INFO).
std::string all_violations(const ValidationReport& r);
/// True when a violation at `path` contains `text`.
bool has_violation(const ValidationReport& r, const std::string& path, const std::string& text);
/// Inverts `count` bytes of a file from `offset` (corrupting a dataset's chunk in place).
void flip_bytes(const std::filesystem::path& file, std::uint64_t offset, std::size_t count);

/// The bytes of a file.
std::string file_bytes(const std::filesystem::path& path);

/// Same shape and the same bits in every value (NaN payloads and signed zeros included).
bool same_bits(const FrameMatrix& a, const FrameMatrix& b);

}  // namespace mocapdb::test
