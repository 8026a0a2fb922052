#pragma once
// Canonicalizing a sample by its initial direction of travel instead of its first frame's pelvis yaw.
//
// A walker's pelvis yaws by ±10-25° within a gait cycle, so the first frame's heading depends on the
// phase the sample starts at (on walks16 it puts the initial travel direction anywhere in -43..+12°),
// and every sample's canonical path then bends differently. The travel frame turns the sample so that
// the root's horizontal displacement from the first frame to the first frame at least `distance_cm`
// away (about a step and a half of a walk, so the pelvis's lateral sway of a few cm tilts it by a
// few degrees at most; the last frame when the sample never gets that far) points along +Z. Distance
// rather than time, because captured walks often start from standing. A sample whose root ends up
// less than `min_travel_cm` away that way (in-place motions: turning on the spot, reaching, jumping
// up) falls back to the first frame's heading (canonicalization_of). The translation is the first
// frame's root on the floor, as canonicalization_of.
//
// Pure function; InvalidArgument for an invalid clip (validate(Clip)).
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb {

struct TravelFrameOptions {
    double distance_cm = 75.0;     ///< displacement whose direction defines the frame
    double min_travel_cm = 20.0;   ///< below this displacement the first frame's heading is used
};

struct TravelFrame {
    Canonicalization canonical;
    bool by_travel = false;  ///< false: fell back to the first frame's heading
    double travel_cm = 0.0;  ///< the root's horizontal displacement the direction was taken from
};

TravelFrame travel_canonicalization(const Clip& sample, const TravelFrameOptions& options = {});

}  // namespace mocapdb
