#include "mocapdb/workflow/set_rate_report.hpp"

#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb::workflow {

RateOutcome rate_report(const AlignedSetData& c, compression::RateOptions options) {
    options.parameters = c.set.parameters.cols();
    RateOutcome r;
    r.report = compression::rate_distortion(c.aligned.tensor, c.skeleton, options);
    r.clip_bytes = 4 * c.clip_channel_values;
    r.seconds = c.seconds_of_motion;
    r.joints = PoseLayout(*c.skeleton).rotation_joints().size();
    return r;
}

}  // namespace mocapdb::workflow
