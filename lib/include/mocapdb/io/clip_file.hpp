#pragma once
// Reading a clip from any supported file, chosen by extension (.bvh, or .amc with its .asf).
#include <filesystem>
#include <optional>

#include "mocapdb/core/diagnostics.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

enum class ClipFormat { Bvh, Amc };

struct ClipReadOptions {
    /// Skeleton for an AMC file; when empty, found beside it by the CMU naming (NN_MM.amc -> NN.asf).
    std::filesystem::path asf;
    /// Frame rate override (Hz). AMC files default to 120 Hz; BVH files to their Frame Time.
    std::optional<double> frame_rate;
    /// Refuse defects instead of working around them with a warning.
    bool strict = false;
    /// What BVH position channels mean (BvhReadOptions::position_channels).
    PositionChannels bvh_positions = PositionChannels::replace_offset;
};

/// The format of a path by its extension (case-insensitive); nullopt when unsupported.
std::optional<ClipFormat> clip_format_of(const std::filesystem::path& path);

/// Reads a BVH or AMC file. Throws ParseError / IoError / InvalidArgument (unsupported extension,
/// AMC without a skeleton) naming the file.
Clip read_clip(const std::filesystem::path& path, const ClipReadOptions& options = {},
               Warnings* out_warnings = nullptr);

}  // namespace mocapdb
