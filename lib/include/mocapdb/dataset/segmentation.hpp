#pragma once
// Cutting long clips into many comparable samples.
#include <vector>

#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct GaitCycleOptions {
    std::vector<std::string> feet;  ///< {left, right}; empty: default_feet(skeleton)
    double min_seconds = 0.3;       ///< cycles shorter or longer than this are skipped (runs: ~0.5-0.8 s,
    double max_seconds = 2.5;       ///< walks: ~1-1.3 s, slow walks longer)
    /// At most this many cycles per clip, evenly spread over its cycles (1: the middle one); 0: all.
    std::size_t max_per_clip = 0;
};

/// Gait cycles: from one forward pass of the left foot past the right (gait_phase.hpp) to the next,
/// so every cycle starts and ends at the same phase. Returns [begin, end) frame ranges of the clip
/// (end = the next pass frame + 1, so consecutive cycles share their boundary frame). Cycles outside
/// [min_seconds, max_seconds], or longer than 1.5x / shorter than 1/1.5 of the clip's median cycle
/// (a missed or spurious pass), are skipped. None when the feet do not alternate (gait_phase.hpp).
/// InvalidArgument when the feet are not found.
std::vector<SampleRef> gait_cycles(const Clip& clip, const std::string& clip_id, const GaitCycleOptions& options = {});

struct FlightWindowOptions {
    FootContactOptions contacts;
    double before_seconds = 0.5;  ///< kept before take-off (the crouch and push-off)
    double after_seconds = 0.5;   ///< kept after landing (the absorption)
};

/// The jump of a clip as one sample (phase-consistent samples): from before_seconds before
/// the take-off of its longest flight (foot_contacts.hpp: longest_flight) to after_seconds after the
/// landing, clipped to the clip. Whole clips of jumps hold different amounts of standing before and
/// after, which a both-ends-pinned alignment then mixes with the jump itself. None when the clip has no
/// flight. InvalidArgument for margins outside [0, 3600] s or feet not found.
std::vector<SampleRef> flight_window(const Clip& clip, const std::string& clip_id,
                                     const FlightWindowOptions& options = {});

/// `keep` of `all`, evenly spread (first and last included; keep = 1: the middle one); all when
/// keep = 0 or keep >= all.size().
std::vector<SampleRef> spread_evenly(const std::vector<SampleRef>& all, std::size_t keep);

/// Fixed windows of `length` frames every `hop` frames (the last partial window is dropped).
std::vector<SampleRef> fixed_windows(const Clip& clip, const std::string& clip_id, std::size_t length, std::size_t hop);

}  // namespace mocapdb
