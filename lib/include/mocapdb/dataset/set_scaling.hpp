#pragma once
// The control-space scaling of a motion set's parameters for kriging and its relatives: standardized
// numeric axes, the set's periodic axes on circles and its categorical axes as level indicators
// (kriging/trend.hpp ControlScaling; docs/synthesis.md). Plain function of the set; no errors beyond
// ControlScaling::from_data's.
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/kriging/trend.hpp"

namespace mocapdb {

/// ControlScaling::from_data over the set's parameters with its periods and level counts.
inline kriging::ControlScaling set_control_scaling(const MotionSet& set) {
    return kriging::ControlScaling::from_data(set.parameters, set.parameter_periods, parameter_level_counts(set));
}

}  // namespace mocapdb
