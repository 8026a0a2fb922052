#pragma once
// The JSON of `mocapdb serve`'s API (docs/serve.md): the clip and set lists, the headers of the binary
// motion replies (rig, frames, errors), a synthesis, a reliability slice and an error. Formatting only;
// each function writes one whole object into an empty JsonWriter.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/clip_view.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

void write_clip_list(JsonWriter& j, const std::string& db, const std::vector<ClipRecord>& clips,
                     const std::optional<PackedTierRecord>& packed);
void write_clip_positions(JsonWriter& j, const std::string& clip, const workflow::ClipPositions& p);
void write_packed_comparison(JsonWriter& j, const std::string& clip, const workflow::PackedComparison& c);

/// A set as the set explorer needs it: parameters with the samples' range, every sample's values.
struct SetView {
    MotionSet set;
    bool aligned = false;
    bool model = false;  ///< a compressed model is stored (else synthesis uses the naive model)
};
void write_set_views(JsonWriter& j, const std::vector<SetView>& sets);

struct SynthesisView {
    std::string set;
    std::vector<std::string> names, units;
    workflow::SynthOutcome outcome;
    bool inside = true;  ///< c within the samples' bounding box
    workflow::SynthesisWarnings warnings;
    std::string model;  ///< the model's kind
};
/// With the positions of the synthesized clip (frames and rig), shown by the viewer.
void write_synthesis_view(JsonWriter& j, const SynthesisView& s, const workflow::ClipPositions& p);

void write_reliability_slice(JsonWriter& j, const std::string& set, const std::vector<std::string>& names,
                             const workflow::SliceAxis& x, const workflow::SliceAxis& y,
                             const workflow::ReliabilityMap& map);

void write_error(JsonWriter& j, const std::string& message);

}  // namespace mocapdb::json
