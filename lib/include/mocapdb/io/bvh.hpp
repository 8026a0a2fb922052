#pragma once
// BVH (Biovision Hierarchy) reading and writing.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

#include "mocapdb/core/diagnostics.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct BvhReadOptions {
    /// Refuse defects instead of working around them (e.g. fewer rows than "Frames:" declares).
    bool strict = false;
    /// Use this rate instead of the header's "Frame Time" (Hz); the header is still checked for syntax.
    std::optional<double> frame_rate;
    /// Centimetres per file length unit (BVH does not state its unit; the CMU conversions here are in cm).
    double cm_per_unit = 1.0;
    /// What position channels mean. Blender, MotionBuilder and most readers: the local translation,
    /// replacing OFFSET on its axes. `add_to_offset` reads files written for the other convention.
    PositionChannels position_channels = PositionChannels::replace_offset;
};

struct BvhWriteOptions {
    /// Significant digits of every number written (9 keeps float32-level data exact; 17 is lossless).
    int precision = 9;
    /// Centimetres per written length unit (1 writes centimetres).
    double cm_per_unit = 1.0;
};

/// Parses BVH text. `source_name` names the file in errors and warnings ("FILE:LINE: ...").
/// Throws ParseError on malformed input; defects it works around are appended to `out_warnings`.
Clip parse_bvh(std::string_view text, const std::string& source_name, const BvhReadOptions& options = {},
               Warnings* out_warnings = nullptr);
/// Reads a BVH file (IoError when it cannot be read).
Clip read_bvh(const std::filesystem::path& path, const BvhReadOptions& options = {}, Warnings* out_warnings = nullptr);

/// Writes the clip as BVH. Joints whose rotation cannot be written as BVH channels as they are (an ASF
/// axis, or rotation channels listed out of composition order) are converted first with
/// to_bvh_channels(); the motion (every joint's global transform) is unchanged.
void write_bvh(std::ostream& out, const Clip& clip, const BvhWriteOptions& options = {});
/// Atomic: writes a temporary file beside `path` and renames it over `path`.
void write_bvh(const std::filesystem::path& path, const Clip& clip, const BvhWriteOptions& options = {});

/// True when every joint can be written to BVH as it is (position channels written as BVH readers
/// take them: replacing OFFSET, or adding to a zero offset).
bool is_bvh_compatible(const Skeleton& skeleton);
/// An equivalent clip whose joints are all BVH-compatible: each joint that needs it gets three
/// rotation channels in `order` (identity axis), with angles unwrapped along time; position channels
/// are kept, as local translations (PositionChannels::replace_offset: offset added where the
/// source skeleton adds). Joints already compatible are kept as they are.
Clip to_bvh_channels(const Clip& clip, EulerOrder order = EulerOrder::ZYX);

}  // namespace mocapdb
