#pragma once
// Poses of a packed group for playback-style access: a per-thread cache of decoded windows.
//
// Details: docs/headers/packing.md (mocapdb/packing/pose_sampler.hpp).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mocapdb/packing/group_decoder.hpp"

namespace mocapdb::packing {

class PoseSampler {
public:
    /// capacity: windows kept decoded (>= 1, InvalidArgument otherwise). Use at least the number of
    /// clips sampled in turn (a crowd of 100 clips needs 100 or more, or every pose misses).
    explicit PoseSampler(const GroupDecoder& decoder, std::size_t capacity = 128);
    ~PoseSampler();
    PoseSampler(PoseSampler&&) noexcept;
    PoseSampler& operator=(PoseSampler&&) noexcept;

    /// The frame's channel row (channel_count() values), valid until the next call on this sampler.
    const double* pose(std::size_t clip, std::size_t frame);
    /// The same, copied into out_row.
    void pose(std::size_t clip, std::size_t frame, double* out_row);
    /// The frame's local joint transforms (LocalPose, group_decoder.hpp) into out (resized to the
    /// skeleton's joints; no allocation once it has that size). Equal to decoder.decode_local_pose
    /// bit for bit; its rotations are those of pose(clip, frame) to ~1e-15. Computed on every call
    /// from the cached pose vector (one exp map per joint, no Euler angles); the row is not formed.
    void local_pose(std::size_t clip, std::size_t frame, LocalPose& out);

    std::size_t channel_count() const { return channels_; }
    std::size_t capacity() const;
    /// Requests whose window was already decoded / had to be decoded (since construction or clear()).
    std::size_t hits() const { return hits_; }
    std::size_t misses() const { return misses_; }
    /// Forgets every decoded window (keeps the memory).
    void clear();

private:
    struct Slot;
    std::size_t fill(std::size_t clip, std::size_t window, std::uint64_t global);
    /// The frame's slot (decoding its window on a miss); counts the hit or miss.
    Slot& slot(std::size_t clip, std::size_t frame);
    /// Frame t's dofs in slot s (a coded window), reconstructed on first use.
    const double* dofs(Slot& s, std::size_t clip, std::size_t t);

    const GroupDecoder* decoder_;
    std::size_t channels_ = 0;
    std::vector<Slot> slots_;
    std::vector<std::int32_t> slot_of_;        ///< per window of the group: its slot, or -1
    std::vector<std::uint64_t> first_window_;  ///< per clip: its first window's index in the group
    std::unique_ptr<detail::WindowScratch> scratch_;
    std::uint64_t tick_ = 0;
    std::size_t hits_ = 0;
    std::size_t misses_ = 0;
};

}  // namespace mocapdb::packing
