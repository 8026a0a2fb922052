#pragma once
// Error-bounded packing of a group of clips (one skeleton topology, one frame rate) into bytes.
//
// Details: docs/headers/packing.md (mocapdb/packing/packed_group.hpp).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/packing/byte_parts.hpp"
#include "mocapdb/packing/error_stats.hpp"

namespace mocapdb::packing {

/// What pack_group writes. Runtime (format 4): the group's header, then a body from which one pose
/// decodes in about a microsecond with nothing decoded before it (time-local keys and detail levels,
/// static codes; runtime_decoder.hpp), at somewhat more bytes than Archive on fine bounds (RESULTS.md).
/// Archive (format 3): whole windows range-coded with adaptive contexts, the smallest bytes, a pose
/// costs its window's decoding (15-100 µs). Both meet E on every source frame, and GroupDecoder reads both.
enum class PackFormat { Runtime, Archive };

/// The time basis of a group: learned (eigenvectors of the windows' time second moment) or the
/// orthonormal DCT-II (cosines); Auto tries both on a sample of the group (see PackOptions).
enum class TimeBasis { Auto, Learned, Cosine };
/// The dof basis of a group: learned (eigenvectors of the dof second moment) or none (identity).
enum class DofBasis { Auto, Learned, Identity };

struct PackOptions {
    double max_error_cm = 1.0;  ///< E, > 0 and finite
    PackFormat format = PackFormat::Runtime;
    /// Runtime format: frames from key to key, 8 (a cold pose reads three detail columns: 10-20 %
    /// faster than 16), 16 (four; 3-10 % fewer bytes where keys are a large share, as on CMU ASF/AMC)
    /// or 0 (both encoded, 8 kept unless 2.5 % larger: RuntimeOptions::window, runtime_encoder.hpp). A
    /// group with more active dofs than the runtime format holds (1024), or with a frame that no
    /// quantizer step of the runtime format brings within E, is written in the Archive format
    /// (PackStats::format says which).
    int runtime_window = 8;
    int window = 32;  ///< Archive format: W, source frames per window, 2 ... 256
    /// Quantizer rounding offset in [0.1, 0.5]: q = sign(c)·floor(|c|/step + rounding). 0.5 is plain
    /// rounding; smaller values widen the zero bin (fewer nonzero coefficients, finer step needed).
    double rounding = 0.4;
    /// Try the roundings 0.5, 0.4, 0.3, 0.2 in every window and keep the one whose coefficients code
    /// smallest (rounding is then ignored). About 4x the encode time.
    bool rounding_search = false;
    /// After a window's step is chosen, drop up to this many of the last nonzero +-1 coefficients in
    /// scan order where the window still meets the bound (0 = off).
    int trim_tail = 64;
    int threads = 2;  ///< encoder threads (>= 1)
    /// Bases (Archive format; the Runtime format uses the learned dof basis unless dof_basis is
    /// Identity, and no time basis). With Auto, each candidate combination is packed on a sample of the group (every k-th
    /// clip, k = ceil(clips / 8), each cut to its first 4000 frames) and the one with the fewest
    /// estimated bytes for the whole group is used (about +60% encode time). Both kinds are stored
    /// the same way, so the decoder does not know or care which was chosen.
    TimeBasis time_basis = TimeBasis::Auto;
    DofBasis dof_basis = DofBasis::Auto;
    /// Also measure what libzstd (level 19) makes of the same quantized coefficients (PackStats::
    /// zstd_*): a measurement for the design, not a format option. Costs encode time.
    bool compare_zstd = false;
};

/// Where the bytes went and what the error is (measured at encode time, on every source frame).
struct PackStats {
    PackFormat format = PackFormat::Archive;  ///< what the bytes are
    std::size_t clips = 0;
    std::size_t frames = 0;
    std::size_t windows = 0;        ///< windows (Runtime: from key to key)
    std::size_t channels = 0;       ///< channels per frame (float32 reference = frames·channels·4)
    std::size_t bytes = 0;          ///< total
    std::size_t header_bytes = 0;   ///< topology, skeletons, bases, contexts
    std::size_t table_bytes = 0;    ///< per-clip and per-window entries (Runtime: the clip table)
    std::size_t payload_bytes = 0;  ///< coded coefficients (Runtime: the body)
    /// Bytes per kind of stored data, summing exactly to `bytes`: header, topology, skeletons,
    /// constant_dofs, bases, contexts, clip_table, window_table, payload (coded windows), raw_windows
    /// (windows stored as source rows). Runtime: header, topology, skeletons, constant_dofs, bases,
    /// clip_table, checksum, then the body's body_header, code_tables (quad codes, key widths and
    /// centers, directory widths), offsets (each window's byte offset), payload (keys and windows) and
    /// slack (zero bytes that let the decoder read 8 bytes at a time). An empty group has only "header".
    ByteParts parts;
    std::size_t probes = 0;       ///< window decodes tried while choosing steps
    std::size_t raw_windows = 0;  ///< windows stored as source rows (no step met the bound)
    ErrorStats error;
    double encode_seconds = 0.0;
    int runtime_window = 0;                     ///< Runtime: W used (8 or 16)
    TimeBasis time_basis = TimeBasis::Learned;  ///< the bases used (never Auto)
    DofBasis dof_basis = DofBasis::Learned;
    /// With compare_zstd: the coefficients (zigzag varints after the step byte, per window) as
    /// zstd frames, one per window (random access); one per window with a 16 kB dictionary trained
    /// on the group (dictionary included); and one stream of all windows (no random access).
    std::size_t zstd_window_bytes = 0;
    std::size_t zstd_dictionary_bytes = 0;
    std::size_t zstd_stream_bytes = 0;
};

struct PackedGroup {
    std::vector<std::uint8_t> bytes;
    PackStats stats;
};

/// Thrown when a window cannot meet the bound even stored as its source channel rows (a window that
/// no quantization step brings within the bound is stored that way, see PackStats::raw_windows):
/// only when the float32-rounded skeleton alone moves a joint by more than E.
class PackingFailed : public Error {
public:
    using Error::Error;
};

/// Packs `clips` (same topology and frame rate; InvalidArgument otherwise, or when options are out of
/// range: E <= 0 or not finite, W outside 2..256). An empty list gives a valid empty group.
PackedGroup pack_group(const std::vector<const Clip*>& clips, const PackOptions& options,
                       const ProgressCallback& progress = {});

/// Splits a collection into groups of one topology and frame rate (indices into `clips`, each group
/// in input order, groups in order of first appearance).
std::vector<std::vector<std::size_t>> group_clips(const std::vector<const Clip*>& clips);

}  // namespace mocapdb::packing
