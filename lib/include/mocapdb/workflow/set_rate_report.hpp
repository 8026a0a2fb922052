#pragma once
// The rate–distortion table of an aligned set as a library step (`mocapdb report --set`
// and the demo): compression::rate_distortion on the set's tensor with the set's parameters charged as
// side information, plus the size of the source motion the rows are compared against. Nothing is
// printed and nothing is stored; the text, CSV, JSON and SVG renderings are the callers'.
// Errors: InvalidArgument on bad targets (rate_distortion.hpp). Threads: reads `data` only.
#include <cstdint>

#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"

namespace mocapdb::workflow {

struct RateOutcome {
    compression::RateReport report;
    std::uint64_t clip_bytes = 0;  ///< the samples' source channels as float32
    double seconds = 0.0;          ///< seconds of motion of the samples (source timing)
    std::size_t joints = 0;        ///< joints with rotations
};

/// The report's rows on the set (options.parameters is set from the set; options.progress per row).
RateOutcome rate_report(const AlignedSetData& data, compression::RateOptions options);

}  // namespace mocapdb::workflow
