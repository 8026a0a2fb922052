#include "mocapdb/dataset/aligned_timing.hpp"

#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb {

MatX AlignedTiming::inverse_warp_increments() const {
    if (warps.rows() < 2) return MatX(0, warps.cols());
    return warps.bottomRows(warps.rows() - 1) - warps.topRows(warps.rows() - 1);
}

AlignedTiming timing_of(const AlignedSet& aligned) {
    AlignedTiming t;
    t.dof_count = aligned.dofs();
    t.warps = aligned.warps;
    return t;
}

void validate(const AlignedTiming& timing) {
    auto fail = [](const std::string& what) { throw InvalidArgument("aligned set: " + what); };
    if (timing.dofs() < 6 || timing.frames() < 2 || timing.samples() < 1)
        fail("tensor must be at least 6 dofs by 2 frames by 1 sample (warps " + std::to_string(timing.frames()) +
             " by " + std::to_string(timing.samples()) + ", " + std::to_string(timing.dofs()) + " dofs)");
    if (!timing.warps.allFinite()) fail("non-finite warp");
    if ((timing.inverse_warp_increments().array() <= 0.0).any()) fail("warps must be strictly increasing");
}

}  // namespace mocapdb
