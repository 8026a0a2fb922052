#pragma once
// report.json of `mocapdb demo`: every number the demo prints, stage by stage (import, set,
// alignment, compression, the rate-distortion rows, each synthesis, the reliability map, timings).
// The demo fills a DemoReport as it runs. Formatting only; no I/O. Keys: docs/json.md.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/workflow/clip_import.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "mocapdb/workflow/set_alignment.hpp"
#include "mocapdb/workflow/set_compression.hpp"
#include "mocapdb/workflow/set_creation.hpp"
#include "mocapdb/workflow/set_rate_report.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

/// One synthesis of the demo: where it was asked, what came back.
struct DemoSynthesis {
    std::string file;    ///< the BVH file's name in the output folder
    std::string where;   ///< "between samples" / "outside the samples" / "requested"
    bool inside = true;  ///< within the samples' bounding box
    workflow::SynthOutcome outcome;
    VecX measured;  ///< by the set's extractors or the reach target measurement; empty: not measured
};

struct DemoSyntheses {
    std::string model;  ///< the model's kind()
    double precompute_s = 0.0;
    double load_s = 0.0;
    std::string measured_with;  ///< what measured the results
    kriging::VariogramModel variogram;
    std::vector<DemoSynthesis> motions;
};

/// The reliability map over the first two parameters (reliability.svg).
struct DemoMap {
    std::string x, y;  ///< the parameters' names
    double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;
    workflow::ReliabilityMap map;
};

struct DemoReport {
    std::string mode;  ///< "procedural-reach", "procedural-walk" or "data"
    std::string out;   ///< the output folder
    std::string database;
    std::string set_name;
    double generate_s = 0.0;
    workflow::ImportOutcome imported;
    workflow::SetOutcome set;
    workflow::AlignOutcome aligned;
    workflow::CompressOutcome compressed;
    workflow::RateOutcome rate;
    double rate_s = 0.0;
    DemoSyntheses synthesis;
    std::optional<DemoMap> map;  ///< none for a set of one parameter
    double total_s = 0.0;
};

void write_demo_report(JsonWriter& j, const DemoReport& r);

}  // namespace mocapdb::json
