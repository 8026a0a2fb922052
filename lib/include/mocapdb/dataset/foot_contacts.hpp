#pragma once
// Foot contacts from joint heights and speeds, and the root trajectory quantities the parameter
// extractors and segmentation share.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/root_trajectory.hpp"  // root_positions, root_headings (used with the contacts)

namespace mocapdb {

struct FootContactOptions {
    /// Foot joints (e.g. {"ltoes", "rtoes"}); empty: default_feet(skeleton).
    std::vector<std::string> feet;
    /// A foot touches the floor when it is within this height above its floor level ...
    double height_tolerance_cm = 5.0;
    /// ... and moves horizontally slower than this.
    double speed_tolerance_cm_s = 40.0;
};

/// Left then right foot joint names: the first joints (not end sites) whose names contain "toe"
/// (else "foot", case-insensitive) and name a side: a word "L"/"Left"/"Left..." of the name (words split
/// at punctuation and camelCase: "Toes_L", "mixamorig:LeftToeBase", "foot.r") or a name that starts
/// with the side (CMU's "ltoes"). InvalidArgument when none are found (callers may pass the names).
std::vector<std::string> default_feet(const Skeleton& skeleton);

/// Contact flags: feet by frames (1 = in contact). The floor level of each foot is the 5th
/// percentile of its height over the clip, so a few glitchy frames do not move it.
Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> foot_contacts(const Clip& clip, const FootContactOptions& options);

/// A flight: frames takeoff + 1 .. landing - 1 have no foot in contact; takeoff and landing do.
struct Flight {
    Eigen::Index takeoff = -1;  ///< last frame in contact before the flight
    Eigen::Index landing = -1;  ///< first frame in contact after it
};

/// The longest flight of `contacts` (feet by frames, foot_contacts) bounded by contact on both sides
/// (the first of equally long ones); nullopt when there is none (no jump, or the clip starts or ends
/// in the air).
std::optional<Flight> longest_flight(const Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>& contacts);

}  // namespace mocapdb
