#pragma once
// Random access to any pose of a packed group in a couple of microseconds: the group's windows
// range-decoded once, at construction, and kept in memory as small dense blocks. A pose then costs
// its frame's products only (y = G v_t, x = U y, dofs to channels or local transforms): no range
// decoding (GroupDecoder::decode_pose spends 15-60 µs there) and no window cache to miss
// (RESULTS.md: about 1.5 µs per local pose at 1 cm on the 31-joint ASF rig).
//
// Details: docs/headers/packing.md (mocapdb/packing/pose_index.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mocapdb/packing/group_decoder.hpp"

namespace mocapdb::packing {

class PoseIndex {
public:
    /// Archive groups: their windows decoded here. Runtime groups (format 4) need no index: it holds
    /// nothing and serves every pose from the decoder's cold path (about a microsecond).
    explicit PoseIndex(const GroupDecoder& decoder);

    /// The frame's channel row into out_row (decoder.skeleton(clip)->channel_count() values).
    void pose(std::size_t clip, std::size_t frame, double* out_row) const;
    /// The frame's local joint transforms (LocalPose, group_decoder.hpp) into out (resized to the
    /// skeleton's joints; no allocation once it has that size).
    void local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const;

    /// Bytes this index holds (the decoder's packed bytes not included).
    std::size_t memory_bytes() const;
    /// Nonzero coefficients over every coded window.
    std::size_t coefficient_count() const { return coefficients_; }
    /// Block columns (16 levels each) held with 8-, 16- and 32-bit levels (over every coded window).
    const std::array<std::size_t, 3>& column_widths() const { return column_widths_; }

private:
    static constexpr std::size_t kBlockRows = 16;  ///< dof rows per block (four vectors of 4)
    static constexpr std::size_t kMaxWindow = 65535;
    /// Per block: its columns of 32-bit levels, of 32- or 16-bit levels, and of any width (all kept).
    using BlockEntry = std::array<std::uint16_t, 3>;
    struct Window {
        std::uint64_t begin = 0;   ///< first byte of its blocks' cells in cells_
        std::uint64_t blocks = 0;  ///< first of its block entries in blocks_
        double step = 0.0;         ///< quantizer step
        std::uint32_t rows = 0;    ///< dof rows up to the last nonzero one (+1); 0: raw or all zero
    };
    /// Frame t's dofs of coded window `global` into the scratch's pose buffer.
    const double* dofs(std::size_t clip, std::size_t global, std::size_t t) const;
    /// The frame's dofs after checking the indices (InvalidArgument); nullptr for a window stored as
    /// source rows (the decoder serves those).
    const double* frame_dofs(std::size_t clip, std::size_t frame) const;

    const GroupDecoder* decoder_;
    std::vector<Window> windows_;      ///< per window of the group (raw windows: rows 0, unused)
    std::vector<double> time_rows_;    ///< time basis, row t contiguous (W x W)
    std::vector<BlockEntry> blocks_;   ///< per window, per block
    std::vector<std::uint8_t> cells_;  ///< per block, per column, kBlockRows levels of the column's width
    std::size_t coefficients_ = 0;
    std::array<std::size_t, 3> column_widths_{};
};

}  // namespace mocapdb::packing
