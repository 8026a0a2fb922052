#pragma once
// The runtime tier's decoder: one pose of a packed group from its runtime body (encode_runtime,
// runtime_encoder.hpp) in about a microsecond, with nothing kept between calls. Format and
// measurements: docs/packing.md, "The runtime tier".
//
// Ownership: the body is VIEWED (never copied): it must stay alive and unchanged while the decoder
// is used (a runtime group, format 4, holds its body: the whole buffer is viewed). A format-3 group
// beside a separate body is only parsed at construction (its header: skeletons, bases, clip table). Construction checks the body whole (its sizes, code tables, every entry's structure
// and offsets) and builds the decode tables (resident_bytes()); damaged bytes throw mocapdb::Error
// there, so decoding never reads outside the body.
//
// Threads: every const method is thread-safe (per-thread scratch, allocated on a thread's first
// decode and reused). A frame decodes to the same bits by every path (decode_local_pose /
// decode_pose, one frame cold, and decode_local_poses / decode_frames, window by window), the bits the
// encoder checked against E.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mocapdb/motion/clip.hpp"
#include "mocapdb/packing/group_decoder.hpp"

namespace mocapdb::packing {

/// The pose kernels a RuntimeDecoder uses: AVX2 where the CPU has it, or the portable build (the same
/// bits; for tests and benchmarks).
enum class RuntimeKernels { Automatic, Portable };

class RuntimeDecoder {
public:
    /// `group`: a packed group's bytes (pack_group); `body`: encode_runtime's bytes for that group,
    /// viewed. Throws Error when either is malformed, truncated or they do not belong together.
    RuntimeDecoder(const std::uint8_t* group, std::size_t group_size, const std::uint8_t* body, std::size_t body_size,
                   RuntimeKernels kernels = RuntimeKernels::Automatic);
    /// A runtime group (pack_group with PackFormat::Runtime: header and body in one buffer, format
    /// 4), viewed whole; its body's checksum is verified here. Throws Error when the bytes are
    /// malformed, damaged or of another format, or hold no clips.
    RuntimeDecoder(const std::uint8_t* group, std::size_t group_size,
                   RuntimeKernels kernels = RuntimeKernels::Automatic);
    ~RuntimeDecoder();
    RuntimeDecoder(RuntimeDecoder&&) noexcept;
    RuntimeDecoder& operator=(RuntimeDecoder&&) noexcept;

    std::size_t clip_count() const;
    std::size_t frame_count(std::size_t clip) const;
    double frame_rate() const;
    /// Frames from key to key (W).
    std::size_t window_length() const;
    /// Bytes of the clip's entries (its keys and windows; the shared tables not included).
    std::size_t clip_bytes(std::size_t clip) const;
    /// The clip's skeleton as decoded (offsets and axes rounded to float32, as GroupDecoder's).
    std::shared_ptr<const Skeleton> skeleton(std::size_t clip) const;
    /// Memory held beyond the viewed body (containers' capacities): the parsed model (skeletons, dof
    /// basis, clip table), the decode tables (quad lookups, key plans, offsets), the pose kernels'
    /// float basis and lanes, and one thread's scratch.
    std::size_t resident_bytes() const;
    /// Whether the AVX2 pose kernels are in use.
    bool uses_avx2() const;

    /// One frame's local joint transforms (LocalPose, group_decoder.hpp: GroupDecoder::
    /// decode_local_pose's layout and meaning) into out, resized to the skeleton's joints. Cold:
    /// reads the frame's two keys and its path of detail columns only. InvalidArgument on a bad index.
    void decode_local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const;
    /// One frame's channel row into out_row (skeleton(clip)->channel_count() values).
    void decode_pose(std::size_t clip, std::size_t frame, double* out_row) const;
    /// Frames [begin, end) window by window (each window's keys and columns decoded once): the same
    /// bits per frame as decode_local_pose. InvalidArgument on a bad range.
    void decode_local_poses(std::size_t clip, std::size_t begin, std::size_t end, std::vector<LocalPose>& out) const;
    /// Channel rows of frames [begin, end), window by window: the same bits as decode_pose.
    FrameMatrix decode_frames(std::size_t clip, std::size_t begin, std::size_t end) const;
    /// The whole clip (skeleton, rate, every frame).
    Clip decode_clip(std::size_t clip) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mocapdb::packing
