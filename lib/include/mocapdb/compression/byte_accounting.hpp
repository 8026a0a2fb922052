#pragma once
// Honest byte accounting: a compressed set is charged for everything needed to rebuild
// its samples with their timing and control parameters, at float32 unless a codec says otherwise.
#include <cstdint>

#include "mocapdb/compression/set_model.hpp"

namespace mocapdb::compression {

constexpr std::uint64_t kFloat32 = 4;

/// Raw size of the aligned tensor as float32: 4 D T N.
std::uint64_t aligned_float32_bytes(const Tensor3& poses);

/// What every method needs besides the poses themselves, float32: warps (T N), control parameters
/// (N P) and the per-sample canonicalization (x, z, yaw: 3 N).
std::uint64_t side_info_bytes(Eigen::Index frames, Eigen::Index samples, Eigen::Index parameters);

/// A Tucker set model at float32: core, three bases, mean and weight (2 D). The weights follow from
/// the skeleton, but are charged anyway so that a reader needs nothing else.
std::uint64_t tucker_float32_bytes(const SetModel& model);

}  // namespace mocapdb::compression
