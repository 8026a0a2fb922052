#pragma once
// The runtime body's layout (internal to the packing module), shared by its encoder
// (runtime_transform.cpp, runtime_writer.cpp) and its decoder (runtime_decoder.cpp).
// docs/packing.md ("The runtime tier") describes the format.
//
// Body: a 24-byte header (version, log2 W, directory levels, key offset, Da as u16, clips, then the
// byte sizes of the side stream, the offset stream and the entries, each u32 little-endian), the side
// stream (quad code tables; the keys' largest widths and three side codes; per clip its step fields'
// bases (8 bits) and widths (4 bits), field 0 to levels, then its key rows' widths, centers and escape
// widths; per clip the directory widths, its entries' offset line (origin, 34 bits two's complement,
// and slope, 24 bits) and offset width), the offset stream (per clip each entry's byte offset minus
// origin + k · slope, at the clip's width) and the entries (byte-aligned, clip by clip), then
// kRuntimeSlack zero bytes.
//
// An entry: its key (step field 0: the step minus the clip's base; then per row the value minus the
// clip's center at the clip's width for the row; a value outside the width's range is -2^(w-1) in its
// slot and follows the slots at the row's escape width) and, unless it is the clip's last, its window:
// per level l the step field l (level 1: step minus base; deeper: (step minus base) ·
// kRuntimePredictors + predictor), the directory (per level 1..stored the width unless the clip table
// holds it, then each node's left-subtree size in bits), and the detail columns in tree order, each by
// quads.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <zlib.h>

namespace mocapdb::packing::detail {

/// Called with a clip's index when the encoder is done with it (progress).
using ClipDone = std::function<void(std::size_t)>;

/// CRC-32 (zlib's) of a runtime body, as a runtime group's header stores it.
inline std::uint32_t runtime_body_crc(const std::uint8_t* data, std::size_t size) {
    uLong crc = ::crc32(0L, Z_NULL, 0);
    for (std::size_t done = 0; done < size;) {
        const std::size_t chunk = std::min<std::size_t>(size - done, std::size_t{1} << 30);
        crc = ::crc32(crc, data + done, static_cast<uInt>(chunk));
        done += chunk;
    }
    return static_cast<std::uint32_t>(crc);
}

constexpr std::uint8_t kRuntimeVersion = 2;
constexpr std::size_t kRuntimeHeaderBytes = 24;
/// Quads: a pattern when all four values are in [-1, 1] (81 patterns), else a width symbol and the
/// four values at that width; code lengths (and the lookup) kQuadCodeBits; contexts per (level,
/// row >> kQuadShift).
constexpr int kQuadCodeBits = 11;
constexpr int kQuadShift = 3;
constexpr int kQuadPatterns = 81;
constexpr int kQuadMaxWidth = 32;
/// Quad alphabet: 0 end of column, 1 + p pattern p, kQuadWideSymbol + w a quad at width w.
constexpr int kQuadEndSymbol = 0;
constexpr int kQuadWideSymbol = 1 + kQuadPatterns;
constexpr int kQuadAlphabet = kQuadWideSymbol + kQuadMaxWidth + 1;
constexpr int kQuadSymbolBits = 7;
/// Key rows: widths and escape widths at most this; side codes (width deltas, center widths, escape
/// width deltas) over an alphabet of kSideAlphabet symbols, lengths at most kSideCodeBits.
constexpr int kKeyMaxWidth = 40;
constexpr int kSideAlphabet = 41;
constexpr int kSideSymbolBits = 6;
constexpr int kSideCodeBits = 15;
constexpr int kMaxLevels = 5;  ///< W up to 32

/// Predictors of a frame at level >= 2 from its interval's ends lo, hi and the parent interval's far
/// end (third): 0 the mean of lo and hi, c > 0: w0 · near + w1 · far + w2 · third (near: lo or hi,
/// whichever is on third's side), in that order of operations. 1: the quadratic through the three, 2:
/// halfway between 0 and 1.
constexpr int kRuntimePredictors = 3;
constexpr double kRuntimePredictorWeights[kRuntimePredictors][3] = {
    {0.5, 0.5, 0.0}, {0.75, 0.375, -0.125}, {0.625, 0.4375, -0.0625}};

/// Quad contexts per level for Da rows.
inline int quad_contexts_per_level(int da) { return ((da + 3) >> kQuadShift) + 1; }

/// Entries of a clip of F frames at window W: ceil((F - 1) / W) windows and the end key (none for 0 frames).
inline std::size_t runtime_entry_count(std::uint64_t frames, int W) {
    return frames == 0 ? 0
                       : static_cast<std::size_t>((frames - 1 + static_cast<std::uint64_t>(W) - 1) /
                                                  static_cast<std::uint64_t>(W)) +
                             1;
}

/// Column levels and their frames in tree order for windows of W = 2^levels frames.
inline void runtime_tree_order(int W, std::vector<int>& level, std::vector<int>& frame) {
    struct Walk {
        std::vector<int>& level;
        std::vector<int>& frame;
        void run(int lo, int hi, int l) {
            if (hi - lo < 2) return;
            const int mid = (lo + hi) / 2;
            level.push_back(l);
            frame.push_back(mid);
            run(lo, mid, l + 1);
            run(mid, hi, l + 1);
        }
    };
    Walk{level, frame}.run(0, W, 1);
}

/// The quantized transform of a group (runtime_transform.cpp): per clip its windows' entries and its
/// end key.
struct RuntimeEntry {
    int key_step = 0;
    std::vector<std::int32_t> key;                   ///< Da values
    int step = -1;                                   ///< level 1's step index; -1: the end key
    std::vector<int> level_step;                     ///< per level 1..levels its step index (step: level 1's)
    std::vector<int> level_predictor;                ///< per level its predictor (0 at level 1)
    std::vector<std::vector<std::int32_t>> columns;  ///< detail columns in tree order (Da values each)
};
struct RuntimeCoefficients {
    int window = 0, levels = 0, key_offset = 0;
    std::vector<RuntimeEntry> entries;
    std::vector<std::size_t> clip_first;  ///< per clip its first entry (clips.size() + 1 values)
    double max_error_cm = 0.0;            ///< over every source frame (the encoder's check)
};

}  // namespace mocapdb::packing::detail
