#pragma once
// A motion set: an ordered list of comparable samples (whole clips or frame ranges of clips) that
// share one skeleton, each with a control-parameter vector.
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"

namespace mocapdb {

/// Frames [begin, end) of a stored clip.
struct SampleRef {
    std::string clip;       ///< clip id in the database
    std::size_t begin = 0;  ///< first frame
    std::size_t end = 0;    ///< one past the last frame
    std::size_t frame_count() const noexcept { return end - begin; }
};

/// Frames of a stored clip whose joint was repaired when the set's samples were taken from it (a
/// solver dropout, see dropout_repair.hpp): joint `joint` at clip frames [begin, end).
struct RepairedFrames {
    std::string clip;
    std::string joint;
    std::size_t begin = 0;
    std::size_t end = 0;
};

struct MotionSet {
    std::string name;
    std::vector<SampleRef> samples;            ///< N samples
    std::vector<std::string> parameter_names;  ///< P names
    std::vector<std::string> parameter_units;  ///< P units ("cm", "rad", "cm/s", "" ...)
    MatX parameters;                           ///< N by P control parameters
    /// Periods of periodic parameters (e.g. 2 pi for a bearing in rad), 0 for a linear one: P values, or
    /// empty when every parameter is linear. Kriging measures distances along a periodic axis on a
    /// circle (kriging/trend.hpp ControlScaling), so c and c + period are the same request.
    VecX parameter_periods;
    std::string parameter_source;  ///< how they were obtained ("csv:FILE", "extract:...")
    /// True when the clips were checked for dropouts as the set was built (sets stored before that
    /// check existed read as false and are taken as stored, unrepaired).
    bool dropouts_checked = false;
    /// The repaired runs of the set's clips (with dropouts_checked; clip order, then joint, frame).
    /// Samples are the clips' frames with these repairs applied (with_repairs, dropout_repair.hpp).
    std::vector<RepairedFrames> repairs;
};

/// Throws InvalidArgument unless: a non-empty name, at least one sample, every sample has at least
/// two frames, the parameter matrix is N by P with P names and P units, all finite; parameter_periods
/// empty or P finite values >= 0.
void validate(const MotionSet& set);

/// Marks parameter `name` periodic with `period` (> 0, finite; in the parameter's unit), or linear with 0.
/// InvalidArgument naming the set's parameters when there is no such parameter, or for a bad period.
void set_parameter_period(MotionSet& set, const std::string& name, double period);

/// Throws InvalidArgument, saying why, when the set cannot serve to tell motions apart by their
/// parameters: fewer than 2 samples, or (with parameters) every sample at the same parameter vector
/// (kriging would get a degenerate kernel and give one motion for every request). Checked where sets
/// are created; stored sets of earlier versions still load.
void check_distinguishable(const MotionSet& set);

}  // namespace mocapdb
