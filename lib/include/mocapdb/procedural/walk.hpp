#pragma once
// Procedural walking: a few gait cycles along a circular arc (constant speed and turn rate), with
// footprints planted on the floor (two-bone leg IK: planted feet do not slide), heel strike → foot
// flat → heel rise about the ball of the foot → swing with toe clearance; pelvis bob, sway, rotation
// and list; thorax counter-rotation; arm swing opposite the legs; a head that stays level and looks
// into the turn.
//
// Contract with the project's extractors (param_extractors.hpp) on the whole clip:
//   speed  = horizontal root path length / duration equals speed_m_s · 100 cm/s (the progression speed
//            is calibrated so that the path, pelvis sway included, has exactly that length), and
//   turn   = root heading change equals turn_deg (the clip spans whole gait cycles, so the pelvis's
//            rotation oscillation is in the same phase at both ends).
// Both hold to floating-point rounding in the generated channels (the tests state the tolerance).
//
// Stride: when stride_m is 0 it follows speed (stride = 0.8 m + 0.4 s · speed: 1.32 m at 1.3 m/s, a
// cadence of 118 steps/min); the gait period is rounded to whole frames, so the stride actually used
// (WalkMotion::stride_m) can differ from the requested one by up to speed / (2 · frame_rate).
// The pelvis height and its bob are chosen as high as the legs allow (knees never straighter than
// max_leg_extension), which is what makes long strides lower the body.
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
    double frame_rate = 60.0;        ///< Hz
    int cycles = 3;                  ///< whole gait cycles in the clip, 1 … 20
    double max_leg_extension = 0.985;  ///< hip–ankle distance / leg length never exceeds this (knees ≥ 20°)
};

struct WalkMotion {
    Clip clip;                ///< humanoid_skeleton(), name "walk"
    double stride_m = 0.0;    ///< stride used (see above)
    double cycle_s = 0.0;     ///< gait period
    double progression_cm_s = 0.0;  ///< forward speed of the path the pelvis sways about
    /// Frames in which each foot (0 = left, 1 = right) is planted flat or pivots on its heel or ball,
    /// as generated (the extractors detect contacts on their own from the motion).
    std::vector<std::vector<bool>> planted;
};

/// Generates the walk. Deterministic. InvalidArgument outside the ranges above.
WalkMotion generate_walk(const WalkParams& params, const WalkOptions& options = {});

}  // namespace mocapdb::procedural
