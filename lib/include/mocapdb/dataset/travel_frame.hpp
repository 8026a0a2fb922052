#pragma once
// Canonicalizing a sample by its initial direction of travel instead of its first frame's pelvis yaw.
//
// Details: docs/headers/dataset.md (mocapdb/dataset/travel_frame.hpp).
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb {

struct TravelFrameOptions {
    double distance_cm = 75.0;    ///< displacement whose direction defines the frame
    double min_travel_cm = 20.0;  ///< below this displacement the first frame's heading is used
};

struct TravelFrame {
    Canonicalization canonical;
    bool by_travel = false;  ///< false: fell back to the first frame's heading
    double travel_cm = 0.0;  ///< the root's horizontal displacement the direction was taken from
};

TravelFrame travel_canonicalization(const Clip& sample, const TravelFrameOptions& options = {});

}  // namespace mocapdb
