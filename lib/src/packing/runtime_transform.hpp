#pragma once
// The runtime tier's closed-loop transform (internal to the packing module): per clip, y = U⁻¹ x of
// every frame (x: weighted active dofs, U: the group's dof basis), keys every W frames at their own
// step, and between them hierarchical levels, each frame predicted from decoded frames on its path
// (runtime_layout.hpp's predictors, one per window and level) and the difference quantized. Every key
// and every level of a window takes the coarsest step (galloping from the previous one, then two and
// four indices coarser tried) for which every one of its source frames stays within E by forward kinematics of every joint and end site,
// through the decoder's own y -> dofs -> row (runtime_pose_plan.hpp): what is checked is what any
// decode gives.
#include <vector>

#include "group_model.hpp"
#include "runtime_layout.hpp"
#include "runtime_pose_plan.hpp"

namespace mocapdb::packing::detail {

/// `clips` in group order (m.clips' order); W a power of two in 2..32; keys key_offset step indices
/// finer than the coarsest that holds (checked again, made finer until they hold). Throws
/// PackingFailed when a frame cannot meet E even at the finest step. Clips run on up to `threads`
/// workers (the result does not depend on their number; a worker's exception reaches the caller);
/// clip_done(i), when set, is called from the workers (concurrently) as each clip i is done.
RuntimeCoefficients runtime_transform(const GroupModel& m, const RuntimePosePlan& plan,
                                      const std::vector<const Clip*>& clips, double max_error_cm, int W, int key_offset,
                                      double rounding, int threads = 1, const ClipDone& clip_done = {});

}  // namespace mocapdb::packing::detail
