#pragma once
// The runtime tier's encoder: from a packed group (pack_group's bytes, whose header gives the
// skeletons, dof weights, dof basis and clip table) and the same clips, a body from which one pose
// decodes in about a microsecond (RuntimeDecoder, runtime_decoder.hpp) with every frame of every
// clip within E of its source by forward kinematics of every joint and end site (checked here, on
// every frame, through the decoder's own arithmetic). Format and measurements: docs/packing.md, "The runtime tier".
//
// Inputs are read only and not kept; the result owns its bytes. Thread-safe (no shared state); the
// clips are searched on RuntimeOptions::threads workers. Cost: every key and window step is searched by decodes and forward kinematics of its frames,
// about half of pack_group's time per window length on the shared folders (twice that with window 0).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb::packing {

struct RuntimeOptions {
    double max_error_cm = 1.0;  ///< E, > 0 and finite
    /// Frames from key to key: 8 (keys 4 step indices finer than the coarsest that holds, a directory
    /// of 1 level), 16 (8 finer, 2 levels), or 0: both are encoded and W = 8 is kept when its bytes
    /// are at most 2.5 % above W = 16's (W = 8 decodes a pose 10-20 % faster; on PFNN it costs 0.2-2.1 %
    /// bytes; on rigs whose keys are a large share of the bytes, such as CMU ASF/AMC, 2.9-10.4 % and
    /// W = 16 is kept).
    int window = 0;
    /// Quantizer rounding offset in [0.1, 0.5] (as PackOptions::rounding).
    double rounding = 0.4;
    /// Encoder threads (>= 1), clip by clip; the bytes do not depend on their number.
    int threads = 1;
};

struct RuntimeStats {
    std::size_t bytes = 0;  ///< the body (header, side stream, offsets, entries, slack)
    std::size_t header_bytes = 0, side_bytes = 0, offset_bytes = 0, entry_bytes = 0, slack_bytes = 0;
    int window = 0;             ///< W used
    int key_offset = 0;         ///< step indices the keys are finer than the coarsest that holds
    int directory_levels = 0;   ///< levels of left-subtree sizes per window
    double max_error_cm = 0.0;  ///< over every source frame, joint and end site (the encoder's check)
    std::size_t clips = 0, frames = 0;
    double encode_seconds = 0.0;
};

struct RuntimeBody {
    std::vector<std::uint8_t> bytes;
    RuntimeStats stats;
};

/// The runtime body of the packed group `group` for its source `clips` (the group's clips in its
/// order: same count, frame counts and topology). Throws InvalidArgument on options out of range or
/// clips that are not the group's, Error when `group` is malformed, PackingFailed when a frame cannot
/// meet E (or more than 256 dofs vary in the group: InvalidArgument).
RuntimeBody encode_runtime(const std::vector<std::uint8_t>& group, const std::vector<const Clip*>& clips,
                           const RuntimeOptions& options);

}  // namespace mocapdb::packing
