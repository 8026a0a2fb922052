#pragma once
// The documents of what a database holds: `mocapdb info DB.h5 --json` (clips, skeletons, sets, the
// packed tier), `set list --json` and `set show NAME --json`. Formatting only; no I/O.
// Keys: docs/json.md.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/database_summary.hpp"
#include "mocapdb/synthesis/edge_warning.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

void write_database_info(JsonWriter& j, const std::string& file, const workflow::DatabaseSummary& d);
/// An array: [{name, samples, parameters, aligned, model, model_ranks}].
void write_set_list(JsonWriter& j, const std::vector<SetRecord>& sets);
/// `labels`: per sample, "CLIP" or "CLIP:BEGIN-END"; `aligned`: the set's aligned form, if stored;
/// `predictor` and `edge_warning`: the synthesis predictor and warning threshold stored with its model
/// (null when none).
void write_set_show(JsonWriter& j, const MotionSet& set, const std::vector<std::string>& labels,
                    const std::optional<AlignedSet>& aligned,
                    const std::optional<synthesis::PredictorChoice>& predictor = std::nullopt,
                    const std::optional<synthesis::EdgeWarning>& edge_warning = std::nullopt);

}  // namespace mocapdb::json
