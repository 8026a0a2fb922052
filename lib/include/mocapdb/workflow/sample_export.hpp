#pragma once
// A sample of an aligned set back at its own timing (`mocapdb export --set S --sample I`):
// its aligned poses (from the set's tensor or a model's reconstruction) resampled at the sample's own
// frames through its warp, and placed back where it was (its canonical transform), as a clip.
// Errors: InvalidArgument for a sample out of range or poses of another shape. Threads: reads only.
#include <string>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/core/tensor3.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"

namespace mocapdb::workflow {

/// `poses` is D by T by N like data.aligned.tensor; the clip is named `name`.
Clip sample_at_own_timing(const AlignedSetData& data, const Tensor3& poses, Eigen::Index sample,
                          const std::string& name);

}  // namespace mocapdb::workflow
