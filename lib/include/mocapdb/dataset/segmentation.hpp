#pragma once
// Cutting long clips into many comparable samples.
#include <vector>

#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct GaitCycleOptions {
    FootContactOptions contacts;  ///< the first foot listed defines the cycle
    double min_seconds = 0.6;     ///< cycles shorter or longer than this are skipped
    double max_seconds = 2.0;
};

/// Gait cycles: from one touch-down of the first foot (contact begins) to its next touch-down.
/// Returns [begin, end) frame ranges of the clip (end = the next touch-down frame + 1, so
/// consecutive cycles share their boundary frame).
std::vector<SampleRef> gait_cycles(const Clip& clip, const std::string& clip_id, const GaitCycleOptions& options = {});

/// Fixed windows of `length` frames every `hop` frames (the last partial window is dropped).
std::vector<SampleRef> fixed_windows(const Clip& clip, const std::string& clip_id, std::size_t length, std::size_t hop);

}  // namespace mocapdb
