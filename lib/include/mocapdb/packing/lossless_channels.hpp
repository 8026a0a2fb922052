#pragma once
// Lossless packing of a clip's channel matrix (frames by channels, cm and radians) into a few bytes
// per value, exact to the bit: what `import` stores (schemas/format-v3.md §5, docs/storage.md).
//
// Details: docs/headers/packing.md (mocapdb/packing/lossless_channels.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::packing {

/// Per-channel decimals marking a channel stored as float64 bits (no decimal form).
constexpr std::int64_t kRawChannel = -1;

/// A packed channel matrix: the zstd frame and the per-channel parameters needed to decode it.
struct PackedChannels {
    std::size_t frames = 0;
    std::vector<double> scale;            ///< C: cm or rad per source unit (the reader's factor)
    std::vector<std::int64_t> decimals;   ///< C: base decimal count k (0..22), or kRawChannel
    std::vector<std::int64_t> predictor;  ///< C: 1 (previous frame) or 2 (linear extrapolation)
    /// Decompressed bytes of the four sections: coarse residuals, extra decimals, refinements, raw.
    std::array<std::uint64_t, 4> section_bytes{};
    std::vector<std::uint8_t> bytes;  ///< one zstd frame (with its content checksum)

    std::size_t channels() const noexcept { return scale.size(); }
};

struct LosslessOptions {
    int zstd_level = 19;  ///< 1..22 (docs/storage.md: 19 measured as the default)
    /// 0: per channel, the order that codes to fewer bytes; 1 or 2: that order for every channel.
    int predictor = 0;
    int max_decimals = 9;  ///< largest base decimal count k tried (0..18)
    /// false: store every channel as float64 bits (the generic fallback; for measurements).
    bool detect_decimals = true;
};

/// Per channel of `skeleton`, the factor the readers multiply the source text by (io/asf_amc.cpp,
/// io/bvh_reader.cpp): pi/180 for rotations in degrees, 1 in radians, cm_per_unit for positions.
std::vector<double> reader_scales(const Skeleton& skeleton);

/// Packs `channels` (F by C, F >= 1) given each column's reader scale `scales` (C, > 0, finite).
/// Any double (also NaN, infinities, -0) is kept exactly. InvalidArgument on a shape or scale or
/// option violation; Error when zstd fails or the verifying decode differs (a bug).
PackedChannels pack_channels(const FrameMatrix& channels, const std::vector<double>& scales,
                             const LosslessOptions& options = {});

/// Decodes `packed` to the F by C matrix pack_channels was given, bit for bit. Error naming what is
/// inconsistent when the parameters or the bytes are malformed (a corrupted or foreign payload).
FrameMatrix unpack_channels(const PackedChannels& packed);

}  // namespace mocapdb::packing
