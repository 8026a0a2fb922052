#pragma once
// Procedural walking: a few gait cycles along a circular arc (constant speed and turn rate), with
// footprints planted on the floor (two-bone leg IK: planted feet do not slide), heel strike → foot
// flat → heel rise about the ball of the foot → swing with toe clearance; pelvis bob, sway, rotation
// and list; thorax counter-rotation; arm swing opposite the legs; a head that stays level and looks
// into the turn.
//
// Details: docs/headers/procedural.md (mocapdb/procedural/walk.hpp).
#include <cstddef>
#include <vector>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb::procedural {

struct WalkParams {
    double speed_m_s = 1.3;  ///< 0.4 … 1.9 m/s
    double turn_deg = 0.0;   ///< heading change over the whole clip, degrees (+ = left), |turn| ≤ 180
    double stride_m = 0.0;   ///< two steps, m; 0 = from speed; else 0.6 … 2.0 m
};

struct WalkOptions {
    double frame_rate = 60.0;          ///< Hz
    int cycles = 3;                    ///< whole gait cycles in the clip, 1 … 20
    double max_leg_extension = 0.985;  ///< hip–ankle distance / leg length never exceeds this (knees ≥ 20°)
};

struct WalkMotion {
    Clip clip;                      ///< humanoid_skeleton(), name "walk"
    double stride_m = 0.0;          ///< stride used (see above)
    double cycle_s = 0.0;           ///< gait period
    double progression_cm_s = 0.0;  ///< forward speed of the path the pelvis sways about
    /// Frames in which each foot (0 = left, 1 = right) is planted flat or pivots on its heel or ball,
    /// as generated (the extractors detect contacts on their own from the motion).
    std::vector<std::vector<bool>> planted;
};

/// Generates the walk. Deterministic. InvalidArgument outside the ranges above.
WalkMotion generate_walk(const WalkParams& params, const WalkOptions& options = {});

}  // namespace mocapdb::procedural
