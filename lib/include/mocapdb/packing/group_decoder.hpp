#pragma once
// Decoding a packed group (packed_group.hpp): any clip, any frame range, one window at a time, or one
// pose by random access. Immutable after construction; every const method is thread-safe (no caches;
// decode buffers are per thread, thread_local, allocated on a thread's first decode and reused).
//
// A frame decodes to the same bits by every path (decode_pose, decode_window, decode_frames,
// decode_clip, PoseSampler): the bits the encoder verified against the bound.
//
// Cost of one pose (decode_pose, cold). Runtime groups (format 4, what `pack` writes by default): its
// two keys and its path of detail columns, about a microsecond (RuntimeDecoder). Archive groups
// (format 3): its window's coefficients are range-decoded whole (every time-basis vector spans the
// window), 15-100 µs; for many poses from the same windows use a PoseSampler (pose_sampler.hpp),
// which keeps decoded windows, and for random poses in a few µs a PoseIndex (pose_index.hpp), which
// keeps the whole group entropy-decoded.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mocapdb/motion/clip.hpp"
#include "mocapdb/packing/packed_group.hpp"

namespace mocapdb::packing {

namespace detail {
struct GroupModel;
struct WindowEntry;
struct WindowScratch;
}  // namespace detail

class PoseSampler;
class PoseIndex;
class RuntimeDecoder;

/// One frame as animation runtimes consume it (ACL, ozz-animation): per joint of the clip's skeleton
/// (GroupDecoder::skeleton(clip)->joints() order, end sites included) the LOCAL transform forward
/// kinematics composes: world_j = world_parent · (translations[j], rotations[j]).
///   rotations[j]    unit quaternion equal (to ~1e-15, up to sign) to Skeleton::local_rotation of the
///                   frame's channel row, i.e. C · R(Euler channels) · C⁻¹ with C the ASF bone axis
///                   (identity for BVH), so FK of a LocalPose is FK of the row and the packed error
///                   bound holds for it. Joints without rotation channels: their rest rotation.
///   translations[j] Skeleton::local_translation of that row (cm): the offset, with the root's (motion
///                   root's) and any moving position channels applied.
/// Computed from the decoded pose vector (exp map -> quaternion, projected onto the channel axes for
/// joints with one or two rotation channels), never through Euler angles.
struct LocalPose {
    std::vector<Quat> rotations;
    std::vector<Vec3> translations;
};

class GroupDecoder {
public:
    /// Parses the group's header; throws mocapdb::Error when the bytes are malformed or truncated.
    explicit GroupDecoder(std::vector<std::uint8_t> bytes);
    ~GroupDecoder();
    GroupDecoder(GroupDecoder&&) noexcept;
    GroupDecoder& operator=(GroupDecoder&&) noexcept;

    /// Runtime (format 4: every method reads the stored bytes through a RuntimeDecoder, a cold pose
    /// in about a microsecond) or Archive (formats 2 and 3: whole windows range-decoded).
    PackFormat format() const;
    std::size_t clip_count() const;
    std::size_t frame_count(std::size_t clip) const;
    double frame_rate() const;
    /// Frames per window (W); window w of a clip holds frames [w·W, min((w+1)·W, frames)). Runtime:
    /// frames from key to key.
    std::size_t window_length() const;
    std::size_t window_count(std::size_t clip) const;
    /// Coded bytes of the clip's windows (payload only: the header and tables are shared; Runtime:
    /// its keys and windows).
    std::size_t clip_payload_bytes(std::size_t clip) const;
    /// Memory the decoder holds beyond its copy of the stored bytes, counted from its containers'
    /// capacities (allocator overhead not counted): the parsed model (bases, scan and context tables,
    /// skeletons, per-clip and per-window entries, scan classes) plus one thread's decode scratch.
    std::size_t resident_bytes() const;
    /// The clip's skeleton as decoded (offsets and axes rounded to float32).
    std::shared_ptr<const Skeleton> skeleton(std::size_t clip) const;

    /// Channel rows of one window (rows = its frames). InvalidArgument on a bad index.
    FrameMatrix decode_window(std::size_t clip, std::size_t window) const;
    /// Channel rows of frames [begin, end) (decoded window by window).
    FrameMatrix decode_frames(std::size_t clip, std::size_t begin, std::size_t end) const;
    /// The whole clip (skeleton, rate, every frame).
    Clip decode_clip(std::size_t clip) const;
    /// One frame's channel row into out_row (skeleton(clip)->channel_count() values), the same bits
    /// as that row of decode_window. InvalidArgument on a bad index; does not allocate after a
    /// thread's first call (for a given group size).
    void decode_pose(std::size_t clip, std::size_t frame, double* out_row) const;
    /// One frame's local joint transforms (LocalPose) into out, resized to the skeleton's joints
    /// (no allocation once out has that size, after a thread's first decode). Same cost as
    /// decode_pose (the window's range decoding dominates); InvalidArgument on a bad index.
    void decode_local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const;

private:
    friend class PoseSampler;
    friend class PoseIndex;
    void check(std::size_t clip) const;
    void check(std::size_t clip, std::size_t frame) const;
    const detail::WindowEntry& entry(std::size_t clip, std::size_t window) const;
    /// Frames of window `window` of the clip (W, fewer for the last window).
    int frames_in(std::size_t clip, std::size_t window) const;
    /// Raw windows: the stored rows of frames [t0, t0 + count) into out (row-major).
    void raw_rows(const detail::WindowEntry& e, int frames, std::size_t channels, int t0, int count, double* out) const;
    /// Coded windows: range-decodes into s.q and lists the nonzero scan positions in s.nonzero
    /// (returns their number).
    std::size_t decode_levels(const detail::WindowEntry& e, detail::WindowScratch& s) const;
    /// Coded windows: range-decodes and dequantizes into s.g / s.columns.
    void load_window(const detail::WindowEntry& e, detail::WindowScratch& s) const;
    std::vector<std::uint8_t> bytes_;
    std::unique_ptr<detail::GroupModel> model_;  ///< Archive formats (null for a runtime group with clips)
    std::unique_ptr<RuntimeDecoder> runtime_;    ///< Runtime format, viewing bytes_
    std::size_t payload_ = 0;
    std::size_t channels_ = 0;
    /// Scan-position classes per step index, for the steps the window table uses (empty otherwise).
    std::vector<std::vector<std::uint8_t>> classes_;
};

}  // namespace mocapdb::packing
