#pragma once
// Foot skating: how far the feet slide horizontally while they are detected as planted.
//
// Contacts come from dataset::foot_contacts (height within tolerance of the foot's floor level AND
// horizontal speed below the speed tolerance). For each foot, the horizontal (x, z) travel
// sum_f |p(f+1) - p(f)|_xz over the frame pairs where the foot is in contact in both frames is the
// skating; divided by the contact time it is a sliding speed. Because the speed test already bounds
// the per-frame travel, this measures slow sliding within contacts, not gross errors (a foot sliding
// faster than the tolerance is simply not a contact; `contact_fraction` shows that).
#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb::eval {

struct FootSkating {
    double travel_cm = 0.0;         ///< horizontal foot travel during contacts, summed over feet
    double contact_seconds = 0.0;   ///< contact time summed over feet (frame pairs / frame rate)
    double cm_per_s = 0.0;          ///< travel_cm / contact_seconds (0 without contact)
    double contact_fraction = 0.0;  ///< frames in contact / (feet x frames)
};

/// Throws InvalidArgument when the feet are not found or the clip has fewer than 2 frames.
FootSkating foot_skating(const Clip& clip, const FootContactOptions& options = {});

}  // namespace mocapdb::eval
