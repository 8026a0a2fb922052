#pragma once
// Random access to any pose of a packed group in a few microseconds: the group's windows
// range-decoded once, at construction, and kept in memory sparse (per window its nonzero quantized
// coefficients with their places in the grid, time column by time column). A pose then costs its
// frame's products only (y = G v_t over the window's nonzero coefficients, x = U y, dofs to channels
// or local transforms): no range decoding (GroupDecoder::decode_pose spends 15-60 µs there) and no
// window cache to miss (RESULTS.md: 1.3-3 µs per local pose at 1 cm on the shared rigs). The trade
// is memory: memory_bytes() is about 5x the packed bytes (docs/packing.md).
//
// Contract: pose / local_pose give exactly the bits of GroupDecoder::decode_pose / decode_local_pose
// (the bits the encoder verified against the bound). InvalidArgument on a bad clip or frame;
// mocapdb::Error from the constructor on malformed window bytes (every window is decoded there).
// Ownership and threads: refers to `decoder` (must outlive the index; only read). Immutable after
// construction; every const method is thread-safe (per-thread scratch, allocated on a thread's first
// call, none per pose after that).
// Memory: 4 bytes per nonzero coefficient, 4 more per level too large for its word (rare), 32 per
// window and the W x W time basis. Holds groups of up to 2^20 coefficients
// per window (Da x W: e.g. 4096 varying dofs at W = 256); InvalidArgument beyond.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mocapdb/packing/group_decoder.hpp"

namespace mocapdb::packing {

class PoseIndex {
public:
    explicit PoseIndex(const GroupDecoder& decoder);

    /// The frame's channel row into out_row (decoder.skeleton(clip)->channel_count() values).
    void pose(std::size_t clip, std::size_t frame, double* out_row) const;
    /// The frame's local joint transforms (LocalPose, group_decoder.hpp) into out (resized to the
    /// skeleton's joints; no allocation once it has that size).
    void local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const;

    /// Bytes this index holds (the decoder's packed bytes not included).
    std::size_t memory_bytes() const;
    /// Nonzero coefficients held (over every coded window).
    std::size_t coefficient_count() const { return words_.size(); }
    /// Levels too large for their words, held apart.
    std::size_t escaped_count() const { return exceptions_.size(); }

private:
    struct Window {
        std::uint64_t begin = 0;  ///< first word of the window
        std::uint64_t exceptions = 0;  ///< its first level too large for its word, in exceptions_
        std::uint32_t count = 0;  ///< its nonzero coefficients
        std::uint32_t rows = 0;   ///< dof rows up to the last nonzero one (+1)
        double step = 0.0;        ///< quantizer step
    };
    /// Frame t's dofs of coded window `global` into the scratch's pose buffer.
    const double* dofs(std::size_t clip, std::size_t global, std::size_t t) const;
    /// The frame's dofs after checking the indices (InvalidArgument); nullptr for a window stored as
    /// source rows (the decoder serves those).
    const double* frame_dofs(std::size_t clip, std::size_t frame) const;

    const GroupDecoder* decoder_;
    std::vector<Window> windows_;        ///< per window of the group (raw windows: count 0, unused)
    std::vector<double> time_rows_;      ///< time basis, row t contiguous (W x W)
    static constexpr unsigned kMaxPlaceBits = 20;  ///< leaves 12 bits of a word for a level
    unsigned row_bits_ = 0;              ///< word: dof row | time column << row_bits_ | level << place_bits_
    unsigned place_bits_ = 0;
    std::vector<std::uint32_t> words_;   ///< every coded window's nonzero coefficients, window by window
    std::vector<std::int32_t> exceptions_;  ///< levels outside their word's range (escape: a field of 0)
};

}  // namespace mocapdb::packing
