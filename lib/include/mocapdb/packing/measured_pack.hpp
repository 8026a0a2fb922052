#pragma once
// Packing a group and measuring what a reader gets: pack_group, then every clip decoded from the
// bytes with GroupDecoder::decode_clip (as a reader decodes it) and compared with the source clip by
// forward kinematics (every joint and end site, world frame, every source frame). The encoder checks
// its bound on exactly what this decode gives (tests/packing: the two maxima are equal); should a
// position land above E all the same (a compiler folding away the float32 rounding of the stored
// skeleton once made them differ by up to 1e-5 cm, core/float32.hpp), the group is packed again with
// E lowered by twice the excess, up to three attempts (the rule `mocapdb pack` applies,
// workflow/pack_collection.cpp), so the figures are those of bytes that meet E.
//
// Inputs are borrowed for the call. Thread-safety: pack_group's threads (options.threads), and as many
// for the measurement (clip by clip; the figures do not depend on their number; decode_seconds sums
// the clips' decode times). Errors: those of pack_group; Error when the decoded group
// still misses E after three attempts.
#include <cstddef>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/packing/error_stats.hpp"
#include "mocapdb/packing/packed_group.hpp"

namespace mocapdb::packing {

struct MeasuredGroup {
    PackedGroup packed;                   ///< the bytes that met E (stats of that attempt)
    std::vector<ErrorStats> clip_errors;  ///< per clip, measured on the decoded bytes
    ErrorAccumulator errors{1.0};         ///< the whole group (histogram range E)
    int attempts = 0;                     ///< pack_group calls (1 unless E had to be lowered)
    double encode_seconds = 0.0;          ///< every pack_group call
    double decode_seconds = 0.0;          ///< decode_clip of every clip, the accepted attempt only
};

/// Packs `clips` at options.max_error_cm and measures the result. `source_positions`, when not
/// empty, holds joint_positions(*clips[k]) for every k (to reuse them across several E); otherwise
/// they are computed here. `progress` is pack_group's (per attempt).
MeasuredGroup pack_measured(const std::vector<const Clip*>& clips, const PackOptions& options,
                            const std::vector<MatX>& source_positions = {}, const ProgressCallback& progress = {});

}  // namespace mocapdb::packing
