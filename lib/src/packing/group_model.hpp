#pragma once
// What the encoder and the decoder of one packed group share (internal to the packing module): the
// skeletons as the decoder sees them (float32-rounded), the per-clip canonicalizations, the learned
// bases, the scan order, the trained contexts, and the one reconstruction routine both use, so that
// the error verified at encode time is exactly the error of any later decode.
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/packing/byte_parts.hpp"
#include "mocapdb/packing/coefficient_coder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "channel_writer.hpp"

namespace mocapdb::packing::detail {

class ByteWriter;
class ByteReader;

/// 3: the skeletons keep what the pose vector <-> channel mapping depends on besides offsets and
/// axes: the motion root (in the topology) and the position-channel convention (per skeleton).
/// Version 2 stored neither: its bytes are read as motion root 0 and positions added to OFFSET,
/// the skeleton its encoder verified with (the same bits). Version 1 bytes (frames reconstructed
/// window-wide) decode to different bits than their encoder verified and are refused.
constexpr std::uint8_t kFormatVersion = 3;
constexpr std::uint8_t kOldestFormatVersion = 2;
/// 4, the runtime group: version 3's header without what only its windows need (time basis,
/// energies, contexts, window table), then the runtime body (runtime_layout.hpp) to the end.
constexpr std::uint8_t kRuntimeFormatVersion = 4;
/// Weight of a translation dof (cm) relative to a rotation dof's lever weight (see weights_of).
constexpr double kTranslationWeight = 3.0;
/// Range (pose units: cm or rad) under which a dof counts as constant in the group.
constexpr double kConstantTolerance = 1e-6;
/// Quantum of the stored basis entries (the encoder inverts the quantized bases, so this costs
/// compactness only, never accuracy).
constexpr double kBasisStep = 1.0 / 4096.0;

/// Step of quantizer index k (0..kMaxStep): 2^(k/12 - 14) weighted cm (6e-5 ... 140).
double step_of(int k);
constexpr int kMaxStep = 254;
/// Step byte of a window stored as its source channel rows (float64, row-major, little-endian).
constexpr std::uint8_t kRawStep = 255;

struct SkeletonEntry {
    std::shared_ptr<const Skeleton>
        skeleton;                        ///< float32-rounded offsets and axes; the source's convention and motion root
    VecX weights;                        ///< D weights (pose dofs, then extra position channels)
    ChannelWriter writer;                ///< pose vector -> channel row of `skeleton`
    std::vector<double> active_weights;  ///< weights[active[i]] (set with the active dofs)
    /// What the bytes hold of each joint's axis (four float32 coefficients) and of the forward
    /// direction (three), which `skeleton` normalizes. Written as they are, so that the decoder
    /// normalizes the same values to the same skeleton (writing the normalized values rounded again
    /// moved positions by up to 5e-7 cm).
    std::vector<std::array<float, 4>> stored_axes;
    std::array<float, 3> stored_forward{};
};

struct ClipEntry {
    std::uint32_t skeleton = 0;
    std::uint64_t frames = 0;
    Canonicalization canonical;  ///< float32-rounded (set_canonical)
    Placement placement;         ///< canonical's, for the channel writer
    void set_canonical(const Canonicalization& c) {
        canonical = c;
        placement = Placement(c);
    }
    std::uint64_t first_window = 0;  ///< index into windows
};

struct WindowEntry {
    std::uint8_t step = 0;
    std::uint64_t offset = 0;  ///< into the payload
    std::uint32_t size = 0;
};

/// Caller-owned buffers of one window's decode: sized on first use, then reused without allocating.
struct WindowScratch {
    std::vector<std::int32_t> q;  ///< quantized coefficients, scan order
    std::vector<std::uint8_t> level;
    std::vector<std::uint32_t> nonzero;  ///< scan positions of the nonzero coefficients (the decoder's)
    std::vector<double> g;               ///< dequantized coefficients, Da by W, column-major
    int columns = 0;                     ///< time columns of g up to its last nonzero one
    int rows = 0;                        ///< dof rows of g up to its last nonzero one
    std::vector<double> y, x, p;         ///< one frame: G v_t (Da), U G v_t (Da), pose dofs (D)
    std::vector<double> yb, xb;          ///< kFrameBlock frames of y and x (frames_pose), Da each
    std::vector<double> row;             ///< one channel row (raw windows' local poses)
    ContextSet contexts;
};

/// The calling thread's scratch (GroupDecoder's and PoseIndex's const methods stay thread-safe and
/// allocate only on a thread's first use).
WindowScratch& thread_scratch();

/// Frames frames_pose reconstructs together (register-blocked over frames: the coefficients and
/// the dof basis are read once per block instead of once per frame).
constexpr int kFrameBlock = 4;

struct GroupModel {
    /// A runtime group (format 4): no time basis, energies, contexts or windows; the body follows the
    /// clip table.
    bool runtime = false;
    std::uint32_t body_crc = 0;  ///< runtime group: CRC-32 (zlib's) of the body
    double frame_rate = 0.0;
    int window = 0;                  ///< W (format 3; 0 in a runtime group)
    int pose_dofs = 0;               ///< D0 (pose vector)
    int dofs = 0;                    ///< D = D0 + extra
    std::vector<int> extra_columns;  ///< channel columns of non-root position channels (extra dofs)
    std::vector<SkeletonEntry> skeletons;
    /// Dofs that vary in the group (indices into D); the others are constant[d] (pose units) in
    /// every frame of every clip (to within kConstantTolerance) and are not transformed.
    std::vector<int> active;
    std::vector<double> constant;         ///< D entries (used where not active)
    MatX dof_basis;                       ///< Da by Da (columns: basis vectors), entries multiples of kBasisStep
    MatX time_basis;                      ///< W by W, entries multiples of kBasisStep
    std::vector<float> dof_energy;        ///< Da, eigenvalues of the dof second moment per window, descending
    std::vector<float> time_energy;       ///< W
    std::vector<std::uint32_t> scan;      ///< scan position -> r1 + D * r2
    std::vector<std::uint16_t> scan_row;  ///< scan position -> r1 (dequantize, without a division)
    std::vector<float> sigma;             ///< expected RMS per scan position
    std::vector<double> levels;           ///< class_levels(sigma)
    ContextSet contexts;
    std::vector<ClipEntry> clips;
    std::vector<WindowEntry> windows;

    /// The scan as the coefficient coder sees it (grid rows = Da).
    ScanGrid grid() const { return ScanGrid{&scan, static_cast<int>(std::max<std::size_t>(1, active.size()))}; }
    /// Fills scan and sigma from the energies.
    void build_scan();
    /// Unweighted dofs (D by F: pose vector, then extra position channels) of a clip.
    MatX dofs_of(const Clip& clip, const Canonicalization& canonical) const;
    /// Weighted active dofs (Da by F) of a clip whose skeleton is `entry`.
    MatX weighted_active(const Clip& clip, const SkeletonEntry& entry, const Canonicalization& canonical) const;
    /// Once active and constant are known: joints whose pose dofs are all constant get their channels
    /// computed once per skeleton (ChannelWriter::fold_constants) instead of in every frame.
    void fold_constant_joints();
    /// Sizes the scratch for this group.
    void prepare(WindowScratch& s) const;
    /// s.g, s.columns and s.rows from quantized coefficients `q` (scan order; n may be short of Da·W,
    /// the rest are zero). Only the first s.columns columns of s.g are written (zeros included): the
    /// frame products read no further.
    void dequantize(int step_index, const std::int32_t* q, std::size_t n, WindowScratch& s) const;
    /// The same from the decoder's list of nonzero scan positions (`count` of them, ascending; q zero
    /// elsewhere): the same s.g, s.columns and s.rows, touching only the nonzero coefficients.
    void dequantize_nonzero(int step_index, const std::int32_t* q, const std::uint32_t* nonzero, std::size_t count,
                            WindowScratch& s) const;
    /// Channel row of frame t (0 <= t < W) of a window's dequantized coefficients g: x = U (G v_t), summed in a
    /// fixed order (time column, then dof basis column), then pose dofs -> channels. Every decode
    /// path and the encoder's check go through here, so a frame has the same bits however decoded.
    /// `g` and `columns` as dequantize leaves them in s (or a copy of them); s's frame buffers are used.
    /// `rows` (dequantize's s.rows): rows of g past it are zero, and so are their terms (skipped:
    /// adding U·(+0) to a sum started at +0 never changes its bits).
    void frame_row(const ClipEntry& clip, const double* g, int columns, int rows, int t, WindowScratch& s,
                   double* row) const;
    /// The first half of frame_row: frame t's dofs (D values: pose vector, then extra position
    /// channels, pose units) into p. frame_row is frame_pose then row_of.
    void frame_pose(const ClipEntry& clip, const double* g, int columns, int rows, int t, WindowScratch& s,
                    double* p) const;
    /// frame_pose's second half: x = U y (y: Da values, zero from `rows` on, whose terms are skipped),
    /// then the dofs into p. PoseIndex forms y by frame_pose's sums and ends here too.
    void pose_of(const ClipEntry& clip, const double* y, int rows, WindowScratch& s, double* p) const;
    /// frame_pose of the kFrameBlock frames t0, t0 + 1, ... (t0 + kFrameBlock <= W) into p (D values
    /// per frame, one frame after the other): the same bits per frame as frame_pose, about half the
    /// time per frame.
    void frames_pose(const ClipEntry& clip, const double* g, int columns, int rows, int t0, WindowScratch& s,
                     double* p) const;
    /// The weighted active dofs x (Da, divided in place) into their places in p.
    void unweight(double* x, const SkeletonEntry& entry, double* p) const;
    /// The second half: the channel row of dofs p.
    void row_of(const ClipEntry& clip, const double* p, double* row) const;
    /// Local joint transforms of dofs p (out sized to the skeleton here).
    void local_of(const ClipEntry& clip, const double* p, LocalPose& out) const;
    /// Local joint transforms of a channel row (raw windows), straight from the skeleton.
    void local_of_row(const ClipEntry& clip, const double* row, LocalPose& out) const;
    /// Channel rows of frames [0, count) of a window from its quantized coefficients (scan order).
    void reconstruct(const ClipEntry& clip, int step_index, const std::vector<std::int32_t>& q, int count,
                     WindowScratch& s, FrameMatrix& out_rows) const;

    /// Header and tables (everything but the window payloads) and their parse. With `parts`, the
    /// bytes of each section are added to it by name (header, topology, skeletons, constant_dofs,
    /// bases, contexts, clip_table, window_table).
    void write_header(std::vector<std::uint8_t>& out, ByteParts* parts = nullptr) const;
    void write_clip_table(ByteWriter& w) const;
    /// Parses a header; returns the offset of the payload (of a runtime group: of its body).
    std::size_t read_header(const std::uint8_t* data, std::size_t size);
    /// The clip table (clips' entries); returns the group's window count (0 in a runtime group).
    std::uint64_t read_clip_table(ByteReader& r, std::uint64_t clip_count);
};

/// The decoder's copy of a skeleton (offsets, axes, forward rounded to float32) and its dof weights
/// (rotations: position_error_weights relative to the root translation's; translations: kTranslationWeight).
SkeletonEntry make_entry(const Skeleton& source, int pose_dofs, std::size_t extra);
/// The same from what the bytes hold: `joints` with float32 offsets (their axes are replaced by
/// `axes` normalized), units with a float32 cm_per_unit, the forward direction, the position-channel
/// convention and the motion root. make_entry(s) is stored_entry of s's values rounded to float32,
/// so encoder and decoder use the same skeleton to the bit.
SkeletonEntry stored_entry(std::vector<Joint> joints, const SourceUnits& units, const std::array<float, 3>& forward,
                           const std::vector<std::array<float, 4>>& axes, PositionChannels positions,
                           std::size_t motion_root, int pose_dofs, std::size_t extra);

/// A basis (entries rounded to multiples of kBasisStep) as coded bytes, and back (n by n).
std::vector<std::uint8_t> encode_basis(const MatX& basis);
MatX decode_basis(const std::uint8_t* data, std::size_t size, Eigen::Index n);

/// Same joints, channels, orders, end sites and motion root (offsets, axes and the position-channel
/// convention may differ: each skeleton of a group keeps its own).
bool same_topology(const Skeleton& a, const Skeleton& b);

/// Row columns of the position channels the pose vector does not carry (the extra dofs): those of
/// every joint outside the motion-root chain (the motion root's are its pose translation; the
/// joints above it stay at rest), in row order.
std::vector<int> extra_position_columns(const Skeleton& s);

}  // namespace mocapdb::packing::detail
